// Where detections wait for their frames: matched by seq and stamp, bounded, never blocked by a forgery.
#include <gtest/gtest.h>

#include <chrono>
#include <future>
#include <thread>

#include "tracker/detection_book.hpp"

namespace bmp::tracker {
namespace {

FrameBoxes answer(int64_t utime, int boxes) {
  FrameBoxes f;
  f.utime = utime;
  f.boxes.resize(static_cast<std::size_t>(boxes));
  return f;
}

constexpr std::chrono::milliseconds kNoWait{0};

// The frame heard, then its answer, as the tracker node meets them.
std::string hearAndAdd(DetectionBook& book, int64_t seq, FrameBoxes boxes) {
  book.frameHeard(seq, boxes.utime);
  return book.add(seq, std::move(boxes));
}

TEST(DetectionBook, AnswerIsTakenOnceForItsSeqAndStamp) {
  DetectionBook book;
  book.add(7, answer(7000, 2));
  EXPECT_FALSE(book.take(7, 9999, kNoWait)) << "another stamp is another frame";
  const auto got = book.take(7, 7000, kNoWait);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->boxes.size(), 2u);
  EXPECT_FALSE(book.take(7, 7000, kNoWait)) << "taken answers are removed";
}

// Another publisher names the frame's seq with a wrong stamp, before and after the real answer: the frame
// still gets its own boxes.
TEST(DetectionBook, ForgedAnswerWithTheFramesSeqDoesNotHideTheRealOne) {
  DetectionBook book;
  book.add(12, answer(1, 0));
  book.add(12, answer(12000, 3));
  book.add(12, answer(2, 0));
  const auto got = book.take(12, 12000, kNoWait);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->boxes.size(), 3u);
}

TEST(DetectionBook, KeepsOnlyTheNewestAnswersAndCountsTheRest) {
  DetectionBook book(4);
  for (int64_t seq = 0; seq < 10; ++seq) book.add(seq, answer(seq * 1000, 1));
  EXPECT_EQ(book.size(), 4u);
  EXPECT_EQ(book.discarded(), 6);
  EXPECT_FALSE(book.take(5, 5000, kNoWait));
  EXPECT_TRUE(book.take(6, 6000, kNoWait));
  EXPECT_TRUE(book.take(9, 9000, kNoWait));
}

// Real time: the newest usable answer before a frame stands in for its own, which it leaves in the book.
TEST(DetectionBook, NewestBeforeAreCopiesOfTheNewestUsableEarlierAnswers) {
  DetectionBook book;
  hearAndAdd(book, 3, answer(3000, 1));
  hearAndAdd(book, 5, answer(5000, 2));
  FrameBoxes skipped = answer(6000, 0);
  skipped.usable = false;
  hearAndAdd(book, 6, skipped);
  hearAndAdd(book, 9, answer(9000, 4));  // after the frame: not a stand-in
  auto got = book.newestBefore(8, 0, 2);
  ASSERT_EQ(got.size(), 2u);
  EXPECT_EQ(got[0].utime, 5000) << "the skipped answer is no stand-in";
  EXPECT_EQ(got[1].utime, 3000);
  EXPECT_TRUE(book.take(5, 5000, kNoWait)) << "still there for its own frame";
  // Its frame took it on time; it is still the newest look at the scene for the frames after.
  got = book.newestBefore(8, 0, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].utime, 5000);
  EXPECT_EQ(book.newestBefore(8, 4, 2).size(), 1u) << "older than min_seq";
  EXPECT_TRUE(book.newestBefore(3, 0, 2).empty());
}

// The stand-ins are remembered for the last few answers only: memory stays bounded however long the run.
TEST(DetectionBook, RemembersOnlyTheNewestAnswersAsStandIns) {
  DetectionBook book;
  for (int64_t seq = 1; seq <= 10; ++seq) hearAndAdd(book, seq, answer(seq * 1000, 1));
  const auto got = book.newestBefore(100, 0, 100);
  ASSERT_EQ(got.size(), DetectionBook::kRecent);
  EXPECT_EQ(got.front().utime, 10000);
  EXPECT_EQ(got.back().utime, static_cast<int64_t>(10 - DetectionBook::kRecent + 1) * 1000);
}

