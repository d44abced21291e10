#pragma once
// An image file's bytes as an LCM image_t, not re-encoded (as bmp-capture publishes them), for process tests.
// Header-only: the including test links bmp_common and bmp_lcm.
#include <string>
#include <utility>

#include <bmp/image_t.hpp>

#include "bmp/common/image_codec.hpp"
#include "bmp/lcm/conversions.hpp"

namespace bmp::test {

inline image_t fileImage(const std::string& path, PixelFormat format) {
  EncodedImage image;
  image.data = readFileBytes(path);
  const ImageProbe probe = probeEncodedImage(image.data);  // the file's real encoding and size
  image.width = probe.width;
  image.height = probe.height;
  image.encoding = probe.encoding;
  image.pixel_format = format;
  return toMsg(std::move(image));
}

}  // namespace bmp::test
