// The per-frame log (bmp-tracker --frame-log): its columns, its values, and lines on disk as they are
// written.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "shared_data.hpp"
#include "tracker/frame_log.hpp"

namespace bmp::tracker {
namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, '\t')) fields.push_back(field);
  return fields;
}

TrackResult sample() {
  TrackResult r;
  r.stamp = 1548339820.779820;
  r.seq = 27;
  r.state = TrackingState::kOk;
  r.num_keypoints = 1000;
  r.num_tracked = 321;
  r.pose_source = PoseSource::kReferenceKeyFrame;
  r.first_inliers = 40;
  r.num_dynamic = 15;
  r.num_excluded = 2;
  r.num_map_points = 801;
  r.num_keyframes = 3;
  r.reference_keyframe_id = 2;
  r.new_keyframe = KeyFramePose{3, r.stamp, SE3::Identity()};
  r.since_last_s = 0.1337;
  r.gap_recheck = GapRecheck::kReferenceTaken;
  r.processing_ms = 7.844;
  r.extract_ms = 5.2;
  r.dynamic_ms = 0.6;
  r.lock_wait_ms = 0.0;
  r.position_std_m = 0.01234;
  return r;
}

TEST(FrameLog, OneLinePerFrameUnderTheHeaderColumns) {
  const std::string path = (test::scratchDir("frame_log") / "frames.tsv").string();
  FrameLog log(path);
  log.append(sample(), {3, "stale"});
  TrackResult lost;
  lost.seq = 28;
  lost.state = TrackingState::kLost;
  lost.first_inliers = 12;
  log.append(lost, {0, "none"});

  std::ifstream in(path);
  std::string first, second;
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(first.rfind("# ", 0), 0u);
  EXPECT_EQ(second, std::string("# ") + FrameLog::columns());
  const std::vector<std::string> names = split(FrameLog::columns());
  const auto lines = test::readTsvRows(path);
  ASSERT_EQ(lines.size(), 2u);
  ASSERT_EQ(lines[0].size(), names.size());
  ASSERT_EQ(lines[1].size(), names.size());
  const std::vector<std::string> expected = {"1548339820.779820",
                                             "27",
                                             "OK",
                                             "1000",
                                             "321",
                                             "reference",
                                             "40",
                                             "15",
                                             "2",
                                             "801",
                                             "3",
                                             "2",
                                             "3",
                                             "133.7",
                                             "3",
                                             "stale",
                                             "reference_taken",
                                             "7.84",
                                             "5.20",
                                             "0.60",
                                             "0.00",
                                             "12.3"};
  for (std::size_t i = 0; i < names.size(); ++i) EXPECT_EQ(lines[0][i], expected[i]) << names[i];
  EXPECT_EQ(lines[1][2], "LOST");
  EXPECT_EQ(lines[1][5], "none");   // a frame not tracked has no pose source ...
  EXPECT_EQ(lines[1][6], "12");     // ... but says how many inliers its first pose kept
  EXPECT_EQ(lines[1][12], "-1");    // no keyframe made
  EXPECT_EQ(lines[1].back(), "-");  // and no position spread
}

// A process killed between frames leaves every line it wrote: each is on disk before append returns.
TEST(FrameLog, EachLineIsOnDiskAsSoonAsItIsWritten) {
  const std::string path = (test::scratchDir("frame_log_flush") / "frames.tsv").string();
  FrameLog log(path);
  for (int i = 0; i < 3; ++i) {
    TrackResult r = sample();
    r.seq = i;
    log.append(r, {});
    ASSERT_EQ(test::readTsvRows(path).size(),
              static_cast<std::size_t>(i + 1));  // read while the log is still open
  }
  EXPECT_EQ(test::readTsvRows(path)[2][15], "-");  // boxes unknown to the caller
}

TEST(FrameLog, AnUnwritablePathIsAnErrorNamingIt) {
  const std::string path = (test::scratchDir("frame_log_bad") / "no_such_folder" / "frames.tsv").string();
  try {
    FrameLog log(path);
    FAIL() << "no error for " << path;
  } catch (const FrameLogError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace bmp::tracker
