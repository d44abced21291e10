#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <type_traits>

#include <opencv2/imgcodecs.hpp>

#include "plan/plan_grid.hpp"

namespace bmp::plan {

Eigen::Vector2i PlanGrid::cellOf(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d rel = (p - origin) / resolution;
  // Clamped to one cell beyond the grid before the cast: a point far off (or a tiny resolution) stays
  // outside it, where casting its double to int would be undefined.
  const auto cell = [](double r, int size) {
    return static_cast<int>(std::clamp(std::floor(r), -1.0, static_cast<double>(size)));
  };
  return {cell(rel.x(), width), cell(rel.y(), height)};
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
  if (!doc.IsMap())
    throw MapFileError(yaml_path +
                       ": not a map description (a YAML mapping of image, resolution, origin, ...)");
  const auto need = [&](const char* key) {
    if (!doc[key]) throw MapFileError(yaml_path + ": key '" + key + "' missing");
    return doc[key];
  };
  // A value of the wrong kind ("resolution: abc") named by its key, not in yaml-cpp's words.
  const auto as = [&](const YAML::Node& node, const std::string& key, auto kind) {
    try {
      return node.as<decltype(kind)>();
    } catch (const YAML::Exception&) {
      throw MapFileError(yaml_path + ": key '" + key + "' must be " +
                         (std::is_same_v<decltype(kind), std::string> ? "text" : "a number"));
    }
  };
  PlanGrid grid;
  std::filesystem::path image_path = as(need("image"), "image", std::string());
  if (image_path.is_relative()) image_path = std::filesystem::path(yaml_path).parent_path() / image_path;
  grid.resolution = as(need("resolution"), "resolution", 0.0);
  const YAML::Node origin = need("origin");
  if (!origin.IsSequence() || origin.size() < 2)
    throw MapFileError(yaml_path + ": origin must be [x, y, yaw]");
  if (origin.size() > 2 && std::abs(as(origin[2], "origin", 0.0)) > 1e-9)
    throw MapFileError(yaml_path + ": a rotated origin (yaw != 0) is not supported");
  grid.origin = {as(origin[0], "origin", 0.0), as(origin[1], "origin", 0.0)};
  const bool negate = as(need("negate"), "negate", 0) != 0;
  const double occupied = as(need("occupied_thresh"), "occupied_thresh", 0.0);
  const double free = as(need("free_thresh"), "free_thresh", 0.0);
  if (!(grid.resolution > 0) || !std::isfinite(grid.resolution))
    throw MapFileError(yaml_path + ": resolution must be positive");
  if (!grid.origin.allFinite()) throw MapFileError(yaml_path + ": origin must be finite");

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
