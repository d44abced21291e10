#include "bmp/common/image_codec.hpp"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

#include <zlib.h>
#include <opencv2/imgcodecs.hpp>

namespace bmp {

namespace {

uint32_t readBE32(const uint8_t* p) {
  return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}
uint16_t readBE16(const uint8_t* p) {
  return static_cast<uint16_t>((p[0] << 8) | p[1]);
}

ImageProbe probePng(const std::vector<uint8_t>& b) {
  ImageProbe probe;
  probe.encoding = ImageEncoding::kPng;
  std::size_t pos = 8;
  bool seen_ihdr = false;
  while (true) {
    if (pos + 12 > b.size()) throw ImageError("PNG truncated: no IEND chunk (file cut short?)");
    const uint32_t length = readBE32(&b[pos]);
    if (length > b.size() - pos - 12)
      throw ImageError("PNG truncated inside a chunk at byte " + std::to_string(pos));
    const uint8_t* type = &b[pos + 4];
    const uint32_t stored_crc = readBE32(&b[pos + 8 + length]);
    const auto crc = static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), type, length + 4));
    const std::string name(reinterpret_cast<const char*>(type), 4);
    if (crc != stored_crc)
      throw ImageError("PNG chunk '" + name + "' at byte " + std::to_string(pos) +
                       " has a bad CRC (corrupt data)");
    if (!seen_ihdr) {
      if (name != "IHDR" || length != 13) throw ImageError("PNG does not start with an IHDR chunk");
      const uint8_t* d = type + 4;
      probe.width = static_cast<int>(readBE32(d));
      probe.height = static_cast<int>(readBE32(d + 4));
      probe.bit_depth = d[8];
      static constexpr int kChannelsByColourType[] = {1, 0, 3, 1, 2, 0, 4};
      probe.channels = d[9] <= 6 ? kChannelsByColourType[d[9]] : 0;
      if (probe.channels == 0) throw ImageError("PNG has an invalid colour type " + std::to_string(d[9]));
      seen_ihdr = true;
    }
    if (name == "IEND") return probe;
    pos += 12 + length;
  }
}

bool isSofMarker(uint8_t m) {
  return m >= 0xC0 && m <= 0xCF && m != 0xC4 && m != 0xC8 && m != 0xCC;
}

ImageProbe probeJpeg(const std::vector<uint8_t>& b) {
  ImageProbe probe;
  probe.encoding = ImageEncoding::kJpeg;
  probe.bit_depth = 8;
  std::size_t pos = 2;
  bool seen_sof = false;
  while (true) {
    if (pos + 4 > b.size()) throw ImageError("JPEG truncated in its headers");
    if (b[pos] != 0xFF) throw ImageError("JPEG header is corrupt at byte " + std::to_string(pos));
    const uint8_t marker = b[pos + 1];
    if (marker == 0xFF) {  // fill byte
      ++pos;
      continue;
    }
    const uint16_t length = readBE16(&b[pos + 2]);
    if (length < 2 || pos + 2 + length > b.size()) throw ImageError("JPEG truncated inside a header segment");
    if (isSofMarker(marker)) {
      if (length < 8) throw ImageError("JPEG frame header too short");
      probe.height = readBE16(&b[pos + 5]);
      probe.width = readBE16(&b[pos + 7]);
      probe.channels = b[pos + 9];
      seen_sof = true;
    }
    if (marker == 0xDA) break;  // start of scan: entropy-coded data follows
    pos += 2 + length;
  }
  if (!seen_sof) throw ImageError("JPEG has no frame header (SOF)");
  // The image must end with EOI; encoders may pad a few bytes after it.
  const std::size_t tail_start = b.size() > 64 ? b.size() - 64 : 0;
  bool has_eoi = false;
  for (std::size_t i = b.size() - 1; i > tail_start && !has_eoi; --i)
    has_eoi = b[i - 1] == 0xFF && b[i] == 0xD9;
  if (!has_eoi) throw ImageError("JPEG truncated: no end-of-image marker (file cut short?)");
  return probe;
}

// Progressive JPEG encoders write about 10 scans (libjpeg's default script); each scan is decoded over the
// whole image, so a message of many tiny scans costs seconds to decode (100000 of them: 1.35 s).
constexpr int kMaxJpegScans = 64;

