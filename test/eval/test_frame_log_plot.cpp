// bmp-eval's picture of the tracker's frame log (frames.tsv): read by column name, malformed lines named.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "eval/eval_error.hpp"
#include "eval/frame_log_plot.hpp"
#include "eval_test_util.hpp"
#include "shared_data.hpp"

namespace bmp::eval {

namespace {

// The header bmp-tracker writes (procs/tracker/frame_log.cpp).
const std::string kHeader =
    "# bmp-tracker frame log: one line per frame\n"
    "# stamp\tseq\tstate\tkeypoints\ttracked\tpose_source\tfirst_inliers\tdynamic\texcluded\tmap_points\t"
    "keyframes\treference_kf\tnew_kf\tsince_last_ms\tframes_missed\tboxes\tgap_recheck\ttrack_ms\t"
    "extract_ms\tdynamic_ms\tlock_wait_ms\n";

std::string frameLine(double stamp, int seq, const std::string& state, int tracked, const std::string& source,
                      int first, int missed, double ms) {
  return std::to_string(stamp) + "\t" + std::to_string(seq) + "\t" + state + "\t1000\t" +
         std::to_string(tracked) + "\t" + source + "\t" + std::to_string(first) +
         "\t0\t0\t900\t5\t1\t-1\t33.3\t" + std::to_string(missed) + "\town\tnone\t" + std::to_string(ms) +
         "\t5.0\t0.5\t0.0\n";
}

std::string write(const std::filesystem::path& dir, const std::string& name, const std::string& text) {
  const std::string path = (dir / name).string();
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST(evalFrameLog, ReadsEachFrameByColumnName) {
  const auto dir = bmp::test::scratchDir("frame_log_read");
  const std::string path = write(dir, "frames.tsv",
                                 kHeader + frameLine(100.0, 0, "OK", 0, "map_start", 0, 0, 30.0) +
                                     frameLine(100.1, 3, "OK", 250, "reference", 80, 2, 26.5) +
                                     frameLine(100.133, 4, "LOST", 0, "none", 12, 0, 40.0));
  const std::vector<FrameLogRow> rows = readFrameLog(path);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_DOUBLE_EQ(rows[1].stamp, 100.1);
  EXPECT_EQ(rows[1].tracked, 250);
  EXPECT_EQ(rows[1].pose_source, "reference");
  EXPECT_EQ(rows[1].first_inliers, 80);
  EXPECT_EQ(rows[1].frames_missed, 2);
  EXPECT_DOUBLE_EQ(rows[1].track_ms, 26.5);
  EXPECT_EQ(rows[2].state, "LOST");
}

TEST(evalFrameLog, AMalformedLineIsNamedByFileAndLine) {
  const auto dir = bmp::test::scratchDir("frame_log_bad");
  const std::string bad_number = write(
      dir, "a.tsv", kHeader + frameLine(1.0, 0, "OK", 10, "motion", 10, 0, 9.0) + "2.0\t1\tOK\t1000\tmany\n");
  try {
    readFrameLog(bad_number);
    FAIL() << "no EvalError";
  } catch (const EvalError& e) {
    EXPECT_NE(std::string(e.what()).find(bad_number + ":4"), std::string::npos) << e.what();
  }
  const std::string no_header = write(dir, "b.tsv", frameLine(1.0, 0, "OK", 10, "motion", 10, 0, 9.0));
  EXPECT_THROW(readFrameLog(no_header), EvalError);
  EXPECT_THROW(readFrameLog((dir / "missing.tsv").string()), EvalError);
}

// bmp-tracker's log since the position_std_mm column: read where there is a figure, none for '-'; a log from
// before the column (kHeader above) reads as before, with none.
TEST(evalFrameLog, ReadsThePositionStdWhereTheLogHasIt) {
  const auto dir = bmp::test::scratchDir("frame_log_std");
  std::string header = kHeader;
  header.insert(header.size() - 1, "\tposition_std_mm");
  auto line = [](const std::string& base, const std::string& std_mm) {
    return base.substr(0, base.size() - 1) + "\t" + std_mm + "\n";
  };
  const std::vector<FrameLogRow> rows =
      readFrameLog(write(dir, "frames.tsv",
                         header + line(frameLine(1.0, 0, "OK", 300, "motion", 280, 0, 9.0), "3.4") +
                             line(frameLine(1.1, 1, "LOST", 0, "none", 8, 0, 9.0), "-")));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_DOUBLE_EQ(rows[0].position_std_mm, 3.4);
  EXPECT_LT(rows[1].position_std_mm, 0.0);
  const std::vector<FrameLogRow> old =
      readFrameLog(write(dir, "old.tsv", kHeader + frameLine(1.0, 0, "OK", 300, "motion", 280, 0, 9.0)));
  ASSERT_EQ(old.size(), 1u);
  EXPECT_LT(old[0].position_std_mm, 0.0);
}

TEST(evalFrameLog, PlotIsAPngOfPlausibleSize) {
  const auto dir = bmp::test::scratchDir("frame_log_plot");
  std::string text = kHeader;
  for (int i = 0; i < 300; ++i)
    text += frameLine(10.0 + i / 30.0, i, i == 200 ? "LOST" : "OK", 240 + (i * 37) % 60,
                      i % 50 == 7 ? "reference" : "motion", 200 + (i * 13) % 50, i % 50 == 7 ? 3 : 0,
                      8.0 + (i % 11));
  const std::string png = (dir / "frames.png").string();
  plotFrameLog(png, readFrameLog(write(dir, "frames.tsv", text)), "test");
  ASSERT_TRUE(std::filesystem::exists(png));
  EXPECT_GT(std::filesystem::file_size(png), 10'000u);  // a blank canvas compresses to a few kB
  EXPECT_THROW(plotFrameLog("/nonexistent-dir/x.png", {}, ""), EvalError);
}

}  // namespace bmp::eval
