// The detector against boxes labelled by hand on real images (labelled_boxes.txt).
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

#include "detector/yolo_decode.hpp"
#include "detector_test_util.hpp"

namespace bmp::detector {
namespace {

struct LabelledBox {
  std::string image;  // relative to the shared folder
  std::string label;
  cv::Rect2f box;
  std::vector<int> sizes;
  int line = 0;
};

std::vector<LabelledBox> readFixtures() {
  std::ifstream in(BMP_DETECTOR_FIXTURES);
  EXPECT_TRUE(in) << BMP_DETECTOR_FIXTURES;
  std::vector<LabelledBox> out;
  int line_no = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_no;
    if (line.empty() || line[0] == '#') continue;
    std::istringstream fields(line);
    LabelledBox b;
    float x1, y1, x2, y2;
    std::string sizes;
    if (!(fields >> b.image >> b.label >> x1 >> y1 >> x2 >> y2 >> sizes)) {
      ADD_FAILURE() << BMP_DETECTOR_FIXTURES << ":" << line_no << ": malformed";
      continue;
    }
    b.box = cv::Rect2f(x1, y1, x2 - x1, y2 - y1);
    std::istringstream list(sizes);
    for (std::string s; std::getline(list, s, ',');) b.sizes.push_back(std::stoi(s));
    b.line = line_no;
    out.push_back(b);
  }
  return out;
}

// Parameter: a model preset; a fixture applies when the preset's input size is in its "sizes" column.
class DetectorImages : public ::testing::TestWithParam<std::string> {};

TEST_P(DetectorImages, FindsEveryLabelledBoxWithClassAndLevel) {
  Detector detector(test::presetConfig(GetParam()), test::repoDynamicClasses());
  const int size = detector.config().input_size;
  const auto fixtures = readFixtures();
  ASSERT_GE(fixtures.size(), 20u);
  std::map<std::string, std::vector<Detection>> seen;  // one inference per image
  int checked = 0;
  for (const auto& f : fixtures) {
    if (std::find(f.sizes.begin(), f.sizes.end(), size) == f.sizes.end()) continue;
    SCOPED_TRACE(std::string(BMP_DETECTOR_FIXTURES) + ":" + std::to_string(f.line) + " " + f.image + " " +
                 f.label + " at " + std::to_string(size));
    auto it = seen.find(f.image);
    if (it == seen.end()) {
      const cv::Mat bgr = cv::imread(test::sharedPath(f.image), cv::IMREAD_COLOR);
      ASSERT_FALSE(bgr.empty()) << test::sharedPath(f.image);
      it = seen.emplace(f.image, detector.detect(bgr)).first;
    }
    const auto& detections = it->second;
    ++checked;
    if (f.label == "none-person") {
      for (const auto& d : detections)
        EXPECT_FALSE(d.label == "person" && d.score >= 0.5f) << "unexpected person, score " << d.score;
      continue;
    }
    const Detection* best = nullptr;
    float best_iou = 0.0f;
    for (const auto& d : detections) {
      if (d.label != f.label) continue;
      const float overlap = iou(d.box, f.box);
      if (overlap > best_iou) best_iou = overlap, best = &d;
    }
    if (best == nullptr) {
      ADD_FAILURE() << "no " << f.label << " detected";
      continue;
    }
    EXPECT_GE(best_iou, 0.5f) << "best " << f.label << " box IoU " << best_iou;
    const DynamicLevel expected = f.label == "person" ? DynamicLevel::kHigh : DynamicLevel::kLow;
    EXPECT_EQ(best->level, expected);
    EXPECT_EQ(best->class_id, f.label == "person" ? 0 : 62);
  }
  EXPECT_GE(checked, 20);
}

INSTANTIATE_TEST_SUITE_P(Models, DetectorImages,
                         ::testing::Values("yolov5n-320", "yolov5n-640", "yolo-fastest-xl"),
                         [](const auto& info) {
                           std::string name = info.param;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

TEST(DetectorModelNames, NamesComeFromTheModelFiles) {
  EXPECT_EQ(Detector(test::presetConfig("yolo-fastest-xl"), test::repoDynamicClasses()).modelName(),
            "yolo-fastest-1.1-xl_320");
  EXPECT_EQ(Detector(test::presetConfig("yolov5n-320"), test::repoDynamicClasses()).modelName(),
            "yolov5n_coco_320");
}

}  // namespace
}  // namespace bmp::detector
