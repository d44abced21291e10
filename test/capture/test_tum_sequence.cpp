#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>

#include <opencv2/imgcodecs.hpp>

#include "capture/pacer.hpp"
#include "capture/tum_sequence.hpp"
#include "capture/tum_source.hpp"
#include "shared_data.hpp"

namespace bmp::capture {
namespace {

namespace fs = std::filesystem;

// associate.py written out plainly (all pairs, sort, greedy): the reference for the fast version.
std::vector<std::pair<double, double>> referenceAssociate(const std::vector<double>& a,
                                                          const std::vector<double>& b, double max_diff) {
  std::vector<std::tuple<double, double, double>> pm;
  for (double x : a)
    for (double y : b)
      if (std::abs(x - y) < max_diff) pm.emplace_back(std::abs(x - y), x, y);
  std::sort(pm.begin(), pm.end());
  std::set<double> ua, ub;
  std::vector<std::pair<double, double>> out;
  for (auto& [d, x, y] : pm)
    if (!ua.count(x) && !ub.count(y)) {
      ua.insert(x);
      ub.insert(y);
      out.emplace_back(x, y);
    }
  std::sort(out.begin(), out.end());
  return out;
}

CameraIntrinsics bonnCamera() {
  CameraIntrinsics k;
  k.width = 640;
  k.height = 480;
  return k;
}

TEST(TumSequence, BonnIndexMatchesAssociatePy) {
  const SequenceIndex index = indexSequence(test::bonnDir());
  EXPECT_EQ(index.name, "rgbd_bonn_crowd");
  EXPECT_EQ(index.missing_files.size(), 6u);  // the dataset's known defect
  EXPECT_EQ(index.groundtruth.size(), 933u);
  std::vector<double> rgb, depth;
  for (const auto& e : readListFile(test::bonnDir() + "/rgb.txt")) rgb.push_back(e.stamp);
  for (const auto& e : readListFile(test::bonnDir() + "/depth.txt"))
    if (fs::exists(test::bonnDir() + "/" + e.path)) depth.push_back(e.stamp);
  const auto expected = referenceAssociate(rgb, depth, 0.02);
  ASSERT_EQ(index.frames.size(), expected.size());
  EXPECT_EQ(index.frames.size(), 927u);
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(index.frames[i].rgb_stamp, expected[i].first);
    EXPECT_EQ(index.frames[i].depth_stamp, expected[i].second);
  }
}

TEST(TumSequence, AssociationIsGreedyByDifference) {
  // 1.008-1.005 (0.003) is the smallest difference and is taken first, so 1.000 gets 1.015 (0.015) even
  // though 1.005 is its nearest stamp: greedy by difference, not nearest-neighbour per stamp.
  const auto m = associateStamps({1.000, 1.008}, {1.005, 1.015}, 0.02);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].first, 0u);
  EXPECT_EQ(m[0].second, 1u);
  EXPECT_EQ(m[1].second, 0u);
  EXPECT_TRUE(associateStamps({1.0}, {1.03}, 0.02).empty());
}

// Each stamp's candidates are its nearest few: a tolerance of any size (bmp-run checks a folder with an
// infinite one) or stamps packed closer than it no longer make every pair a candidate. 20000 x 20000 frames
// took 16 GB that way; here each frame pairs with its own depth image, 5 ms later.
TEST(TumSequence, AssociationOfLongListsWithAnyToleranceKeepsTheNearestPairs) {
  std::vector<double> rgb, depth;
  for (int i = 0; i < 20000; ++i) {
    rgb.push_back(1000.0 + i / 30.0);
    depth.push_back(1000.005 + i / 30.0);
  }
  for (const double tolerance : {0.02, 3600.0, std::numeric_limits<double>::infinity()}) {
    const auto m = associateStamps(rgb, depth, tolerance);
    ASSERT_EQ(m.size(), rgb.size()) << tolerance;
    std::size_t own = 0;
    for (std::size_t i = 0; i < m.size(); ++i) own += m[i].first == i && m[i].second == i;
    EXPECT_EQ(own, rgb.size()) << tolerance;
  }
}

TEST(TumSequence, MissingFolderAndListAreClearErrors) {
  try {
    indexSequence("/nonexistent/sequence");
    FAIL();
  } catch (const SequenceError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/sequence"), std::string::npos);
  }
  const auto dir = test::scratchDir("tum_no_depth_list");
  std::ofstream(dir / "rgb.txt") << "1.0 rgb/1.png\n";
  try {
    indexSequence(dir.string());
    FAIL();
  } catch (const SequenceError& e) {
    EXPECT_NE(std::string(e.what()).find("depth.txt"), std::string::npos) << e.what();
  }
}

