#include "tracker/orb_extractor.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include <opencv2/imgproc.hpp>

#include "tracker/cell_corners.hpp"

namespace bmp::tracker {

namespace {
constexpr int kPatchRadius = 15;    // orientation patch
constexpr int kPatternRadius = 13;  // test pairs stay inside this circle under any rotation
constexpr int kBorder = 19;         // corners nearer the edge cannot be described
constexpr double kPatchSize = 31.0;
constexpr int kPatternPoints = 512;  // 256 tests, 2 points each
constexpr int kMomentLanes = 32;     // u = -15..16 per patch row (16: weight 0; kBorder keeps it inside)

// Uniform in [0, 1) from the raw generator: std distributions differ between standard libraries.
double uniform01(std::mt19937& rng) {
  return (static_cast<double>(rng()) + 0.5) / 4294967296.0;
}
}  // namespace

ScalePyramid::ScalePyramid(int n, double f)
    : levels(n), factor(f), log_factor(std::log(f)), scale(n), sigma2(n), inv_sigma2(n) {
  for (int i = 0; i < n; ++i) {
    scale[i] = std::pow(f, i);
    sigma2[i] = scale[i] * scale[i];
    inv_sigma2[i] = 1.0 / sigma2[i];
  }
}

OrbExtractor::OrbExtractor(const OrbOptions& options)
    : options_(options), pyramid_(options.num_levels, options.scale_factor) {
  // Geometric share per level, as the image area shrinks by factor^2 and the scale by factor.
  const double inv = 1.0 / options.scale_factor;
  double n = options.num_features * (1.0 - inv) / (1.0 - std::pow(inv, options.num_levels));
  int total = 0;
  for (int l = 0; l + 1 < options.num_levels; ++l) {
    per_level_.push_back(static_cast<int>(std::lround(n)));
    total += per_level_.back();
    n *= inv;
  }
  per_level_.push_back(std::max(0, options.num_features - total));

  for (int v = 0; v <= kPatchRadius; ++v)
    circle_half_width_.push_back(
        static_cast<int>(std::floor(std::sqrt(kPatchRadius * kPatchRadius - v * v) + 0.5)));
  for (int v = 0; v <= kPatchRadius; ++v)
    for (int lane = 0; lane < kMomentLanes; ++lane) {
      const int u = lane - kPatchRadius;
      const bool in = std::abs(u) <= circle_half_width_[v];
      moment_u_.push_back(static_cast<int16_t>(in ? u : 0));
      moment_v_.push_back(static_cast<int16_t>(in ? v : 0));
    }

  // BRIEF's isotropic Gaussian sampling (sigma = patch/5), restricted to the rotation-safe circle.
  std::mt19937 rng(20261122u);
  const double sigma = kPatchSize / 5.0;
  while (static_cast<int>(pattern_x_.size()) < kPatternPoints) {
    const double r = std::sqrt(-2.0 * std::log(uniform01(rng)));
    const double a = 2.0 * M_PI * uniform01(rng);
    const cv::Point2f p(static_cast<float>(std::round(sigma * r * std::cos(a))),
                        static_cast<float>(std::round(sigma * r * std::sin(a))));
    if (p.x * p.x + p.y * p.y > kPatternRadius * kPatternRadius) continue;
    pattern_x_.push_back(p.x);
    pattern_y_.push_back(p.y);
  }
}

void OrbExtractor::detectLevel(const cv::Mat& image, int target, const SparseRegions& sparse,
                               std::vector<cv::KeyPoint>& out) const {
  std::vector<cv::KeyPoint> kept =
      cellCorners(image, {kBorder, options_.cell_size, options_.fast_threshold, options_.fast_min_threshold});
  const int w = image.cols, h = image.rows;
  if (static_cast<int>(kept.size()) <= target) {
    out = std::move(kept);
    return;
  }
  // Buckets sized so that there are about as many buckets as wanted features.
  const double area = static_cast<double>(w - 2 * kBorder) * (h - 2 * kBorder);
  const double side = std::max(4.0, std::sqrt(area / target));
  const int bcols = std::max(1, static_cast<int>(std::ceil((w - 2 * kBorder) / side)));
  const int brows = std::max(1, static_cast<int>(std::ceil((h - 2 * kBorder) / side)));
  std::vector<std::vector<int>> buckets(static_cast<std::size_t>(bcols * brows));
  for (int i = 0; i < static_cast<int>(kept.size()); ++i) {
    const int bx = std::min(bcols - 1, static_cast<int>((kept[i].pt.x - kBorder) / side));
    const int by = std::min(brows - 1, static_cast<int>((kept[i].pt.y - kBorder) / side));
    buckets[by * bcols + bx].push_back(i);
  }
  for (auto& b : buckets)
    std::sort(b.begin(), b.end(), [&](int a, int c) { return kept[a].response > kept[c].response; });
  out.clear();
  if (sparse.boxes.empty() || sparse.share >= 1.0) {
    std::vector<int> all(buckets.size());
    for (std::size_t b = 0; b < buckets.size(); ++b) all[b] = static_cast<int>(b);
    spread(kept, buckets, all, target, false, out);
    return;
  }
  // Buckets whose centre lies in a sparse box count `share` of their area; each group gets its part of
  // the target and is spread on its own (its last, partial round by response, not by position).
  std::vector<int> dense_buckets, sparse_buckets;
  for (int by = 0; by < brows; ++by)
    for (int bx = 0; bx < bcols; ++bx) {
      const cv::Point2f centre(static_cast<float>(kBorder + (bx + 0.5) * side),
                               static_cast<float>(kBorder + (by + 0.5) * side));
      bool in = false;
      for (const cv::Rect2f& r : sparse.boxes) in = in || r.contains(centre);
      (in ? sparse_buckets : dense_buckets).push_back(by * bcols + bx);
    }
  const double weight_dense = static_cast<double>(dense_buckets.size());
  const double weight_sparse = static_cast<double>(sparse_buckets.size()) * sparse.share;
  const int target_sparse =
      static_cast<int>(std::lround(target * weight_sparse / std::max(1e-9, weight_dense + weight_sparse)));
  spread(kept, buckets, dense_buckets, target - target_sparse, true, out);
  // What the static scene could not use goes back to the boxes.
  spread(kept, buckets, sparse_buckets, target - static_cast<int>(out.size()), true, out);
}

void OrbExtractor::spread(const std::vector<cv::KeyPoint>& kept, const std::vector<std::vector<int>>& buckets,
                          const std::vector<int>& which, int target, bool strongest_last_round,
                          std::vector<cv::KeyPoint>& out) {
  // Round k takes the k-th strongest keypoint of every bucket.
  const std::size_t goal = out.size() + static_cast<std::size_t>(std::max(0, target));
  for (std::size_t rank = 0; out.size() < goal; ++rank) {
    std::vector<int> round;
    for (const int b : which)
      if (rank < buckets[b].size()) round.push_back(buckets[b][rank]);
    if (round.empty()) break;
    if (strongest_last_round && out.size() + round.size() > goal)
      std::sort(round.begin(), round.end(),
                [&](int a, int c) { return kept[a].response > kept[c].response; });
    for (const int i : round) {
      if (out.size() >= goal) break;
      out.push_back(kept[i]);
    }
  }
}

float OrbExtractor::orientation(const cv::Mat& image, const cv::Point2f& pt) const {
  const int step = static_cast<int>(image.step1());
  const uint8_t* center = image.ptr<uint8_t>(cvRound(pt.y)) + cvRound(pt.x);
  int m01 = 0, m10 = 0;
#ifdef __SSE2__
  // Row v and row -v together: m10 += u (below + above), m01 += v (below - above), as multiply-adds of 16-bit
  // lanes against the circle's weights (0 outside it). Integer sums: the same moments as the loop below.
  const __m128i zero = _mm_setzero_si128();
  __m128i acc10 = zero, acc01 = zero;
  for (int v = 0; v <= kPatchRadius; ++v) {
    const uint8_t* below = center + v * step - kPatchRadius;
    const uint8_t* above = center - v * step - kPatchRadius;
    const __m128i* wu = reinterpret_cast<const __m128i*>(&moment_u_[v * kMomentLanes]);
    const __m128i* wv = reinterpret_cast<const __m128i*>(&moment_v_[v * kMomentLanes]);
    for (int half = 0; half < 2; ++half) {
      const __m128i b = _mm_loadu_si128(reinterpret_cast<const __m128i*>(below + 16 * half));
      const __m128i b_lo = _mm_unpacklo_epi8(b, zero), b_hi = _mm_unpackhi_epi8(b, zero);
      const __m128i u_lo = _mm_loadu_si128(wu + 2 * half), u_hi = _mm_loadu_si128(wu + 2 * half + 1);
      if (v == 0) {  // the centre row counts once
        acc10 = _mm_add_epi32(acc10, _mm_add_epi32(_mm_madd_epi16(b_lo, u_lo), _mm_madd_epi16(b_hi, u_hi)));
        continue;
      }
      const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(above + 16 * half));
      const __m128i a_lo = _mm_unpacklo_epi8(a, zero), a_hi = _mm_unpackhi_epi8(a, zero);
      const __m128i v_lo = _mm_loadu_si128(wv + 2 * half), v_hi = _mm_loadu_si128(wv + 2 * half + 1);
      acc10 = _mm_add_epi32(acc10, _mm_madd_epi16(_mm_add_epi16(b_lo, a_lo), u_lo));
      acc10 = _mm_add_epi32(acc10, _mm_madd_epi16(_mm_add_epi16(b_hi, a_hi), u_hi));
      acc01 = _mm_add_epi32(acc01, _mm_madd_epi16(_mm_sub_epi16(b_lo, a_lo), v_lo));
      acc01 = _mm_add_epi32(acc01, _mm_madd_epi16(_mm_sub_epi16(b_hi, a_hi), v_hi));
    }
  }
  alignas(16) int32_t sum10[4], sum01[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(sum10), acc10);
  _mm_store_si128(reinterpret_cast<__m128i*>(sum01), acc01);
  m10 = sum10[0] + sum10[1] + sum10[2] + sum10[3];
  m01 = sum01[0] + sum01[1] + sum01[2] + sum01[3];
#else
  for (int u = -kPatchRadius; u <= kPatchRadius; ++u) m10 += u * center[u];
  for (int v = 1; v <= kPatchRadius; ++v) {
    int row_sum = 0;
    const int d = circle_half_width_[v];
    for (int u = -d; u <= d; ++u) {
      const int below = center[u + v * step], above = center[u - v * step];
      row_sum += below - above;
      m10 += u * (below + above);
    }
    m01 += v * row_sum;
  }
#endif
  return static_cast<float>(cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10)));
}

