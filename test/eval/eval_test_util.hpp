#pragma once
// Small builders shared by the bmp-eval tests.
#include <string>

#include "bmp/common/tum_trajectory.hpp"

namespace bmp::eval::test {

SE3 pose(double x, double y, double z, double yaw = 0.0, double pitch = 0.0, double roll = 0.0);
// T applied on the left of every pose: the same motion expressed in another world frame.
Trajectory transformed(const Trajectory& trajectory, const SE3& T);
void writeText(const std::string& path, const std::string& text);
std::string readText(const std::string& path);
// Runs a shell command; returns its exit status (-1 when it did not exit normally).
int runCommand(const std::string& command);

}  // namespace bmp::eval::test