TEST(TumSequence, MalformedListLineNamesFileAndLine) {
  const auto dir = test::scratchDir("tum_bad_list");
  std::ofstream(dir / "rgb.txt") << "# header\n1.0 rgb/1.png\nnot-a-stamp rgb/2.png\n";
  try {
    readListFile((dir / "rgb.txt").string());
    FAIL();
  } catch (const SequenceError& e) {
    EXPECT_NE(std::string(e.what()).find("rgb.txt:3"), std::string::npos) << e.what();
  }
  std::ofstream(dir / "depth.txt") << "1.0\n";
  EXPECT_THROW(readListFile((dir / "depth.txt").string()), SequenceError);
  // Relative stamps: each frame would be refused downstream, one by one.
  std::ofstream(dir / "rgb.txt") << "0.5 rgb/a.png\n-10.12574 rgb/b.png\n";
  try {
    readListFile((dir / "rgb.txt").string());
    ADD_FAILURE() << "a negative stamp accepted";
  } catch (const SequenceError& e) {
    EXPECT_NE(std::string(e.what()).find("rgb.txt:2: the stamp in '-10.12574 rgb/b.png' is negative"),
              std::string::npos)
        << e.what();
  }
}

// A folder of five real Bonn frames, then damaged in the ways real folders are.
class DamagedFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratchDir(::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_ / "rgb");
    fs::create_directories(dir_ / "depth");
    const SequenceIndex bonn = indexSequence(test::bonnDir());
    std::ofstream rgb(dir_ / "rgb.txt"), depth(dir_ / "depth.txt");
    for (std::size_t i = 100; i < 105; ++i) {
      const FramePair& f = bonn.frames[i];
      const std::string rn = "rgb/" + fs::path(f.rgb_path).filename().string();
      const std::string dn = "depth/" + fs::path(f.depth_path).filename().string();
      fs::copy_file(f.rgb_path, dir_ / rn);
      fs::copy_file(f.depth_path, dir_ / dn);
      rgb << std::fixed << f.rgb_stamp << " " << rn << "\n";
      depth << std::fixed << f.depth_stamp << " " << dn << "\n";
      depth_files_.push_back(dir_ / dn);
      rgb_files_.push_back(dir_ / rn);
    }
  }
  std::vector<CapturedFrame> playAll(SkipReport& skips, std::vector<std::string>& warnings) {
    TumSourceOptions options;
    options.warn = [&](const std::string& w) { warnings.push_back(w); };
    TumSource source(indexSequence(dir_.string()), bonnCamera(), options);
    std::vector<CapturedFrame> frames;
    while (auto f = source.next()) frames.push_back(std::move(*f));
    skips = source.skips();
    return frames;
  }
  fs::path dir_;
  std::vector<fs::path> depth_files_, rgb_files_;
};

// --frames 60 on Bonn used to report all 6 of the sequence's missing files as skipped, though one falls among
// those frames: each is counted by the range it falls in, so consecutive ranges share them out.
TEST(TumSequence, MissingFilesAreCountedForThePlayedFramesOnly) {
  const SequenceIndex index = indexSequence(test::bonnDir());
  const auto missing = [&](FrameSelection selection) {
    TumSourceOptions options;
    options.selection = selection;
    return TumSource(index, bonnCamera(), options).skips().missing_files;
  };
  EXPECT_EQ(missing({0, 60, 1}), 1);
  EXPECT_EQ(missing({60, -1, 1}), 5);
  EXPECT_EQ(missing({0, -1, 1}), 6);
  EXPECT_EQ(missing({300, 400, 1}), 0);
}

// Every n-th frame for any n: a step past the end ends the play (9223372036854775807 wrapped the cursor and
// read past the end of the frame list).
TEST(TumSequence, AnyStepPlaysTheFramesItSelects) {
  const SequenceIndex index = indexSequence(test::bonnDir());
  const auto total = static_cast<int64_t>(index.frames.size());
  for (const FrameSelection& selection : {FrameSelection{1, -1, INT64_MAX}, FrameSelection{0, -1, total},
                                          FrameSelection{5, 12, 3}, FrameSelection{3, -1, INT64_MAX - 2}}) {
    TumSourceOptions options;
    options.selection = selection;
    TumSource source(index, bonnCamera(), options);
    std::vector<int64_t> played;
    while (auto f = source.next()) played.push_back(f->index);
    EXPECT_EQ(static_cast<int64_t>(played.size()), source.size()) << selection.every;
    ASSERT_FALSE(played.empty());
    EXPECT_EQ(played.front(), selection.start);
  }
  EXPECT_EQ(selectedCount({5, 12, 3}, total), 3);  // 5, 8, 11
  EXPECT_EQ(selectedCount({1, -1, INT64_MAX}, total), 1);
  EXPECT_EQ(selectedCount({0, -1, 1}, total), total);
  EXPECT_EQ(selectedCount({total, -1, 1}, total), 0);
}

