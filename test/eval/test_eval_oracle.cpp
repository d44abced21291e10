// Oracle: bmp_eval against test/eval/tum_reference.py (numpy, written from the TUM scripts' definitions) on
// the real Bonn ground truth and a perturbed, time-shifted, re-framed copy of it.
#include <cstdint>
#include <cstdio>
#include <map>
#include <random>
#include <sstream>

#include <gtest/gtest.h>

#include "eval/ate.hpp"
#include "eval/eval_input.hpp"
#include "eval/rpe.hpp"
#include "eval_test_util.hpp"
#include "shared_data.hpp"

namespace bmp::eval {

namespace {

constexpr const char* kPython = "/usr/bin/python3";  // the interpreter with numpy

// mt19937's sequence is fixed by the standard, so this noise is the same everywhere.
class Noise {
 public:
  explicit Noise(std::uint32_t seed) : rng_(seed) {}
  double uniform(double half_width) {
    return (static_cast<double>(rng_()) / 4294967295.0 * 2.0 - 1.0) * half_width;
  }

 private:
  std::mt19937 rng_;
};

// Every fifth pose dropped, stamps 12.3 ms late, positions with a slow random walk plus jitter, small
// orientation noise, all expressed in another world frame.
std::string writePerturbedCopy(const Trajectory& gt, const std::string& path) {
  Noise noise(20261122);
  const SE3 other_world = test::pose(1.5, -0.7, 0.2, 0.8, 0.1, -0.3);
  Eigen::Vector3d drift = Eigen::Vector3d::Zero();
  Trajectory est;
  for (std::size_t k = 0; k < gt.size(); ++k) {
    drift += Eigen::Vector3d(noise.uniform(0.002), noise.uniform(0.002), noise.uniform(0.002));
    if (k % 5 == 4) continue;
    const SE3 jitter = test::pose(noise.uniform(0.01), noise.uniform(0.01), noise.uniform(0.01),
                                  noise.uniform(0.01), noise.uniform(0.01), noise.uniform(0.01));
    SE3 T = gt[k].T_world_cam * jitter;
    T.translation() += drift;
    est.push_back({gt[k].stamp + 0.0123, other_world * T});
  }
  writeTumTrajectory(path, est);
  return path;
}

std::map<std::string, double> runReference(const std::string& gt, const std::string& est,
                                           const std::string& options) {
  const std::string command = std::string(kPython) + " '" + BMP_EVAL_REFERENCE_PY + "' '" + gt + "' '" + est +
                              "' " + options + " 2>&1";
  std::map<std::string, double> values;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return values;
  char line[512];
  while (std::fgets(line, sizeof(line), pipe) != nullptr) {
    std::istringstream in(line);
    std::string key;
    double value = 0;
    if (in >> key >> value) values[key] = value;
  }
  const int status = pclose(pipe);
  EXPECT_EQ(status, 0) << command;
  return values;
}

void expectStats(const std::map<std::string, double>& ref, const std::string& prefix, const ErrorStats& s,
                 double tolerance) {
  ASSERT_TRUE(ref.count(prefix + ".count")) << "reference printed no " << prefix;
  EXPECT_EQ(static_cast<std::size_t>(ref.at(prefix + ".count")), s.count) << prefix;
  const std::pair<const char*, double> fields[] = {{"rmse", s.rmse}, {"mean", s.mean}, {"median", s.median},
                                                   {"std", s.std},   {"min", s.min},   {"max", s.max}};
  for (const auto& [name, value] : fields) {
    EXPECT_NEAR(ref.at(prefix + "." + name), value, tolerance) << prefix << "." << name;
  }
}

struct Case {
  const char* name;
  const char* reference_options;
  AteOptions ate;
  RpeOptions rpe;
};

}  // namespace

TEST(evalOracle, AgreesWithNumpyReferenceOnBonnCrowd) {
  const std::string gt_path = bmp::test::bonnDir() + "/groundtruth.txt";
  const Trajectory gt_raw = loadTrajectory(gt_path);
  const std::string est_path =
      writePerturbedCopy(gt_raw, (bmp::test::scratchDir("eval_oracle") / "perturbed.txt").string());
  // Both sides read the same files.
  const Trajectory gt = loadTrajectory(gt_path);
  const Trajectory est = loadTrajectory(est_path);

  std::vector<Case> cases(3);
  cases[0] = {"defaults", "", {}, {}};
  cases[1] = {"frames", "--delta 1 --delta_unit f", {}, {}};
  cases[1].rpe.unit = DeltaUnit::kFrames;
  cases[2] = {"offset-scale", "--offset -0.0123 --scale 1.05 --delta 0.5", {}, {}};
  cases[2].ate.offset = cases[2].rpe.offset = -0.0123;
  cases[2].ate.scale = cases[2].rpe.scale = 1.05;
  cases[2].rpe.delta = 0.5;

  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const auto ref = runReference(gt_path, est_path, c.reference_options);
    const AteResult ate = computeAte(gt, est, c.ate);
    const RpeResult rpe = computeRpe(gt, est, c.rpe);
    ASSERT_GT(ate.stats.count, 600u);
    ASSERT_GT(rpe.trans.count, 500u);
    EXPECT_GT(ate.stats.rmse, 0.005);  // the perturbation is really there
    expectStats(ref, "ate", ate.stats, 1e-6);
    expectStats(ref, "rpe_trans", rpe.trans, 1e-6);
    expectStats(ref, "rpe_rot_deg", rpe.rot_deg, 1e-6);
  }
}

}  // namespace bmp::eval
