#include "tracker/moving_probability.hpp"

#include <algorithm>

namespace bmp::tracker {

namespace {

// Bayes with the observation's likelihoods under "dynamic" and "static".
double posterior(double prior, double like_dynamic, double like_static) {
  const double p = std::clamp(prior, 0.0, 1.0);
  const double num = like_dynamic * p;
  const double den = num + like_static * (1.0 - p);
  return den > 0.0 ? num / den : p;  // both likelihoods 0: the observation says nothing
}

}  // namespace

double updateMovingProbability(double prior, bool observed_dynamic, const MovingProbabilityOptions& o) {
  const double like_dynamic = observed_dynamic ? o.lambda : 1.0 - o.lambda;
  const double like_static = observed_dynamic ? 1.0 - o.omega : o.omega;
  return posterior(prior, like_dynamic, like_static);
}

double withdrawObservation(double posterior_after, bool observed_dynamic, const MovingProbabilityOptions& o) {
  // The update multiplies the odds by like_dynamic / like_static; the likelihoods swapped divide them by it.
  const double like_dynamic = observed_dynamic ? o.lambda : 1.0 - o.lambda;
  const double like_static = observed_dynamic ? 1.0 - o.omega : o.omega;
  return posterior(posterior_after, like_static, like_dynamic);
}

}  // namespace bmp::tracker
