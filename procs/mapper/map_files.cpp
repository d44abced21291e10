#include "mapper/map_files.hpp"

#include <filesystem>

#include <opencv2/imgcodecs.hpp>

#include "bmp/common/atomic_file.hpp"
#include "mapper/cloud_files.hpp"
#include "mapper/grid_pair.hpp"
#include "mapper/map_pictures.hpp"

namespace bmp::mapper {

namespace {

std::string png(const cv::Mat& image) {
  std::vector<uchar> bytes;
  if (!cv::imencode(".png", image, bytes)) throw FileWriteError("cannot encode a PNG picture");
  return std::string(bytes.begin(), bytes.end());
}

}  // namespace

void checkMapFolder(const std::string& dir) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw FileWriteError(dir + ": cannot create the map folder: " + ec.message());
  const std::string probe = (fs::path(dir) / ".bmp-mapper-write-check").string();
  writeFileAtomically(probe, "");  // throws FileWriteError naming the file, hence the folder
  fs::remove(probe, ec);
}

std::vector<std::string> writeMapFiles(const std::string& dir, Mapper& mapper) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw FileWriteError(dir + ": cannot create the folder: " + ec.message());
  mapper.flush();
  const PointList& cloud = mapper.cloud();
  const OccupancyGrid2D grid = mapper.grid();
  const MapperSettings& s = mapper.settings();
  const GridSettings grounded = mapper.groundedGrid();
  const PlaneFrame frame = PlaneFrame::fromUp(grounded.up, grounded.axes_from);
  std::vector<std::string> written;
  const auto put = [&](const std::string& name, const std::string& content) {
    const std::string path = (fs::path(dir) / name).string();
    writeFileAtomically(path, content);
    written.push_back(path);
  };
  put("map.pcd", encodePcd(cloud));
  put("map.ply", encodePly(cloud));
  put("map.bt", mapper.occupancy().binaryFile());
  for (auto& path : writeGridPair(dir, grid)) written.push_back(std::move(path));
  put("cloud_top.png", png(renderTopView(cloud, frame, grounded, s.pictures)));
  put("cloud_oblique.png", png(renderObliqueView(cloud, frame, grounded, s.pictures)));
  put("occupancy.png", png(renderGrid(grid, s.pictures.grid_cell_px)));
  return written;
}

}  // namespace bmp::mapper