void OrbExtractor::describe(const cv::Mat& blurred, const cv::KeyPoint& kp, uint8_t* out) const {
  const float a = kp.angle * static_cast<float>(M_PI / 180.0);
  const float c = std::cos(a), s = std::sin(a);
  const int step = static_cast<int>(blurred.step1());
  const uint8_t* center = blurred.ptr<uint8_t>(cvRound(kp.pt.y)) + cvRound(kp.pt.x);
  // Rotated pattern as pixel offsets first, rounded half to even as cvRound does.
  int offset[kPatternPoints];
  int k = 0;
#ifdef __SSE2__
  // Four at a time; the same float operations in the same order as below, so the same offsets. Row times
  // step in float is exact (|row| <= 13, step < 2^20).
  if (step < (1 << 20)) {
    const __m128 vs = _mm_set1_ps(s), vc = _mm_set1_ps(c), vstep = _mm_set1_ps(static_cast<float>(step));
    for (; k + 4 <= kPatternPoints; k += 4) {
      const __m128 x = _mm_loadu_ps(&pattern_x_[k]), y = _mm_loadu_ps(&pattern_y_[k]);
      const __m128i row = _mm_cvtps_epi32(_mm_add_ps(_mm_mul_ps(x, vs), _mm_mul_ps(y, vc)));
      const __m128i col = _mm_cvtps_epi32(_mm_sub_ps(_mm_mul_ps(x, vc), _mm_mul_ps(y, vs)));
      const __m128 o = _mm_add_ps(_mm_mul_ps(_mm_cvtepi32_ps(row), vstep), _mm_cvtepi32_ps(col));
      _mm_storeu_si128(reinterpret_cast<__m128i*>(offset + k), _mm_cvtps_epi32(o));
    }
  }
#endif
  for (; k < kPatternPoints; ++k) {
    const float x = pattern_x_[k], y = pattern_y_[k];
    offset[k] = cvRound(x * s + y * c) * step + cvRound(x * c - y * s);
  }
  for (int byte = 0; byte < kDescriptorBytes; ++byte) {
    uint8_t bits = 0;
    const int* o = offset + 16 * byte;
    for (int bit = 0; bit < 8; ++bit)
      bits |= static_cast<uint8_t>((center[o[2 * bit]] < center[o[2 * bit + 1]]) << bit);
    out[byte] = bits;
  }
}

