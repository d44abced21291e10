#pragma once
// The Bayesian moving probability (An et al. 2025, section 3.3, with the static-case update stated
// correctly in ../shared/DESIGN.md). Each keypoint carries P(dynamic); its prior is the posterior of what it
// was matched to (map point or last-frame keypoint), 0.5 when unmatched; each detector observation
// z in {d, s} updates it by Bayes with P(z=d|d) = lambda and P(z=s|s) = omega.
namespace bmp::tracker {

struct MovingProbabilityOptions {
  double lambda = 0.9;           // P(z = d | dynamic): the detector sees a mover as dynamic
  double omega = 0.9;            // P(z = s | static): the detector sees a static point as static
  double unmatched_prior = 0.5;  // prior of a keypoint matched to nothing
  double threshold = 0.5;        // P(dynamic) above this keeps a keypoint out of pose, new points and BA
};

// Posterior P(dynamic) after observing z = d (observed_dynamic) or z = s, from prior p.
//   z = d:  lambda p / (lambda p + (1 - omega)(1 - p))
//   z = s:  (1 - lambda) p / ((1 - lambda) p + omega (1 - p))
double updateMovingProbability(double prior, bool observed_dynamic, const MovingProbabilityOptions& o);
// The inverse: the probability before an observation z was taken into `posterior` (its likelihood ratio
// divided out). A frame observed with stand-in boxes (real time, its own answer late) takes its own answer
// in their place this way, not on top of them.
double withdrawObservation(double posterior_after, bool observed_dynamic, const MovingProbabilityOptions& o);

inline bool isDynamic(double p, const MovingProbabilityOptions& o) {
  return p > o.threshold;
}

}  // namespace bmp::tracker
