#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "plan/plan_grid.hpp"

namespace bmp::plan {

Eigen::Vector2i PlanGrid::cellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d rel = (p - origin) / resolution;
  return {static_cast<int>(std::floor(rel.x())), static_cast<int>(std::floor(rel.y()))};
}

Eigen::Vector2d PlanGrid::centreOf(int col, int row) const {
  return origin + resolution * Eigen::Vector2d(col + 0.5, row + 0.5);
}

PlanGrid readMapServerMap(const std::string& yaml_path) {
  YAML::Node doc;
  // yaml-cpp says "bad file" for both; a path that names nothing is the likelier mistake.
  if (!std::filesystem::exists(yaml_path)) throw MapFileError(yaml_path + ": no such file");
  if (std::filesystem::is_directory(yaml_path))
    throw MapFileError(yaml_path + ": is a folder, not a map file");
  try {
    doc = YAML::LoadFile(yaml_path);
  } catch (const YAML::Exception& e) {
    throw MapFileError(yaml_path + ": " + e.what());
  }
  const auto need = [&](const char* key) {
    if (!doc[key]) throw MapFileError(yaml_path + ": key '" + key + "' missing");
    return doc[key];
  };
  PlanGrid grid;
  std::filesystem::path image_path = need("image").as<std::string>();
  if (image_path.is_relative()) image_path = std::filesystem::path(yaml_path).parent_path() / image_path;
  grid.resolution = need("resolution").as<double>();
  const YAML::Node origin = need("origin");
  if (!origin.IsSequence() || origin.size() < 2)
    throw MapFileError(yaml_path + ": origin must be [x, y, yaw]");
  if (origin.size() > 2 && std::abs(origin[2].as<double>()) > 1e-9)
    throw MapFileError(yaml_path + ": a rotated origin (yaw != 0) is not supported");
  grid.origin = {origin[0].as<double>(), origin[1].as<double>()};
  const bool negate = need("negate").as<int>() != 0;
  const double occupied = need("occupied_thresh").as<double>(), free = need("free_thresh").as<double>();
  if (!(grid.resolution > 0)) throw MapFileError(yaml_path + ": resolution must be positive");

  const cv::Mat image = cv::imread(image_path.string(), cv::IMREAD_GRAYSCALE);
  if (image.empty()) throw MapFileError(image_path.string() + ": cannot read the map image");
  grid.width = image.cols;
  grid.height = image.rows;
  grid.cells.resize(static_cast<std::size_t>(grid.width) * grid.height);
  for (int row = 0; row < grid.height; ++row) {
    const uchar* line = image.ptr<uchar>(grid.height - 1 - row);  // image top = largest y
    for (int col = 0; col < grid.width; ++col) {
      const double p = negate ? line[col] / 255.0 : (255.0 - line[col]) / 255.0;
      grid.cells[static_cast<std::size_t>(row) * grid.width + col] = p > occupied ? kOccupied
                                                                     : p < free   ? kFree
                                                                                  : kUnknown;
    }
  }
  return grid;
}

}  // namespace bmp::plan