TEST_F(DamagedFolder, IntactFolderPlaysEveryFrameAsFileBytes) {
  SkipReport skips;
  std::vector<std::string> warnings;
  const auto frames = playAll(skips, warnings);
  ASSERT_EQ(frames.size(), 5u);
  EXPECT_EQ(skips.total(), 0);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(frames[0].color.encoding, ImageEncoding::kJpeg);
  EXPECT_EQ(frames[0].color.data, readFileBytes(rgb_files_[0].string()));  // forwarded, not re-encoded
  EXPECT_EQ(frames[0].depth.encoding, ImageEncoding::kPng);
}

// A listed file that is a symlink to itself is skipped as missing; it ended the whole run ("Too many levels
// of symbolic links" thrown from the check).
TEST_F(DamagedFolder, ASymlinkLoopIsSkippedAsMissing) {
  fs::remove(depth_files_[2]);
  fs::create_symlink(depth_files_[2].filename(), depth_files_[2]);
  SkipReport skips;
  std::vector<std::string> warnings;
  const auto frames = playAll(skips, warnings);
  EXPECT_EQ(frames.size(), 4u);
  EXPECT_EQ(skips.missing_files, 1);
}

TEST_F(DamagedFolder, CorruptMissingAndWrongSizeAreSkippedWithReasons) {
  // 1: corrupt PNG (a flipped bit), 2: missing depth file, 3: depth of the wrong size.
  std::vector<uint8_t> bytes = readFileBytes(depth_files_[1].string());
  bytes[bytes.size() / 2] ^= 0x10;
  std::ofstream(depth_files_[1], std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  fs::remove(depth_files_[2]);
  cv::imwrite(depth_files_[3].string(), cv::Mat(240, 320, CV_16UC1, cv::Scalar(1000)));
  SkipReport skips;
  std::vector<std::string> warnings;
  const auto frames = playAll(skips, warnings);
  EXPECT_EQ(frames.size(), 2u);  // frames 0 and 4
  EXPECT_EQ(skips.corrupt_files, 1);
  EXPECT_EQ(skips.missing_files, 1);
  EXPECT_EQ(skips.wrong_size, 1);
  ASSERT_EQ(warnings.size(), 3u);
  const auto mentions = [&](const std::string& what, const fs::path& file) {
    for (const auto& w : warnings)
      if (w.find(file.filename().string()) != std::string::npos && w.find(what) != std::string::npos)
        return true;
    return false;
  };
  EXPECT_TRUE(mentions("CRC", depth_files_[1]));
  EXPECT_TRUE(mentions("does not exist", depth_files_[2]));
  EXPECT_TRUE(mentions("320x240", depth_files_[3]));
}

TEST_F(DamagedFolder, DecodeVerificationCatchesWhatHeadersCannot) {
  // A JPEG whose entropy-coded middle is zeroed still has valid markers; only a decode can tell, and even
  // then libjpeg may recover. Colour replaced by a depth PNG is a format error in both modes.
  fs::copy_file(depth_files_[0], rgb_files_[0], fs::copy_options::overwrite_existing);
  SkipReport skips;
  std::vector<std::string> warnings;
  const auto frames = playAll(skips, warnings);
  EXPECT_EQ(frames.size(), 4u);
  EXPECT_EQ(skips.corrupt_files, 1);
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("8-bit"), std::string::npos) << warnings[0];
}

TEST_F(DamagedFolder, SelectionStartEndEvery) {
  TumSourceOptions options;
  options.selection = {1, 5, 2};
  TumSource source(indexSequence(dir_.string()), bonnCamera(), options);
  EXPECT_EQ(source.size(), 2);
  std::vector<int64_t> indices;
  while (auto f = source.next()) indices.push_back(f->index);
  EXPECT_EQ(indices, (std::vector<int64_t>{1, 3}));
}

// The ground truth is optional: one bad line in it (a motion-capture dropout written as nan) used to stop
// the whole folder from playing. The frames play, and the reason names the file and line.
TEST_F(DamagedFolder, AMalformedGroundTruthIsLeftOutNotFatal) {
  std::ofstream(dir_ / "groundtruth.txt") << "# timestamp tx ty tz qx qy qz qw\n"
                                          << "1548339822.0 0 0 0 0 0 0 1\n"
                                          << "1548339822.1 nan nan nan nan nan nan nan\n";
  const SequenceIndex index = indexSequence(dir_.string());
  EXPECT_EQ(index.frames.size(), 5u);
  EXPECT_TRUE(index.groundtruth.empty());
  EXPECT_NE(index.groundtruth_problem.find("groundtruth.txt:3"), std::string::npos)
      << index.groundtruth_problem;
}

