#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "mrs_vpr/evaluation/progress_line.hpp"

namespace mrs_vpr {
namespace {

/// A clock the test moves by hand: no test depends on how fast the machine is.
struct FakeClock {
  double now = 100.0;
  ProgressLine::Clock clock() {
    return [this] { return now; };
  }
};

TEST(ProgressLine, FormatsDoneTotalRateAndTimeLeft) {
  // 400 of 1000 frames at 50 frames/s: 600 frames left, 12 s.
  EXPECT_EQ(ProgressLine::format("reference", "frames", 400, 1000, 50.0),
            "reference: 400/1000 frames (40%), 50 frames/s, 12.0 s left");
  // A slow run keeps a decimal of its rate; a long one gives minutes and hours.
  EXPECT_EQ(ProgressLine::format("queries", "queries", 3, 1000, 1.5),
            "queries: 3/1000 queries (0%), 1.5 queries/s, 11 min 05 s left");
  EXPECT_EQ(ProgressLine::format("bag", "images", 10, 100000, 1.0),
            "bag: 10/100000 images (0%), 1.0 images/s, 27 h 46 min left");
}

TEST(ProgressLine, LeavesOutWhatIsNotKnown) {
  // No rate known yet: no rate, no estimate.
  EXPECT_EQ(ProgressLine::format("reference", "frames", 0, 1000, 0.0), "reference: 0/1000 frames (0%)");
  EXPECT_EQ(ProgressLine::format("reference", "frames", 10, 1000, 0.0), "reference: 10/1000 frames (1%)");
  // Unknown total: count and rate only. Done: no time left.
  EXPECT_EQ(ProgressLine::format("reference", "frames", 300, 0, 150.0), "reference: 300 frames, 150 frames/s");
  EXPECT_EQ(ProgressLine::format("reference", "frames", 1000, 1000, 250.0),
            "reference: 1000/1000 frames (100%), 250 frames/s");
}

TEST(ProgressLine, FormatsDurations) {
  EXPECT_EQ(ProgressLine::formatDuration(0.04), "0.0 s");
  EXPECT_EQ(ProgressLine::formatDuration(59.94), "59.9 s");
  EXPECT_EQ(ProgressLine::formatDuration(125.0), "2 min 05 s");
  EXPECT_EQ(ProgressLine::formatDuration(3720.0), "1 h 02 min");
  EXPECT_EQ(ProgressLine::formatDuration(-1.0), "?");
}

TEST(ProgressLine, RewritesOneLineOnATerminalAtMostFiveTimesASecond) {
  FakeClock time;
  std::ostringstream out;
  ProgressLine progress("reference", "frames", 100, out, true, time.clock());
  progress.update(10);  // no time has passed: nothing written; the rate is counted from here
  EXPECT_EQ(out.str(), "");
  time.now += 0.5;
  progress.update(60);
  EXPECT_EQ(out.str(), "\rreference: 60/100 frames (60%), 100 frames/s, 0.4 s left");
  time.now += 0.1;  // within the period: not rewritten
  progress.update(70);
  EXPECT_EQ(out.str(), "\rreference: 60/100 frames (60%), 100 frames/s, 0.4 s left");
  time.now += 0.4;
  progress.update(100);
  progress.finish("of 64x32 px");
  // A shorter line is padded with spaces over the longer one before it; the final line ends with the
  // only newline.
  const std::string first = "reference: 60/100 frames (60%), 100 frames/s, 0.4 s left";
  const std::string second = "reference: 100/100 frames (100%), 90 frames/s";
  const std::string final_text = "reference: 100 frames of 64x32 px in 1.0 s, 100 frames/s";
  ASSERT_LT(second.size(), first.size());
  ASSERT_GT(final_text.size(), second.size());
  EXPECT_EQ(out.str(), "\r" + first + "\r" + second + std::string(first.size() - second.size(), ' ') + "\r" +
                           final_text + "\n");
}

TEST(ProgressLine, WritesAPlainLineEveryTenSecondsIntoAFile) {
  FakeClock time;
  std::ostringstream out;
  ProgressLine progress("bag", "images", 3840, out, false, time.clock());
  for (int done = 1; done <= 3840; ++done) {
    time.now += 1.0 / 128.0;  // 128 images/s for 30 s, in steps that add up exactly
    progress.update(done);
  }
  progress.finish();
  std::istringstream lines(out.str());
  std::string line;
  int count = 0;
  while (std::getline(lines, line)) {
    ++count;
    EXPECT_EQ(line.find('\r'), std::string::npos) << line;
  }
  // After 10, 20 and 30 s, then the final line.
  EXPECT_EQ(count, 4) << out.str();
  EXPECT_NE(out.str().find("bag: 1280/3840 images (33%), 128 images/s, 20.0 s left\n"), std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("bag: 3840 images in 30.0 s, 128 images/s\n"), std::string::npos) << out.str();
}

TEST(ProgressLine, ASlowFirstItemDoesNotSpoilTheEstimate) {
  FakeClock time;
  std::ostringstream out;
  ProgressLine progress("reference", "frames", 1000, out, false, time.clock());
  time.now += 5.0;  // the first frame waited for a library to load
  progress.update(1);
  for (int done = 2; done <= 641; ++done) {
    time.now += 1.0 / 128.0;  // then 128 frames/s
    progress.update(done);
  }
  // 10 s after the start: 640 frames in the 5 s since the first one, 359 left.
  EXPECT_EQ(out.str(), "reference: 641/1000 frames (64%), 128 frames/s, 2.8 s left\n");
}

TEST(ProgressLine, EndsAnUnfinishedLineSoThatAnErrorStartsOnItsOwn) {
  FakeClock time;
  std::ostringstream out;
  {
    ProgressLine progress("reference", "frames", 100, out, true, time.clock());
    time.now += 1.0;
    progress.update(10);
  }
  EXPECT_EQ(out.str().back(), '\n');
  std::ostringstream quiet;
  { ProgressLine progress("reference", "frames", 100, quiet, true, time.clock()); }
  EXPECT_EQ(quiet.str(), "");  // nothing was written, so nothing to end
}

}  // namespace
}  // namespace mrs_vpr
