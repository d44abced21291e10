#include "eval_test_util.hpp"

#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

namespace bmp::eval::test {

SE3 pose(double x, double y, double z, double yaw, double pitch, double roll) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  return makeSE3({x, y, z}, q);
}

Trajectory transformed(const Trajectory& trajectory, const SE3& T) {
  Trajectory out = trajectory;
  for (auto& p : out) p.T_world_cam = T * p.T_world_cam;
  return out;
}

void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path) << text;
}

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int runCommand(const std::string& command) {
  const int status = std::system(command.c_str());
  return (status != -1 && WIFEXITED(status)) ? WEXITSTATUS(status) : -1;
}

}  // namespace bmp::eval::test
