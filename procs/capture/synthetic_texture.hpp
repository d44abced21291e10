#pragma once
// Procedural textures for the synthetic scene: seeded random shapes at several scales drawn with OpenCV,
// stored as a mip pyramid and sampled trilinearly in world units, so the rendered images carry dense,
// non-repetitive corners without aliasing (sampling: synthetic_sampler.hpp).
#include <cmath>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace bmp::capture::synth {

constexpr double kPi = 3.14159265358979323846;

// SplitMix64: the same numbers on every platform and standard library (std distributions are not).
class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int integer(int lo, int hi) { return lo + static_cast<int>(next() % static_cast<uint64_t>(hi - lo + 1)); }
  double normal() {
    const double u1 = 1.0 - uniform();  // (0, 1]: log stays finite
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * kPi * uniform());
  }

 private:
  uint64_t state_;
};

// Independent stream seeds for (seed, purpose, index).
uint64_t mixSeed(uint64_t seed, uint64_t a, uint64_t b = 0);

struct TextureStyle {
  double texels_per_metre = 200.0;
  double shapes_per_square_metre = 110.0;
  double brightness = 1.0;  // baked-in shading of the face, view independent
};

// A BGR texture of the given size in metres (CV_8UC3), slightly blurred so level 0 does not alias.
cv::Mat drawTexture(double width_m, double height_m, const TextureStyle& style, uint64_t seed);

// Rows x cols of unit-variance normal samples (CV_32FC1).
cv::Mat unitNoiseTile(int rows, int cols, uint64_t seed);

}  // namespace bmp::capture::synth
