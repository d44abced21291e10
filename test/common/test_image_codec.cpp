#include <gtest/gtest.h>

#include <fstream>

#include <opencv2/imgcodecs.hpp>

#include "bmp/common/image_codec.hpp"
#include "forged_image.hpp"
#include "shared_data.hpp"

namespace bmp {
namespace {

using test::setJpegSize;
using test::setPngSize;

const std::string kDepth = "data/rgbd_bonn_crowd/depth/1548339829.89888.png";
const std::string kColour = "data/rgbd_bonn_crowd/rgb/1548339829.89644.jpg";

TEST(ImageProbe, RealBonnFiles) {
  const ImageProbe depth = probeEncodedImage(readFileBytes(test::sharedPath(kDepth)));
  EXPECT_EQ(depth.encoding, ImageEncoding::kPng);
  EXPECT_EQ(depth.width, 640);
  EXPECT_EQ(depth.height, 480);
  EXPECT_EQ(depth.bit_depth, 16);
  EXPECT_EQ(depth.channels, 1);
  const ImageProbe colour = probeEncodedImage(readFileBytes(test::sharedPath(kColour)));
  EXPECT_EQ(colour.encoding, ImageEncoding::kJpeg);
  EXPECT_EQ(colour.width, 640);
  EXPECT_EQ(colour.height, 480);
  EXPECT_EQ(colour.channels, 3);
}

TEST(ImageProbe, DetectsCorruption) {
  std::vector<uint8_t> png = readFileBytes(test::sharedPath(kDepth));
  std::vector<uint8_t> flipped = png;
  flipped[png.size() / 2] ^= 0x40;  // one bit inside the compressed data
  EXPECT_THROW(probeEncodedImage(flipped), ImageError);
  std::vector<uint8_t> truncated(png.begin(), png.begin() + static_cast<long>(png.size() / 2));
  EXPECT_THROW(probeEncodedImage(truncated), ImageError);
  std::vector<uint8_t> jpeg = readFileBytes(test::sharedPath(kColour));
  std::vector<uint8_t> jpeg_cut(jpeg.begin(), jpeg.begin() + static_cast<long>(jpeg.size() - 500));
  EXPECT_THROW(probeEncodedImage(jpeg_cut), ImageError);
  EXPECT_THROW(probeEncodedImage({'h', 'e', 'l', 'l', 'o'}), ImageError);
  EXPECT_THROW(probeEncodedImage({}), ImageError);
}

TEST(ImageCodec, DecodesRealFilesWithDeclaredFormat) {
  EncodedImage depth{640, 480, ImageEncoding::kPng, PixelFormat::kMono16,
                     readFileBytes(test::sharedPath(kDepth))};
  const cv::Mat d = decodeImage(depth);
  EXPECT_EQ(d.type(), CV_16UC1);
  EXPECT_GT(cv::countNonZero(d), 100000);
  EncodedImage colour{640, 480, ImageEncoding::kJpeg, PixelFormat::kBgr8,
                      readFileBytes(test::sharedPath(kColour))};
  EXPECT_EQ(decodeImage(colour).type(), CV_8UC3);
  // Declared size must match.
  colour.width = 320;
  EXPECT_THROW(decodeImage(colour), ImageError);
}

TEST(ImageCodec, RawAndPngRoundTrip) {
  cv::Mat depth(48, 64, CV_16UC1);
  cv::randu(depth, 0, 60000);
  for (ImageEncoding enc : {ImageEncoding::kRaw, ImageEncoding::kPng}) {
    const EncodedImage e = encodeImage(depth, enc);
    EXPECT_EQ(cv::norm(decodeImage(e), depth, cv::NORM_INF), 0.0) << toString(enc);
  }
  EncodedImage bad = encodeImage(depth, ImageEncoding::kRaw);
  bad.data.pop_back();
  EXPECT_THROW(decodeImage(bad), ImageError);
  EncodedImage garbage{64, 48, ImageEncoding::kPng, PixelFormat::kMono16, {1, 2, 3, 4}};
  EXPECT_THROW(decodeImage(garbage), ImageError);
}

// A JPEG whose EXIF says to turn it 180 degrees: decoded as stored, so colour still lies over depth (OpenCV
// turned it by default, silently, the size unchanged).
TEST(ImageCodec, AJpegsExifOrientationIsIgnored) {
  cv::Mat image(48, 64, CV_8UC3, cv::Scalar(0, 0, 0));
  image(cv::Rect(0, 0, 16, 12)).setTo(cv::Scalar(255, 255, 255));  // a white top-left corner
  EncodedImage jpeg = encodeImage(image, ImageEncoding::kJpeg);
  // APP1 "Exif", big-endian TIFF, one IFD entry: Orientation (0x0112), SHORT, 1, value 3 (turned 180).
  const std::vector<uint8_t> app1 = {0xFF, 0xE1, 0x00, 0x22, 'E',  'x',  'i',  'f',  0,    0,    'M',  'M',
                                     0x00, 0x2A, 0x00, 0x00, 0x00, 0x08, 0x00, 0x01, 0x01, 0x12, 0x00, 0x03,
                                     0x00, 0x00, 0x00, 0x01, 0x00, 0x03, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00};
  jpeg.data.insert(jpeg.data.begin() + 2, app1.begin(), app1.end());  // after SOI
  const cv::Mat decoded = decodeImage(jpeg);
  ASSERT_EQ(decoded.size(), image.size());
  EXPECT_GT(decoded.at<cv::Vec3b>(2, 2)[0], 200) << "the white corner is still top left";
  EXPECT_LT(decoded.at<cv::Vec3b>(45, 61)[0], 50);
  // Grey too.
  jpeg.pixel_format = PixelFormat::kMono8;
  EXPECT_GT(decodeImage(jpeg).at<uint8_t>(2, 2), 200);
}

// decodeImage's ImageError message, or "decoded" (any other exception fails the test).
std::string decodeError(const EncodedImage& image) {
  try {
    decodeImage(image);
    return "decoded";
  } catch (const ImageError& e) {
    return e.what();
  }
}

// A hostile publisher's few hundred bytes whose header claims a huge image: refused from the header,
// before OpenCV allocates (a 20000x20000 JPEG took 1.2 GB and 5.5 s to decode only to be refused).
TEST(ImageCodec, AHeaderClaimingAHugeImageIsRefusedBeforeDecoding) {
  EncodedImage depth{640, 480, ImageEncoding::kPng, PixelFormat::kMono16,
                     readFileBytes(test::sharedPath(kDepth))};
  setPngSize(depth.data, 20000, 20000);
  EXPECT_EQ(decodeError(depth), "png header says 20000x20000, declared 640x480 (not decoded)");
  EncodedImage colour{640, 480, ImageEncoding::kJpeg, PixelFormat::kBgr8,
                      readFileBytes(test::sharedPath(kColour))};
  setJpegSize(colour.data, 20000, 20000);
  EXPECT_EQ(decodeError(colour), "jpeg header says 20000x20000, declared 640x480 (not decoded)");
  // Data of one format declared as the other is refused too.
  colour.encoding = ImageEncoding::kPng;
  EXPECT_THROW(decodeImage(colour), ImageError);
}

// What costs far more to decode than the size it declares is refused before decoding: a depth PNG that is
// not 16-bit grey (16-bit colour decodes unchanged to 6 or 8 bytes a pixel), a JPEG of many scans.
TEST(ImageCodec, ADepthPngThatIsNotSixteenBitGreyIsRefusedBeforeDecoding) {
  const EncodedImage real{640, 480, ImageEncoding::kPng, PixelFormat::kMono16,
                          readFileBytes(test::sharedPath(kDepth))};
  EXPECT_EQ(decodeImage(real).type(), CV_16UC1);
  EncodedImage colour16{640, 480, ImageEncoding::kPng, PixelFormat::kMono16, {}};
  ASSERT_TRUE(cv::imencode(".png", cv::Mat(480, 640, CV_16UC3, cv::Scalar(1, 2, 3)), colour16.data));
  EXPECT_EQ(
      decodeError(colour16),
      "undecodable png data: PNG is 16-bit of colour type 2, not 16-bit grey as declared (not decoded)");
  EncodedImage grey8 = encodeImage(cv::Mat(480, 640, CV_8UC1, cv::Scalar(9)), ImageEncoding::kPng);
  grey8.pixel_format = PixelFormat::kMono16;
  EXPECT_EQ(decodeError(grey8),
            "undecodable png data: PNG is 8-bit of colour type 0, not 16-bit grey as declared (not decoded)");
}

TEST(ImageCodec, AJpegOfManyScansIsRefusedAndAProgressiveOneDecodes) {
  const cv::Mat colour = cv::imread(test::sharedPath(kColour), cv::IMREAD_COLOR);
  ASSERT_FALSE(colour.empty());
  std::vector<uint8_t> progressive;
  ASSERT_TRUE(cv::imencode(".jpg", colour, progressive, {cv::IMWRITE_JPEG_PROGRESSIVE, 1}));
  EncodedImage jpeg{640, 480, ImageEncoding::kJpeg, PixelFormat::kBgr8, progressive};
  EXPECT_EQ(decodeImage(jpeg).size(), colour.size());
  // One of its scans again and again before the end marker, as a hostile publisher might.
  std::vector<std::size_t> starts;
  for (std::size_t i = 0; i + 1 < progressive.size(); ++i)
    if (progressive[i] == 0xFF && progressive[i + 1] == 0xDA) starts.push_back(i);
  ASSERT_GE(starts.size(), 3u);
  const std::vector<uint8_t> scan(progressive.begin() + static_cast<std::ptrdiff_t>(starts[1]),
                                  progressive.begin() + static_cast<std::ptrdiff_t>(starts[2]));
  jpeg.data.assign(progressive.begin(), progressive.end() - 2);
  for (int k = 0; k < 100; ++k) jpeg.data.insert(jpeg.data.end(), scan.begin(), scan.end());
  jpeg.data.insert(jpeg.data.end(), {0xFF, 0xD9});
  const std::string why = decodeError(jpeg);
  EXPECT_NE(why.find("scans, more than 64 (not decoded)"), std::string::npos) << why;
}

// OpenCV throws its own exception for some headers (here: over its pixel limit) instead of failing; the
// caller still gets an ImageError, so a process that skips bad frames skips this one too.
TEST(ImageCodec, OpenCvsOwnRefusalIsAnImageError) {
  EncodedImage depth{70000, 70000, ImageEncoding::kPng, PixelFormat::kMono16,
                     readFileBytes(test::sharedPath(kDepth))};
  setPngSize(depth.data, 70000, 70000);
  EXPECT_EQ(decodeError(depth).rfind("undecodable png data: OpenCV", 0), 0u) << decodeError(depth);
}

// A file far larger than any image (a 300 MB one listed in rgb.txt; 200 GB stopped capture with an unnamed
// bad_alloc) is refused by its size, named, before anything is allocated for it.
TEST(ImageCodec, AFileLargerThanAnyImageIsRefusedByItsSize) {
  const std::string path = test::scratchDir("huge_image_file") / "huge.jpg";
  {
    std::ofstream out(path, std::ios::binary);
    out.seekp(300LL << 20);  // sparse: no disk space taken
    out.put('\0');
  }
  try {
    readFileBytes(path);
    FAIL() << "read";
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": 300 MiB, larger than any image read (256 MiB)"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace bmp
