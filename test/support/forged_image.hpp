#pragma once
// Encoded images whose headers lie, as a hostile publisher sends them: the size in a PNG's IHDR (with its
// CRC made right again, so the file stays well-formed) or in a JPEG's frame header rewritten. Header-only.
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace bmp::test {

inline void putBigEndian(std::vector<uint8_t>& b, std::size_t at, uint32_t v, int bytes) {
  for (int i = 0; i < bytes; ++i) b.at(at + i) = static_cast<uint8_t>(v >> (8 * (bytes - 1 - i)));
}

// PNG's CRC-32 (polynomial 0xEDB88320), bit by bit: a header chunk is 17 bytes.
inline uint32_t pngCrc(const uint8_t* data, std::size_t n) {
  uint32_t crc = 0xFFFFFFFFu;
  for (std::size_t i = 0; i < n; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return crc ^ 0xFFFFFFFFu;
}

inline void setPngSize(std::vector<uint8_t>& png, uint32_t width, uint32_t height) {
  putBigEndian(png, 16, width, 4);
  putBigEndian(png, 20, height, 4);
  putBigEndian(png, 29, pngCrc(&png.at(12), 17), 4);  // over the chunk type and its 13 bytes
}

// Rewrites the size in the first frame header (SOF0-2) of a JPEG.
inline void setJpegSize(std::vector<uint8_t>& jpeg, uint16_t width, uint16_t height) {
  std::size_t pos = 2;
  while (pos + 9 < jpeg.size()) {
    const uint8_t marker = jpeg[pos + 1];
    if (marker == 0xC0 || marker == 0xC1 || marker == 0xC2) {
      putBigEndian(jpeg, pos + 5, height, 2);
      putBigEndian(jpeg, pos + 7, width, 2);
      return;
    }
    pos += 2 + ((jpeg[pos + 2] << 8) | jpeg[pos + 3]);
  }
  throw std::runtime_error("no frame header in the JPEG");
}

}  // namespace bmp::test
