#include "capture/synthetic_texture.hpp"

#include "capture/synthetic_sampler.hpp"

#include <algorithm>
#include <cstring>

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
// Most shapes take the surface's own hue, so that walls, floor and furniture look distinct.
cv::Scalar contrastColour(SplitMix64& rng, double palette_hue) {
  const bool dark = rng.uniform() < 0.5;
  const double v = dark ? rng.uniform(0.05, 0.35) : rng.uniform(0.65, 1.0);
  const double hue =
      rng.uniform() < 0.7 ? std::fmod(palette_hue + rng.uniform(0, 1.2) + 6.0, 6.0) : rng.uniform(0, 6);
  return hsvToBgr(hue, rng.uniform(0.1, 0.8), v);
}

void drawShape(cv::Mat& img, SplitMix64& rng, double size, double palette_hue) {
  const cv::Point2d c(rng.uniform(0, img.cols), rng.uniform(0, img.rows));
  const cv::Scalar colour = contrastColour(rng, palette_hue);
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
  const double palette_hue = rng.uniform(0, 6);
  cv::Mat img(rows, cols, CV_8UC3, hsvToBgr(palette_hue, rng.uniform(0.1, 0.5), rng.uniform(0.4, 0.7)));

  // Soft large-scale blotches, so that flat regions between shapes are not uniform.
  cv::Mat coarse(std::max(2, rows / 50), std::max(2, cols / 50), CV_8UC3);
  for (int y = 0; y < coarse.rows; ++y)
    for (int x = 0; x < coarse.cols; ++x)
      for (int ch = 0; ch < 3; ++ch)
        coarse.at<cv::Vec3b>(y, x)[ch] = static_cast<uint8_t>(rng.integer(40, 215));
  cv::Mat blotches;
  cv::resize(coarse, blotches, img.size(), 0, 0, cv::INTER_CUBIC);
  cv::addWeighted(img, 0.5, blotches, 0.5, 0.0, img);

  // Shapes from 1.5 cm to 30 cm, log-uniform, large first so the fine detail stays on top.
  const int count = static_cast<int>(style.shapes_per_square_metre * width_m * height_m) + 4;
  std::vector<double> sizes(count);
  for (double& s : sizes) s = std::exp(rng.uniform(std::log(0.015), std::log(0.30))) * tpm;
  std::sort(sizes.begin(), sizes.end(), std::greater<>());
  for (double s : sizes) drawShape(img, rng, s, palette_hue);

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
    : texels_per_metre_(static_cast<float>(texels_per_metre)) {
  // Four channels so that a texel is one aligned 32-bit load and the channel loop vectorises.
  cv::Mat image;
  cv::cvtColor(level0, image, cv::COLOR_BGR2BGRA);
  while (true) {
    Level level;
    level.image = image;
    level.data = image.ptr<uint8_t>(0);
    level.step = image.step[0];
    level.max_x = static_cast<float>(image.cols) - 1.001f;
    level.max_y = static_cast<float>(image.rows) - 1.001f;
    level.scale = std::ldexp(1.0f, -static_cast<int>(levels_.size()));
    levels_.push_back(level);
    if (levels_.size() >= 8 || std::min(image.cols, image.rows) < 16) break;
    cv::Mat next;
    cv::pyrDown(image, next);
    image = next;
  }
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
