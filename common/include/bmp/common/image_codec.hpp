#pragma once
// Images as they travel: raw pixels or the bytes of a PNG/JPEG file. Also a cheap structural check of
// encoded files (headers, PNG chunk CRCs, end markers) so a capture process can refuse a corrupt file
// without paying for a full decode.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace bmp {

enum class ImageEncoding : int8_t { kRaw = 0, kPng = 1, kJpeg = 2 };
enum class PixelFormat : int8_t { kBgr8 = 0, kMono8 = 1, kMono16 = 2 };

struct EncodedImage {
  int width = 0;
  int height = 0;
  ImageEncoding encoding = ImageEncoding::kRaw;
  PixelFormat pixel_format = PixelFormat::kBgr8;
  std::vector<uint8_t> data;
};

class ImageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// What the header of an encoded file says.
struct ImageProbe {
  ImageEncoding encoding = ImageEncoding::kRaw;
  int width = 0;
  int height = 0;
  int channels = 0;
  int bit_depth = 0;
};

// Checks the structure of PNG or JPEG bytes. Throws ImageError saying what is wrong (unknown format,
// truncated, bad chunk CRC, missing end marker).
ImageProbe probeEncodedImage(const std::vector<uint8_t>& bytes);

// Decodes to CV_8UC3 (kBgr8), CV_8UC1 (kMono8) or CV_16UC1 (kMono16), checking the result against the
// declared size and format. Throws ImageError.
cv::Mat decodeImage(const EncodedImage& image);
// Encodes a CV_8UC3, CV_8UC1 or CV_16UC1 matrix (JPEG only for 8 bit). Throws ImageError.
EncodedImage encodeImage(const cv::Mat& mat, ImageEncoding encoding, int jpeg_quality = 95);

PixelFormat pixelFormatOf(const cv::Mat& mat);
const char* toString(ImageEncoding encoding);
const char* toString(PixelFormat format);

// The largest image file read: a 16 MP 16-bit PNG stored uncompressed is 32 MiB. A larger file is not a
// frame's image (a 200 GB file listed in rgb.txt stopped capture with an unnamed bad_alloc).
inline constexpr std::uintmax_t kMaxImageFileBytes = std::uintmax_t{256} << 20;

// Whole file as bytes; throws ImageError naming the file when it cannot be read or is larger than
// kMaxImageFileBytes.
std::vector<uint8_t> readFileBytes(const std::string& path);

}  // namespace bmp
