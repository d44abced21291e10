#include "tracker/moving_probability.hpp"

#include <algorithm>

namespace bmp::tracker {

namespace {

// The observation's likelihood under "dynamic" and under "static" (the paper's lambda and omega).
struct Likelihoods {
  double dynamic, stat;
};
Likelihoods likelihoods(bool observed_dynamic, const MovingProbabilityOptions& o) {
  return observed_dynamic ? Likelihoods{o.lambda, 1.0 - o.omega} : Likelihoods{1.0 - o.lambda, o.omega};
}

// Bayes with the observation's likelihoods under "dynamic" and "static".
double posterior(double prior, double like_dynamic, double like_static) {
  const double p = std::clamp(prior, 0.0, 1.0);
  const double num = like_dynamic * p;
  const double den = num + like_static * (1.0 - p);
  return den > 0.0 ? num / den : p;  // both likelihoods 0: the observation says nothing
}

}  // namespace

double updateMovingProbability(double prior, bool observed_dynamic, const MovingProbabilityOptions& o) {
  const Likelihoods like = likelihoods(observed_dynamic, o);
  return posterior(prior, like.dynamic, like.stat);
}

double withdrawObservation(double posterior_after, bool observed_dynamic, const MovingProbabilityOptions& o) {
  // The update multiplies the odds by like.dynamic / like.stat; the likelihoods swapped divide them by it.
  const Likelihoods like = likelihoods(observed_dynamic, o);
  return posterior(posterior_after, like.stat, like.dynamic);
}

}  // namespace bmp::tracker
