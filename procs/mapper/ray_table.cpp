#include "mapper/ray_table.hpp"

namespace bmp::mapper {

RayTable::RayTable(const CameraIntrinsics& camera)
    : camera_(camera), rays_(camera.height, camera.width, CV_32FC2) {
  const CameraModel model(camera);
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector2d uv =
          model.hasDistortion() ? model.undistortPixel(Eigen::Vector2d(u, v)) : Eigen::Vector2d(u, v);
      rays_.at<cv::Vec2f>(v, u) = cv::Vec2f(static_cast<float>((uv.x() - camera.cx) / camera.fx),
                                            static_cast<float>((uv.y() - camera.cy) / camera.fy));
    }
  }
}

bool RayTable::fits(const CameraIntrinsics& c) const {
  return !rays_.empty() && c.width == camera_.width && c.height == camera_.height && c.fx == camera_.fx &&
         c.fy == camera_.fy && c.cx == camera_.cx && c.cy == camera_.cy && c.distortion == camera_.distortion;
}

}  // namespace bmp::mapper
