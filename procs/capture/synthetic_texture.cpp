#include "capture/synthetic_texture.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace bmp::capture::synth {
namespace {

// HSV (h in [0, 6), s and v in [0, 1]) to a BGR scalar.
cv::Scalar hsvToBgr(double h, double s, double v) {
  const int i = static_cast<int>(h) % 6;
  const double f = h - std::floor(h);
  const double p = v * (1 - s), q = v * (1 - s * f), t = v * (1 - s * (1 - f));
  double r = v, g = t, b = p;
  switch (i) {
    case 1:
      r = q, g = v, b = p;
      break;
    case 2:
      r = p, g = v, b = t;
      break;
    case 3:
      r = p, g = q, b = v;
      break;
    case 4:
      r = t, g = p, b = v;
      break;
    case 5:
      r = v, g = p, b = q;
      break;
    default:
      break;
  }
  return cv::Scalar(255 * b, 255 * g, 255 * r);
}

// Dark or bright, so that neighbouring shapes usually differ strongly in intensity (FAST looks at grey).
cv::Scalar contrastColour(SplitMix64& rng) {
  const bool dark = rng.uniform() < 0.5;
  const double v = dark ? rng.uniform(0.05, 0.35) : rng.uniform(0.65, 1.0);
  return hsvToBgr(rng.uniform(0, 6), rng.uniform(0.1, 0.9), v);
}

void drawShape(cv::Mat& img, SplitMix64& rng, double size) {
  const cv::Point2d c(rng.uniform(0, img.cols), rng.uniform(0, img.rows));
  const cv::Scalar colour = contrastColour(rng);
  const double angle = rng.uniform(0, kPi);
  const double aspect = rng.uniform(0.3, 1.0);
  const auto pt = [&](double x, double y) {
    return cv::Point(cvRound(c.x + x * std::cos(angle) - y * std::sin(angle)),
                     cvRound(c.y + x * std::sin(angle) + y * std::cos(angle)));
  };
  const int thickness = std::max(1, cvRound(size * rng.uniform(0.05, 0.15)));
  switch (rng.integer(0, 6)) {
    case 0:  // axis-aligned rectangle: the corners ORB likes best
      cv::rectangle(img, cv::Point(cvRound(c.x), cvRound(c.y)),
                    cv::Point(cvRound(c.x + size), cvRound(c.y + size * aspect)), colour, cv::FILLED);
      break;
    case 1: {  // rotated rectangle
      const std::vector<cv::Point> poly{pt(-size / 2, -size * aspect / 2), pt(size / 2, -size * aspect / 2),
                                        pt(size / 2, size * aspect / 2), pt(-size / 2, size * aspect / 2)};
      cv::fillConvexPoly(img, poly, colour, cv::LINE_AA);
      break;
    }
    case 2:
      cv::circle(img, c, std::max(1, cvRound(size / 2)), colour, cv::FILLED, cv::LINE_AA);
      break;
    case 3:
      cv::circle(img, c, std::max(2, cvRound(size / 2)), colour, thickness, cv::LINE_AA);
      break;
    case 4:
      cv::line(img, pt(-size, 0), pt(size, 0), colour, thickness, cv::LINE_AA);
      break;
    case 5: {
      const std::vector<cv::Point> tri{pt(0, -size / 2), pt(size / 2, size * aspect / 2),
                                       pt(-size / 2, size * aspect / 2)};
      cv::fillConvexPoly(img, tri, colour, cv::LINE_AA);
      break;
    }
    default:
      cv::ellipse(img, c, cv::Size(std::max(1, cvRound(size / 2)), std::max(1, cvRound(size * aspect / 2))),
                  angle * 180 / kPi, 0, 360, colour, cv::FILLED, cv::LINE_AA);
      break;
  }
}

}  // namespace

uint64_t mixSeed(uint64_t seed, uint64_t a, uint64_t b) {
  SplitMix64 rng(seed ^ (a * 0xD1B54A32D192ED03ULL) ^ (b * 0x8CB92BA72F3D8DD7ULL));
  rng.next();
  return rng.next();
}