// Start-of-scan markers in the data: an upper bound (a table's bytes may look like one), which is all the
// limit needs. Entropy-coded data escapes every 0xFF, so real scans cannot hide.
int countJpegScans(const std::vector<uint8_t>& b) {
  int scans = 0;
  for (std::size_t i = 0; i + 1 < b.size(); ++i)
    if (b[i] == 0xFF && b[i + 1] == 0xDA) ++scans;
  return scans;
}

// The size an encoded image's header declares, read without decoding (for PNG only the IHDR chunk, so
// no CRC walk over the whole file): decodeImage compares it with the declared size before OpenCV
// allocates anything, since a few hundred hostile bytes can claim 20000x20000 pixels. Also refuses what
// would cost far more to decode than its declared size: a 16-bit image that is not grey (decoded
// unchanged, up to 8 bytes a pixel), a JPEG of too many scans.
std::pair<int, int> headerSize(const EncodedImage& image) {
  const std::vector<uint8_t>& b = image.data;
  if (image.encoding == ImageEncoding::kPng) {
    static constexpr uint8_t kSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (b.size() < 33 || std::memcmp(b.data(), kSignature, 8) != 0 || std::memcmp(&b[12], "IHDR", 4) != 0)
      throw ImageError("no PNG header");
    const uint32_t width = readBE32(&b[16]);
    const uint32_t height = readBE32(&b[20]);
    const int bit_depth = b[24], colour_type = b[25];
    if (image.pixel_format == PixelFormat::kMono16 && (bit_depth != 16 || colour_type != 0))
      throw ImageError("PNG is " + std::to_string(bit_depth) + "-bit of colour type " +
                       std::to_string(colour_type) + ", not 16-bit grey as declared (not decoded)");
    const auto side = [](uint32_t v) { return v > 1u << 30 ? -1 : static_cast<int>(v); };
    return {side(width), side(height)};
  }
  if (b.size() < 3 || b[0] != 0xFF || b[1] != 0xD8 || b[2] != 0xFF) throw ImageError("no JPEG header");
  const ImageProbe probe = probeJpeg(b);  // walks the header segments only
  if (const int scans = countJpegScans(b); scans > kMaxJpegScans)
    throw ImageError("JPEG has " + std::to_string(scans) + " scans, more than " +
                     std::to_string(kMaxJpegScans) + " (not decoded)");
  return {probe.width, probe.height};
}

}  // namespace

ImageProbe probeEncodedImage(const std::vector<uint8_t>& bytes) {
  static constexpr uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPngSignature, 8) == 0) return probePng(bytes);
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) return probeJpeg(bytes);
  if (bytes.empty()) throw ImageError("empty file");
  throw ImageError("neither PNG nor JPEG (unknown signature)");
}

PixelFormat pixelFormatOf(const cv::Mat& mat) {
  switch (mat.type()) {
    case CV_8UC3:
      return PixelFormat::kBgr8;
    case CV_8UC1:
      return PixelFormat::kMono8;
    case CV_16UC1:
      return PixelFormat::kMono16;
    default:
      throw ImageError("unsupported pixel type " + std::to_string(mat.type()));
  }
}

const char* toString(ImageEncoding encoding) {
  switch (encoding) {
    case ImageEncoding::kRaw:
      return "raw";
    case ImageEncoding::kPng:
      return "png";
    case ImageEncoding::kJpeg:
      return "jpeg";
  }
  return "unknown";
}

const char* toString(PixelFormat format) {
  switch (format) {
    case PixelFormat::kBgr8:
      return "bgr8";
    case PixelFormat::kMono8:
      return "mono8";
    case PixelFormat::kMono16:
      return "mono16";
  }
  return "unknown";
}

