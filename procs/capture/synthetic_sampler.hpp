#pragma once
// Mip-mapped texture sampling for the synthetic renderer, inline because it runs once per pixel.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include <opencv2/core.hpp>

#if defined(__SSE2__)
#include <emmintrin.h>
#include <xmmintrin.h>
#endif

namespace bmp::capture::synth {

// Where a sample reads: one or two pyramid levels with coordinates and weights. Rendering locates and
// prefetches the samples of a whole row before it samples them: texture reads are scattered over
// megabytes, and waiting for memory would otherwise dominate the frame time.
struct TexelLookup;

class SurfaceTexture {
 public:
  SurfaceTexture() = default;
  // level0: CV_8UC3 texture; the pyramid is built here.
  SurfaceTexture(const cv::Mat& level0, double texels_per_metre);

  // The lookup for (u, v) metres and a pixel covering `footprint` metres of the surface: trilinear between
  // the two mip levels that bracket the footprint.
  TexelLookup locate(float u, float v, float footprint) const;

  struct Level {
    cv::Mat image;  // CV_8UC4: BGR plus a padding byte, so a texel pair is one 8-byte load
    const uint8_t* data = nullptr;
    std::size_t step = 0;
    float max_x = 0;  // largest coordinate a bilinear sample may start from
    float max_y = 0;
    float scale = 1.0f;  // level coordinates per level-0 coordinate
  };

 private:
  std::vector<Level> levels_;
  float texels_per_metre_ = 1.0f;
};

struct TexelLookup {
  const SurfaceTexture::Level* a = nullptr;
  const SurfaceTexture::Level* b = nullptr;  // null when one level suffices
  float xa = 0, ya = 0, xb = 0, yb = 0;
  float wa = 1, wb = 0;
};

namespace detail {

#if defined(__SSE2__)
using Acc = __m128;
inline Acc zeroAcc() {
  return _mm_setzero_ps();
}
#else
struct Acc {
  float v[4];
};
inline Acc zeroAcc() {
  return Acc{{0, 0, 0, 0}};
}
#endif

// Bilinear sample at texel-centre coordinates (x, y), clamped to the image, added to acc with weight w.
// The SSE2 path (every x86-64 CPU) does the four channels at once.
// First texel of the 2 x 2 block a bilinear sample at (x, y) reads (coordinates clamped in place).
inline const uint8_t* texelRow(const SurfaceTexture::Level& level, float& x, float& y) {
  x = std::min(std::max(x, 0.0f), level.max_x);
  y = std::min(std::max(y, 0.0f), level.max_y);
  return level.data + level.step * static_cast<std::size_t>(y) + 4 * static_cast<int>(x);
}

inline void bilinear(const SurfaceTexture::Level& level, float x, float y, float w, Acc& acc) {
  const uint8_t* r0 = texelRow(level, x, y);
  const int x0 = static_cast<int>(x), y0 = static_cast<int>(y);
  const float ax = x - static_cast<float>(x0), ay = y - static_cast<float>(y0);
  const uint8_t* r1 = r0 + level.step;
  const float w00 = w * (1 - ax) * (1 - ay), w01 = w * ax * (1 - ay);
  const float w10 = w * (1 - ax) * ay, w11 = w * ax * ay;
#if defined(__SSE2__)
  const __m128i zero = _mm_setzero_si128();
  const __m128i top = _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r0)), zero);
  const __m128i bottom = _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(r1)), zero);
  const __m128 t00 = _mm_cvtepi32_ps(_mm_unpacklo_epi16(top, zero));
  const __m128 t01 = _mm_cvtepi32_ps(_mm_unpackhi_epi16(top, zero));
  const __m128 t10 = _mm_cvtepi32_ps(_mm_unpacklo_epi16(bottom, zero));
  const __m128 t11 = _mm_cvtepi32_ps(_mm_unpackhi_epi16(bottom, zero));
  const __m128 upper = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(w00), t00), _mm_mul_ps(_mm_set1_ps(w01), t01));
  const __m128 lower = _mm_add_ps(_mm_mul_ps(_mm_set1_ps(w10), t10), _mm_mul_ps(_mm_set1_ps(w11), t11));
  acc = _mm_add_ps(acc, _mm_add_ps(upper, lower));
#else
  for (int c = 0; c < 4; ++c) acc.v[c] += (w00 * r0[c] + w01 * r0[c + 4]) + (w10 * r1[c] + w11 * r1[c + 4]);
#endif
}

// log2 for x >= 1, linear between powers of two: continuous and monotonic, which is all that mip blending
// needs, and far cheaper than std::log2.
inline float approxLog2(float x) {
  uint32_t bits = 0;
  std::memcpy(&bits, &x, sizeof bits);
  const int exponent = static_cast<int>((bits >> 23) & 0xFF) - 127;
  bits = (bits & 0x007FFFFFu) | 0x3F800000u;
  float mantissa = 0.0f;
  std::memcpy(&mantissa, &bits, sizeof mantissa);
  return static_cast<float>(exponent) + (mantissa - 1.0f);
}

}  // namespace detail

inline TexelLookup SurfaceTexture::locate(float u, float v, float footprint) const {
  TexelLookup q;
  // pyrDown keeps texel 2i of a level as texel i of the next: coordinates halve about texel centre 0.
  const float x0 = u * texels_per_metre_ - 0.5f;
  const float y0 = v * texels_per_metre_ - 0.5f;
  const float texels = footprint * texels_per_metre_;
  const int last = static_cast<int>(levels_.size()) - 1;
  if (texels <= 1.0f) {
    q.a = &levels_[0], q.xa = x0, q.ya = y0;
    return q;
  }
  const float lod = std::min(detail::approxLog2(texels), static_cast<float>(last));
  const int l = std::min(static_cast<int>(lod), last);
  const float frac = lod - static_cast<float>(l);
  q.a = &levels_[l], q.xa = x0 * q.a->scale, q.ya = y0 * q.a->scale, q.wa = 1.0f - frac;
  if (frac > 0.0f) q.b = &levels_[l + 1], q.xb = x0 * q.b->scale, q.yb = y0 * q.b->scale, q.wb = frac;
  return q;
}

inline void prefetch(const TexelLookup& q) {
#if defined(__SSE2__)
  const auto touch = [](const SurfaceTexture::Level& level, float x, float y) {
    const auto* r0 = reinterpret_cast<const char*>(detail::texelRow(level, x, y));
    _mm_prefetch(r0, _MM_HINT_T0);
    _mm_prefetch(r0 + level.step, _MM_HINT_T0);
  };
  touch(*q.a, q.xa, q.ya);
  if (q.b) touch(*q.b, q.xb, q.yb);
#else
  (void)q;
#endif
}

// Colour (B, G, R in 0..255).
inline void sample(const TexelLookup& q, float out[3]) {
  detail::Acc acc = detail::zeroAcc();
  detail::bilinear(*q.a, q.xa, q.ya, q.wa, acc);
  if (q.b) detail::bilinear(*q.b, q.xb, q.yb, q.wb, acc);
#if defined(__SSE2__)
  alignas(16) float lanes[4];
  _mm_store_ps(lanes, acc);
  out[0] = lanes[0], out[1] = lanes[1], out[2] = lanes[2];
#else
  out[0] = acc.v[0], out[1] = acc.v[1], out[2] = acc.v[2];
#endif
}

}  // namespace bmp::capture::synth