// Lists whose paths were written relative to another folder leave every file missing; the error says so
// and shows one, instead of only "no colour/depth pair".
TEST_F(DamagedFolder, ListsOfFilesThatAreNotThereSaySo) {
  std::ofstream(dir_ / "depth.txt") << "1548339822.0 images/depth/1.png\n1548339822.1 images/depth/2.png\n";
  try {
    indexSequence(dir_.string());
    FAIL() << "expected SequenceError";
  } catch (const SequenceError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("0 depth files found"), std::string::npos) << what;
    EXPECT_NE(what.find("2 listed files do not exist, such as " + (dir_ / "images/depth/1.png").string()),
              std::string::npos)
        << what;
  }
}

// A recorder killed while writing leaves half a line at the end of rgb.txt: the frames before it play, and
// the warning names the file and line. A byte-order mark (a list saved by a Windows editor) is no error.
TEST_F(DamagedFolder, AListCutOffWhileWrittenPlaysWhatIsWhole) {
  std::string rgb;
  {
    std::ifstream in(dir_ / "rgb.txt");
    rgb.assign(std::istreambuf_iterator<char>(in), {});
  }
  std::ofstream(dir_ / "rgb.txt") << "\xEF\xBB\xBF" << rgb << "1548339999.3";  // a stamp, no file, no newline
  const SequenceIndex index = indexSequence(dir_.string());
  EXPECT_EQ(index.frames.size(), 5u);
  ASSERT_EQ(index.list_problems.size(), 1u);
  EXPECT_NE(index.list_problems[0].find("rgb.txt:6: the last line, '1548339999.3', has no end of line"),
            std::string::npos)
      << index.list_problems[0];
  // The same half line inside the file is damage, not a cut-off end: refused, naming the line.
  std::ofstream(dir_ / "rgb.txt") << "1548339999.3\n" << rgb;
  EXPECT_THROW(indexSequence(dir_.string()), SequenceError);
}

// Nanosecond stamps would pair (colour and depth share them) and play with every frame interval 1e9 times too
// long: refused, saying what the stamps look like and how to convert them.
TEST_F(DamagedFolder, StampsInNanosecondsAreRefusedWithAHint) {
  std::ofstream(dir_ / "rgb.txt") << "1548339822100000000 " << fs::relative(rgb_files_[0], dir_).string()
                                  << "\n";
  try {
    indexSequence(dir_.string());
    FAIL() << "expected SequenceError";
  } catch (const SequenceError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("rgb.txt:1: the stamp in '1548339822100000000"), std::string::npos) << what;
    EXPECT_NE(what.find("not in seconds (micro- or nanoseconds?)"), std::string::npos) << what;
  }
}

TEST(Pacer, RealtimeFollowsStampsAndFastDoesNotWait) {
  Pacer realtime(RateMode::kRealtime, 2.0);
  const auto t0 = std::chrono::steady_clock::now();
  realtime.waitUntilDue(10.0);
  realtime.waitUntilDue(10.2);  // due 0.1 s after the first at speed 2
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_GE(waited, 0.099);
  EXPECT_LT(waited, 5.0);  // not the 10 s of the stamps themselves (a loaded machine may add a little)
  Pacer fast(RateMode::kFast, 1.0);
  const auto t1 = std::chrono::steady_clock::now();
  fast.waitUntilDue(0.0);
  fast.waitUntilDue(100.0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), 5.0)
      << "fast waited for stamps 100 s apart";
  EXPECT_THROW(parseRateMode("slow"), std::invalid_argument);
}

// A long wait (a stamp far ahead, a slow speed) is slept in slices with a call between them, which stops it:
// one sleep to a stamp 1e10 s ahead hung capture, deaf to SIGINT (found by review). Speeds out of range
// (1e-300 overflowed the clock) are refused.
TEST(Pacer, ALongWaitIsSleptInSlicesAndCanBeStopped) {
  Pacer pacer(RateMode::kRealtime, 1.0);
  ASSERT_TRUE(pacer.waitUntilDue(0.0));
  EXPECT_GT(pacer.waitFor(1e10), 1e9);
  int calls = 0;
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_FALSE(pacer.waitUntilDue(1e10, [&] { return ++calls == 3; }));
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(calls, 3);
  EXPECT_GE(waited, 0.25);  // three slices of 100 ms
  EXPECT_LT(waited, 10.0);
  EXPECT_THROW(Pacer(RateMode::kRealtime, 1e-300), std::invalid_argument);
  EXPECT_THROW(Pacer(RateMode::kRealtime, 1e9), std::invalid_argument);
  EXPECT_EQ(Pacer(RateMode::kFast, 1.0).waitFor(1e10), 0.0);
}

}  // namespace
}  // namespace bmp::capture
