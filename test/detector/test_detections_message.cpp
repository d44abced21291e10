// The DETECTIONS contract both ways: what bmp-detector writes reads back the same, through LCM's own
// encoding, and a message no detector could have written is refused with the frame and the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "bmp/lcm/lcm_node.hpp"
#include "detector/lcm/detections_message.hpp"

namespace bmp::detector {
namespace {

FrameResult twoBoxes() {
  FrameResult r;
  r.seq = 41;
  r.utime = 1548339829896440;
  r.ok = true;
  r.width = 640;
  r.height = 480;
  r.total_ms = 18.8;
  Detection person;
  person.box = cv::Rect2f(272.5f, 30.0f, 140.0f, 450.0f);
  person.class_id = 0;
  person.label = "person";
  person.score = 0.91f;
  person.level = DynamicLevel::kHigh;
  Detection monitor;
  monitor.box = cv::Rect2f(0.0f, 100.25f, 120.0f, 80.0f);
  monitor.class_id = 62;
  monitor.label = "tv";
  monitor.score = 0.55f;
  monitor.level = DynamicLevel::kLow;
  r.detections = {person, monitor};
  return r;
}

// Through LCM's encoder and decoder (memq), as a subscriber receives it.
detections_t overTheWire(const detections_t& msg) {
  LcmNode node("memq://");
  std::vector<detections_t> got;
  node.subscribe<detections_t>("DETECTIONS",
                               [&](const detections_t& m, const ReceivedInfo&) { got.push_back(m); });
  node.publish("DETECTIONS", msg);
  node.handle(100);
  EXPECT_EQ(got.size(), 1u);
  return got.empty() ? detections_t{} : got.front();
}

TEST(DetectionsMessage, RoundTripKeepsFrameBoxesClassesAndLevels) {
  const FrameResult r = twoBoxes();
  const detections_t msg = overTheWire(toDetectionsMessage(r, "yolov5n_coco_320"));
  EXPECT_EQ(msg.num_detections, 2);
  EXPECT_EQ(msg.detections[0].dynamic_level, +detection_t::LEVEL_HIGH);
  EXPECT_EQ(msg.detections[1].dynamic_level, +detection_t::LEVEL_LOW);

  const FrameDetections back = fromDetectionsMessage(msg);
  EXPECT_EQ(back.seq, 41);
  EXPECT_EQ(back.utime, r.utime);
  EXPECT_EQ(back.model, "yolov5n_coco_320");
  EXPECT_EQ(back.width, 640);
  EXPECT_EQ(back.height, 480);
  EXPECT_NEAR(back.inference_ms, 18.8, 1e-5);
  ASSERT_EQ(back.detections.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const Detection& a = r.detections[i];
    const Detection& b = back.detections[i];
    EXPECT_EQ(b.box, a.box) << i;
    EXPECT_EQ(b.class_id, a.class_id) << i;
    EXPECT_EQ(b.label, a.label) << i;
    EXPECT_FLOAT_EQ(b.score, a.score) << i;
    EXPECT_EQ(b.level, a.level) << i;
  }
}

TEST(DetectionsMessage, NoBoxesIsAValidAnswer) {
  FrameResult r = twoBoxes();
  r.detections.clear();
  const FrameDetections back = fromDetectionsMessage(overTheWire(toDetectionsMessage(r, "m")));
  EXPECT_TRUE(back.detections.empty());
  EXPECT_EQ(back.seq, 41);
}

TEST(DetectionsMessage, SkippedFrameIsAnsweredWithItsReasonAndNoBoxes) {
  FrameResult r = twoBoxes();
  r.ok = false;
  r.error = "colour image: not a JPEG";
  const detections_t msg = overTheWire(toDetectionsMessage(r, "m"));
  EXPECT_EQ(msg.seq, 41);
  EXPECT_EQ(msg.skipped, "colour image: not a JPEG");
  EXPECT_EQ(msg.num_detections, 0);
  const FrameDetections back = fromDetectionsMessage(msg);
  EXPECT_EQ(back.skipped, "colour image: not a JPEG");
  EXPECT_TRUE(back.detections.empty());
  // Processed frames say nothing was skipped.
  EXPECT_TRUE(fromDetectionsMessage(toDetectionsMessage(twoBoxes(), "m")).skipped.empty());
}

// Each way another publisher's message can be wrong is refused, naming the frame and the reason.
TEST(DetectionsMessage, MalformedMessagesAreRefusedNamingFrameAndReason) {
  const detections_t good = toDetectionsMessage(twoBoxes(), "m");
  struct Case {
    const char* expect;
    void (*spoil)(detections_t&);
  };
  const std::vector<Case> cases = {
      {"unknown dynamic level 7", [](detections_t& m) { m.detections[0].dynamic_level = 7; }},
      {"not a box", [](detections_t& m) { m.detections[1].width = 0.0f; }},
      {"not a box", [](detections_t& m) { m.detections[0].x = std::numeric_limits<float>::quiet_NaN(); }},
      {"outside the 640x480 image", [](detections_t& m) { m.detections[0].y = 400.0f; }},
      {"outside [0, 1]", [](detections_t& m) { m.detections[1].score = 1.5f; }},
      {"image size 0x480", [](detections_t& m) { m.image_width = 0; }},
      {"skipped (busy) yet carries boxes", [](detections_t& m) { m.skipped = "busy"; }},
      {"class 80 is not a COCO index", [](detections_t& m) { m.detections[1].class_id = 80; }},
      {"class -1 is not a COCO index", [](detections_t& m) { m.detections[0].class_id = -1; }},
      {"301 boxes, over the 300 a detector may send",
       [](detections_t& m) {
         m.detections.resize(301, m.detections[0]);
         m.num_detections = 301;
       }},
  };
  for (const Case& c : cases) {
    detections_t bad = good;
    c.spoil(bad);
    try {
      fromDetectionsMessage(bad);
      ADD_FAILURE() << "accepted a message that should fail with: " << c.expect;
    } catch (const DetectionsMessageError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("frame seq 41"), std::string::npos) << what;
      EXPECT_NE(what.find(c.expect), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace bmp::detector
