#include "tracker/trajectory_smoother.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

namespace bmp::tracker {
namespace {

bool known(double std_m) {
  return std::isfinite(std_m) && std_m > 0.0;
}

// Solves M x = b for the symmetric positive definite pentadiagonal M given by its diagonal d, first
// off-diagonal e and second off-diagonal f (LDL^T without fill beyond the band); b has 3 columns.
void solvePentadiagonal(std::vector<double> d, std::vector<double> e, std::vector<double> f,
                        std::vector<Eigen::Vector3d>& b) {
  const std::size_t n = d.size();
  // Factor: L has unit diagonal and sub-diagonals l1 (i, i-1) and l2 (i, i-2); D is d after the loop.
  std::vector<double> l1(n, 0.0), l2(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    if (i >= 2) l2[i] = f[i - 2] / d[i - 2];
    if (i >= 1) {
      const double off = e[i - 1] - (i >= 2 ? l2[i] * d[i - 2] * l1[i - 1] : 0.0);
      l1[i] = off / d[i - 1];
    }
    d[i] -= (i >= 1 ? l1[i] * l1[i] * d[i - 1] : 0.0) + (i >= 2 ? l2[i] * l2[i] * d[i - 2] : 0.0);
  }
  for (std::size_t i = 1; i < n; ++i) {
    b[i] -= l1[i] * b[i - 1];
    if (i >= 2) b[i] -= l2[i] * b[i - 2];
  }
  for (std::size_t i = 0; i < n; ++i) b[i] /= d[i];
  for (std::size_t k = n; k-- > 0;) {
    if (k + 1 < n) b[k] -= l1[k + 1] * b[k + 1];
    if (k + 2 < n) b[k] -= l2[k + 2] * b[k + 2];
  }
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The median std of the stretch's known ones (0 when none is known).
double medianStd(const std::vector<SmootherSample>& s, std::size_t begin, std::size_t end) {
  std::vector<double> stds;
  for (std::size_t i = begin; i < end; ++i)
    if (known(s[i].std_m)) stds.push_back(s[i].std_m);
  return stds.empty() ? 0.0 : median(std::move(stds));
}

// measuredAccelSigma, with the std that stands for a frame whose own is unknown (the stretch's median).
std::optional<double> accelOfStretch(const std::vector<SmootherSample>& s, std::size_t begin, std::size_t end,
                                     double lag_s, double fallback) {
  const std::size_t n = end - begin;
  if (lag_s <= 0.0 || n < 3) return std::nullopt;
  std::vector<double> spacings;
  for (std::size_t i = begin + 1; i < end; ++i) spacings.push_back(s[i].stamp - s[i - 1].stamp);
  const double spacing = median(spacings);
  if (!(spacing > 0.0) || lag_s / spacing > static_cast<double>(n)) return std::nullopt;
  const auto lag = static_cast<std::size_t>(std::max(1.0, std::round(lag_s / spacing)));
  // Too few second differences to take a median of: no measurement (the floor applies).
  constexpr std::size_t kMinDifferences = 10;
  if (n < 2 * lag + kMinDifferences) return std::nullopt;
  auto var = [&](std::size_t i) {
    const double sd = known(s[i].std_m) ? s[i].std_m : fallback;
    return sd * sd;
  };
  std::vector<double> per_axis;  // each second difference's squared acceleration per axis, less its noise
  for (std::size_t i = begin + lag; i + lag < end; ++i) {
    const std::size_t j = i - lag, k = i + lag;
    const double t0 = s[i].stamp - s[j].stamp, t1 = s[k].stamp - s[i].stamp, span = t0 + t1;
    if (!(t0 > 0.0 && t1 > 0.0)) continue;  // not a stretch (stamps repeat or step back): no difference
    const double cj = 2.0 / (t0 * span), ck = 2.0 / (t1 * span), ci = -(cj + ck);
    const Eigen::Vector3d a = cj * s[j].position + ci * s[i].position + ck * s[k].position;
    const double noise = cj * cj * var(j) + ci * ci * var(i) + ck * ck * var(k);
    per_axis.push_back(a.squaredNorm() / 3.0 - noise);
  }
  if (per_axis.empty()) return std::nullopt;
  return std::sqrt(std::max(0.0, median(std::move(per_axis))));
}

void smoothStretch(const std::vector<SmootherSample>& s, std::size_t begin, std::size_t end,
                   const SmootherOptions& options, std::vector<Eigen::Vector3d>& out) {
  const std::size_t n = end - begin;
  if (n < 3) return;
  const double fallback = medianStd(s, begin, end);
  if (fallback <= 0.0) return;
  const double accel_sigma = std::max(
      options.accel_sigma, accelOfStretch(s, begin, end, options.accel_lag_s, fallback).value_or(0.0));

  // Normal equations of sum w_i |p_i - z_i|^2 + sum_k |a_k|^2 / accel_sigma^2, with a_k the acceleration
  // from frames k-1, k, k+1 at their own spacing.
  std::vector<double> d(n), e(n, 0.0), f(n, 0.0);
  std::vector<Eigen::Vector3d> b(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double sd = known(s[begin + i].std_m) ? s[begin + i].std_m : fallback;
    d[i] = 1.0 / (sd * sd);
    b[i] = d[i] * s[begin + i].position;
  }
  const double inv_var = 1.0 / (accel_sigma * accel_sigma);
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const double dt0 = s[begin + k].stamp - s[begin + k - 1].stamp;
    const double dt1 = s[begin + k + 1].stamp - s[begin + k].stamp;
    const double h = 0.5 * (dt0 + dt1);
    const std::array<double, 3> c{1.0 / (dt0 * h), -(1.0 / dt0 + 1.0 / dt1) / h, 1.0 / (dt1 * h)};
    for (int r = 0; r < 3; ++r) {
      d[k - 1 + r] += inv_var * c[r] * c[r];
      if (r < 2) e[k - 1 + r] += inv_var * c[r] * c[r + 1];
    }
    f[k - 1] += inv_var * c[0] * c[2];
  }
  solvePentadiagonal(std::move(d), std::move(e), std::move(f), b);
  for (std::size_t i = 0; i < n; ++i) out[begin + i] = b[i];
}

}  // namespace

std::optional<double> measuredAccelSigma(const std::vector<SmootherSample>& s, std::size_t begin,
                                         std::size_t end, double lag_s) {
  return accelOfStretch(s, begin, end, lag_s, medianStd(s, begin, end));
}

std::vector<Eigen::Vector3d> smoothPositions(const std::vector<SmootherSample>& samples,
                                             const SmootherOptions& options) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(samples.size());
  for (const auto& s : samples) out.push_back(s.position);
  if (options.accel_sigma <= 0.0) return out;
  std::size_t begin = 0;
  for (std::size_t i = 1; i <= samples.size(); ++i) {
    const bool breaks = i == samples.size() || samples[i].starts_stretch ||
                        !(samples[i].stamp > samples[i - 1].stamp) ||
                        samples[i].stamp - samples[i - 1].stamp > options.max_gap_s;
    if (!breaks) continue;
    smoothStretch(samples, begin, i, options, out);
    begin = i;
  }
  return out;
}

}  // namespace bmp::tracker