OrbFeatures OrbExtractor::extract(const cv::Mat& gray, const SparseRegions& sparse) const {
  CV_Assert(gray.type() == CV_8UC1);
  OrbFeatures result;
  std::vector<cv::Mat> descriptor_blocks;
  cv::Mat level_image = gray;
  for (int level = 0; level < pyramid_.levels; ++level) {
    if (level > 0) {
      const cv::Size size(static_cast<int>(std::lround(gray.cols / pyramid_.scale[level])),
                          static_cast<int>(std::lround(gray.rows / pyramid_.scale[level])));
      if (size.width <= 2 * kBorder || size.height <= 2 * kBorder) break;
      cv::Mat next;
      cv::resize(level_image, next, size, 0, 0, cv::INTER_LINEAR);
      level_image = next;
    }
    SparseRegions level_sparse{{}, sparse.share};
    const float inv = static_cast<float>(1.0 / pyramid_.scale[level]);
    for (const cv::Rect2f& r : sparse.boxes)
      level_sparse.boxes.emplace_back(r.x * inv, r.y * inv, r.width * inv, r.height * inv);
    std::vector<cv::KeyPoint> keys;
    detectLevel(level_image, per_level_[level], level_sparse, keys);
    if (keys.empty()) continue;
    cv::Mat blurred;
    cv::GaussianBlur(level_image, blurred, cv::Size(7, 7), 2, 2, cv::BORDER_REFLECT_101);
    cv::Mat desc(static_cast<int>(keys.size()), kDescriptorBytes, CV_8U);
    const float scale = static_cast<float>(pyramid_.scale[level]);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      auto& kp = keys[i];
      kp.angle = orientation(level_image, kp.pt);
      describe(blurred, kp, desc.ptr<uint8_t>(static_cast<int>(i)));
      kp.octave = level;
      kp.size = static_cast<float>(kPatchSize) * scale;
      kp.pt *= scale;
      result.keys.push_back(kp);
    }
    descriptor_blocks.push_back(desc);
  }
  if (!descriptor_blocks.empty()) cv::vconcat(descriptor_blocks, result.descriptors);
  return result;
}

}  // namespace bmp::tracker