cv::Mat decodeImage(const EncodedImage& image) {
  int type = 0;
  switch (image.pixel_format) {
    case PixelFormat::kBgr8:
      type = CV_8UC3;
      break;
    case PixelFormat::kMono8:
      type = CV_8UC1;
      break;
    case PixelFormat::kMono16:
      type = CV_16UC1;
      break;
    default:
      throw ImageError("unknown pixel format " + std::to_string(static_cast<int>(image.pixel_format)));
  }
  cv::Mat mat;
  if (image.encoding == ImageEncoding::kRaw) {
    const std::size_t expected = static_cast<std::size_t>(image.width) * image.height * CV_ELEM_SIZE(type);
    if (image.width <= 0 || image.height <= 0 || image.data.size() != expected)
      throw ImageError("raw image of " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                       " " + toString(image.pixel_format) + " needs " + std::to_string(expected) +
                       " bytes, got " + std::to_string(image.data.size()));
    mat = cv::Mat(image.height, image.width, type, const_cast<uint8_t*>(image.data.data())).clone();
  } else if (image.encoding == ImageEncoding::kPng || image.encoding == ImageEncoding::kJpeg) {
    if (image.data.empty()) throw ImageError("empty encoded image");
    std::pair<int, int> size;
    try {
      size = headerSize(image);
    } catch (const ImageError& e) {
      throw ImageError(std::string("undecodable ") + toString(image.encoding) + " data: " + e.what());
    }
    const auto [width, height] = size;
    if (width != image.width || height != image.height)
      throw ImageError(std::string(toString(image.encoding)) + " header says " + std::to_string(width) + "x" +
                       std::to_string(height) + ", declared " + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + " (not decoded)");
    // A JPEG's EXIF orientation is ignored: turned, the colour image would no longer lie over the depth
    // image (or be refused for its size, with no word of why). IMREAD_UNCHANGED ignores it already.
    const int flags =
        image.pixel_format == PixelFormat::kBgr8    ? cv::IMREAD_COLOR | cv::IMREAD_IGNORE_ORIENTATION
        : image.pixel_format == PixelFormat::kMono8 ? cv::IMREAD_GRAYSCALE | cv::IMREAD_IGNORE_ORIENTATION
                                                    : cv::IMREAD_UNCHANGED;
    try {
      mat = cv::imdecode(
          cv::Mat(1, static_cast<int>(image.data.size()), CV_8UC1, const_cast<uint8_t*>(image.data.data())),
          flags);
    } catch (const cv::Exception& e) {  // OpenCV throws on some corrupt headers instead of failing
      throw ImageError(std::string("undecodable ") + toString(image.encoding) + " data: " + e.what());
    }
    if (mat.empty()) throw ImageError(std::string("undecodable ") + toString(image.encoding) + " data");
    if (mat.type() != type)
      throw ImageError(std::string("decoded ") + toString(image.encoding) + " has pixel type " +
                       std::to_string(mat.type()) + ", expected " + toString(image.pixel_format));
  } else {
    throw ImageError("unknown image encoding " + std::to_string(static_cast<int>(image.encoding)));
  }
  if (mat.cols != image.width || mat.rows != image.height)
    throw ImageError("image is " + std::to_string(mat.cols) + "x" + std::to_string(mat.rows) + ", declared " +
                     std::to_string(image.width) + "x" + std::to_string(image.height));
  return mat;
}

EncodedImage encodeImage(const cv::Mat& mat, ImageEncoding encoding, int jpeg_quality) {
  EncodedImage out;
  out.width = mat.cols;
  out.height = mat.rows;
  out.encoding = encoding;
  out.pixel_format = pixelFormatOf(mat);
  if (encoding == ImageEncoding::kRaw) {
    const cv::Mat contiguous = mat.isContinuous() ? mat : mat.clone();
    out.data.assign(contiguous.data, contiguous.data + contiguous.total() * contiguous.elemSize());
    return out;
  }
  if (encoding == ImageEncoding::kJpeg && out.pixel_format == PixelFormat::kMono16)
    throw ImageError("JPEG cannot hold 16-bit images");
  const std::string ext = encoding == ImageEncoding::kPng ? ".png" : ".jpg";
  std::vector<int> params;
  if (encoding == ImageEncoding::kJpeg) params = {cv::IMWRITE_JPEG_QUALITY, jpeg_quality};
  // Fast PNG compression: these images travel over loopback, where bytes are cheap and time is not.
  if (encoding == ImageEncoding::kPng) params = {cv::IMWRITE_PNG_COMPRESSION, 1};
  if (!cv::imencode(ext, mat, out.data, params)) throw ImageError("cannot encode image as " + ext);
  return out;
}

std::vector<uint8_t> readFileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ImageError(path + ": cannot open file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw ImageError(path + ": cannot read file size");
  if (static_cast<std::uintmax_t>(size) > kMaxImageFileBytes)
    throw ImageError(path + ": " + std::to_string(static_cast<std::uintmax_t>(size) >> 20) +
                     " MiB, larger than any image read (" + std::to_string(kMaxImageFileBytes >> 20) +
                     " MiB)");
  in.seekg(0, std::ios::beg);
  std::vector<uint8_t> bytes(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
    throw ImageError(path + ": read failed");
  return bytes;
}

}  // namespace bmp