// Another publisher's answers: for frames still to come they wait for their frames but stand in for none,
// so they cannot push the real stand-ins out; a second, different answer for a frame is refused, the first
// kept; the same answer again (a frame capture sent again, answered again) changes nothing.
TEST(DetectionBook, ForgedAnswersNeitherDisplaceStandInsNorReplaceTheFirst) {
  DetectionBook book;
  ASSERT_EQ(hearAndAdd(book, 5, answer(5000, 3)), "");
  for (int64_t seq = 6; seq < 6 + static_cast<int64_t>(DetectionBook::kRecent); ++seq)
    ASSERT_EQ(book.add(seq, answer(seq * 1000, 0)), "");
  auto got = book.newestBefore(6, 0, 1);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0].boxes.size(), 3u) << "frame 5's answer still stands in";
  EXPECT_EQ(book.add(5, answer(5000, 3)), "") << "the same answer again";
  EXPECT_NE(book.add(5, answer(5000, 0)), "") << "a different one";
  const auto taken = book.take(5, 5000, kNoWait);
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->boxes.size(), 3u) << "the first answer kept";
  EXPECT_FALSE(book.take(5, 5000, kNoWait)) << "once";
}

// Lockstep capture sent a frame again and the detector answered it again: the frame took its answer, and
// the answer again is not kept to be taken a second time (as late boxes for the keyframe it made).
TEST(DetectionBook, AnAnswerForAFrameThatTookOneIsNotKept) {
  DetectionBook book;
  ASSERT_EQ(hearAndAdd(book, 5, answer(5000, 3)), "");
  ASSERT_TRUE(book.take(5, 5000, kNoWait));
  EXPECT_EQ(book.add(5, answer(5000, 3)), "") << "the same answer again is no news";
  EXPECT_FALSE(book.take(5, 5000, kNoWait)) << "and is not taken again";
  EXPECT_EQ(book.add(5, answer(5000, 1)), "a second, different answer for frame 5, which took its first");
  EXPECT_FALSE(book.take(5, 5000, kNoWait));
  EXPECT_EQ(book.size(), 0u);
  ASSERT_EQ(hearAndAdd(book, 6, answer(6000, 2)), "") << "the next frame's answer is kept";
  EXPECT_TRUE(book.take(6, 6000, kNoWait));
}

// A frame tracked without its answer (real time, not come yet) takes it late, once.
TEST(DetectionBook, AFrameThatTookNoneTakesItsAnswerLate) {
  DetectionBook book;
  book.frameHeard(5, 5000);
  EXPECT_FALSE(book.take(5, 5000, kNoWait));
  ASSERT_EQ(book.add(5, answer(5000, 3)), "");
  const auto late = book.take(5, 5000, kNoWait);
  ASSERT_TRUE(late);
  EXPECT_EQ(late->boxes.size(), 3u);
  EXPECT_EQ(book.add(5, answer(5000, 3)), "");
  EXPECT_FALSE(book.take(5, 5000, kNoWait)) << "once";
}

// A capture restarted on the same recording stamps its frames as before: they are new frames, and their
// answers are kept.
TEST(DetectionBook, AfterACaptureRestartTheReplayedFramesTakeTheirAnswersAgain) {
  DetectionBook book;
  for (int64_t seq = 0; seq < 10; ++seq) {
    ASSERT_EQ(hearAndAdd(book, seq, answer(seq * 1000, 1)), "");
    ASSERT_TRUE(book.take(seq, seq * 1000, kNoWait));
  }
  for (int64_t seq = 0; seq < 10; ++seq) {
    ASSERT_EQ(hearAndAdd(book, seq, answer(seq * 1000, 2)), "") << seq;
    const auto got = book.take(seq, seq * 1000, kNoWait);
    ASSERT_TRUE(got) << seq;
    EXPECT_EQ(got->boxes.size(), 2u);
  }
}

