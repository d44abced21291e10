#include "tracker/moving_probability.hpp"

#include <algorithm>

namespace bmp::tracker {

double updateMovingProbability(double prior, bool observed_dynamic, const MovingProbabilityOptions& o) {
  const double p = std::clamp(prior, 0.0, 1.0);
  const double like_dynamic = observed_dynamic ? o.lambda : 1.0 - o.lambda;
  const double like_static = observed_dynamic ? 1.0 - o.omega : o.omega;
  const double num = like_dynamic * p;
  const double den = num + like_static * (1.0 - p);
  return den > 0.0 ? num / den : p;  // both likelihoods 0: the observation says nothing
}

double withdrawObservation(double posterior, bool observed_dynamic, const MovingProbabilityOptions& o) {
  // The update multiplies the odds by like_dynamic / like_static; this divides them by it.
  const double p = std::clamp(posterior, 0.0, 1.0);
  const double like_dynamic = observed_dynamic ? o.lambda : 1.0 - o.lambda;
  const double like_static = observed_dynamic ? 1.0 - o.omega : o.omega;
  const double num = like_static * p;
  const double den = num + like_dynamic * (1.0 - p);
  return den > 0.0 ? num / den : p;
}

}  // namespace bmp::tracker