cv::Mat drawTexture(double width_m, double height_m, const TextureStyle& style, uint64_t seed) {
  SplitMix64 rng(seed);
  const double tpm = style.texels_per_metre;
  const int cols = std::max(16, static_cast<int>(std::ceil(width_m * tpm)) + 2);
  const int rows = std::max(16, static_cast<int>(std::ceil(height_m * tpm)) + 2);
  cv::Mat img(rows, cols, CV_8UC3, hsvToBgr(rng.uniform(0, 6), rng.uniform(0.1, 0.5), rng.uniform(0.4, 0.7)));

  // Soft large-scale blotches, so that flat regions between shapes are not uniform.
  cv::Mat coarse(std::max(2, rows / 50), std::max(2, cols / 50), CV_8UC3);
  for (int y = 0; y < coarse.rows; ++y)
    for (int x = 0; x < coarse.cols; ++x)
      for (int ch = 0; ch < 3; ++ch)
        coarse.at<cv::Vec3b>(y, x)[ch] = static_cast<uint8_t>(rng.integer(40, 215));
  cv::Mat blotches;
  cv::resize(coarse, blotches, img.size(), 0, 0, cv::INTER_CUBIC);
  cv::addWeighted(img, 0.5, blotches, 0.5, 0.0, img);

  // Shapes from 1.5 cm to 45 cm, log-uniform, large first so the fine detail stays on top.
  const int count = static_cast<int>(style.shapes_per_square_metre * width_m * height_m) + 4;
  std::vector<double> sizes(count);
  for (double& s : sizes) s = std::exp(rng.uniform(std::log(0.015), std::log(0.45))) * tpm;
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  for (double s : sizes) drawShape(img, rng, s);

  // Fine grain, then a light blur so that level 0 is band-limited.
  cv::Mat grain(rows, cols, CV_8UC3);
  for (int y = 0; y < rows; ++y) {
    auto* p = grain.ptr<uint8_t>(y);
    for (int x = 0; x < cols * 3; ++x) p[x] = static_cast<uint8_t>(rng.integer(0, 16));
  }
  cv::add(img, grain, img);
  cv::subtract(img, cv::Scalar::all(8), img);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 0.6);
  img.convertTo(img, CV_8UC3, style.brightness);
  return img;
}

SurfaceTexture::SurfaceTexture(const cv::Mat& level0, double texels_per_metre)
    : texels_per_metre_(texels_per_metre) {
  levels_.push_back(level0);
  while (levels_.size() < 8 && std::min(levels_.back().cols, levels_.back().rows) >= 16) {
    cv::Mat next;
    cv::pyrDown(levels_.back(), next);
    levels_.push_back(next);
  }
}

namespace {

// Bilinear sample at texel-centre coordinates (x, y), clamped to the image, accumulated with weight w.
inline void bilinear(const cv::Mat& img, float x, float y, float w, float out[3]) {
  x = std::min(std::max(x, 0.0f), static_cast<float>(img.cols) - 1.001f);
  y = std::min(std::max(y, 0.0f), static_cast<float>(img.rows) - 1.001f);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float ax = x - static_cast<float>(x0), ay = y - static_cast<float>(y0);
  const uint8_t* r0 = img.ptr<uint8_t>(y0) + 3 * x0;
  const uint8_t* r1 = r0 + img.step[0];
  for (int c = 0; c < 3; ++c) {
    const float top = r0[c] + ax * (static_cast<float>(r0[c + 3]) - r0[c]);
    const float bottom = r1[c] + ax * (static_cast<float>(r1[c + 3]) - r1[c]);
    out[c] += w * (top + ay * (bottom - top));
  }
}

}  // namespace

void SurfaceTexture::sample(double u, double v, double footprint, float out[3]) const {
  out[0] = out[1] = out[2] = 0.0f;
  // pyrDown keeps texel 2i of a level as texel i of the next: coordinates halve about texel centre 0.
  const float x0 = static_cast<float>(u * texels_per_metre_ - 0.5);
  const float y0 = static_cast<float>(v * texels_per_metre_ - 0.5);
  const double texels = footprint * texels_per_metre_;
  if (texels <= 1.0) {
    bilinear(levels_[0], x0, y0, 1.0f, out);
    return;
  }
  const double lod = std::min(std::log2(texels), static_cast<double>(levels_.size() - 1));
  const int l = std::min(static_cast<int>(lod), static_cast<int>(levels_.size()) - 1);
  const float frac = static_cast<float>(lod - l);
  const float s0 = std::ldexp(1.0f, -l);
  bilinear(levels_[l], x0 * s0, y0 * s0, 1.0f - frac, out);
  if (frac > 0.0f && l + 1 < static_cast<int>(levels_.size()))
    bilinear(levels_[l + 1], x0 * s0 * 0.5f, y0 * s0 * 0.5f, frac, out);
}

cv::Mat unitNoiseTile(int rows, int cols, uint64_t seed) {
  SplitMix64 rng(seed);
  cv::Mat tile(rows, cols, CV_32FC1);
  for (int y = 0; y < rows; ++y) {
    auto* p = tile.ptr<float>(y);
    for (int x = 0; x < cols; ++x) p[x] = static_cast<float>(rng.normal());
  }
  return tile;
}

}  // namespace bmp::capture::synth