// Lockstep waits for the frame's answer; an answer that comes while it waits ends the wait.
TEST(DetectionBook, TakeWaitsForAnAnswerThatArrives) {
  DetectionBook book;
  auto waiter = std::async(std::launch::async, [&] { return book.take(3, 3000, std::chrono::seconds(30)); });
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  book.add(3, answer(3000, 1));
  const auto got = waiter.get();
  ASSERT_TRUE(got);
  EXPECT_EQ(got->boxes.size(), 1u);
}

// Once a frame is heard, answers naming its seq with another stamp are forgeries: refused, and any waiting
// are dropped, so they can neither stand in for later frames nor fill the book.
TEST(DetectionBook, OnceTheFrameIsHeardOtherStampsAreRefused) {
  DetectionBook book;
  EXPECT_EQ(book.add(12, answer(1, 5)), "");  // before the frame: kept apart, as any answer
  book.frameHeard(12, 12000);
  EXPECT_EQ(book.size(), 0u) << "the forgery waiting for frame 12 is dropped";
  EXPECT_TRUE(book.newestBefore(13, 0, 4).empty()) << "and is no stand-in";
  EXPECT_EQ(book.add(12, answer(2, 5)), "answer for frame 12 has stamp 2 us, the frame's is 12000");
  EXPECT_EQ(book.add(12, answer(12000, 3)), "");
  const auto got = book.take(12, 12000, kNoWait);
  ASSERT_TRUE(got);
  EXPECT_EQ(got->boxes.size(), 3u);
}

// A restarted capture (seq from 0 again) is heard as a new stream: the rule holds for its frames too.
TEST(DetectionBook, AfterACaptureRestartTheNewFramesAreTheHeardOnes) {
  DetectionBook book(4);
  for (int64_t seq = 100; seq < 110; ++seq) book.frameHeard(seq, seq * 1000);
  book.frameHeard(0, 7);
  EXPECT_NE(book.add(0, answer(8, 1)), "") << "another stamp for the new stream's frame 0";
  EXPECT_EQ(book.add(0, answer(7, 1)), "");
  EXPECT_EQ(book.add(105, answer(1, 1)), "") << "the old stream's frames are forgotten";
}

// The old stream's answers, waiting unused (real time leaves many), go with its frames: the new stream's
// answers, lower in seq, would otherwise be the first pushed out, and its stand-ins never found.
TEST(DetectionBook, AfterACaptureRestartTheOldStreamsAnswersMakeRoomForTheNew) {
  DetectionBook book(4);
  for (int64_t seq = 100; seq < 110; ++seq) {
    book.frameHeard(seq, seq * 1000);
    book.add(seq, answer(seq * 1000, 1));
  }
  const int64_t pushed_out = book.discarded();
  book.frameHeard(0, 7);
  EXPECT_EQ(book.discarded(), pushed_out + 4) << "the old stream's 4 waiting answers, unused";
  ASSERT_EQ(book.add(0, answer(7, 2)), "");
  book.frameHeard(1, 8);
  EXPECT_EQ(book.newestBefore(1, 0, 2).size(), 1u) << "frame 0's answer stands in for frame 1";
  const auto taken = book.take(0, 7, kNoWait);
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->boxes.size(), 2u);
}

// A flood of forged answers for frames not heard yet (varying stamps) holds at most kMaxPerSeq per seq, so
// it cannot push out the real answers waiting in the book.
TEST(DetectionBook, AFloodForOneFutureFrameIsBounded) {
  DetectionBook book(8);
  book.frameHeard(5, 5000);
  ASSERT_EQ(book.add(5, answer(5000, 1)), "");
  for (int64_t stamp = 0; stamp < 1000; ++stamp) book.add(6, answer(stamp, 0));
  EXPECT_EQ(book.size(), 1 + DetectionBook::kMaxPerSeq);
  EXPECT_EQ(book.discarded(), 0);
  EXPECT_TRUE(book.take(5, 5000, kNoWait)) << "the real answer is still there";
  EXPECT_NE(book.add(6, answer(6000, 1)), "") << "the seq is full until its frame is heard";
  book.frameHeard(6, 6000);
  EXPECT_EQ(book.add(6, answer(6000, 1)), "");
  EXPECT_TRUE(book.take(6, 6000, kNoWait));
}

}  // namespace
}  // namespace bmp::tracker
