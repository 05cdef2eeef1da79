// The two ways a progress line is written: rewritten on a terminal, whole lines in a log.
#include "util/progress_line.h"

#include <gtest/gtest.h>

namespace ra::util {
namespace {

TEST(ProgressLine, RewrittenInPlaceOnATerminal) {
  const ProgressLine line(true);
  EXPECT_EQ(line.text_of_show("[3/89] tally_points"), "\r[3/89] tally_points\033[K");
}

// A log keeps every byte: no carriage return, no escape, one line per call.
TEST(ProgressLine, WholeLinesElsewhere) {
  const ProgressLine line(false);
  EXPECT_EQ(line.text_of_show("[3/89] tally_points"), "[3/89] tally_points\n");
}

// The terminal's line is ended once, and only when one was shown; a log's lines end themselves.
TEST(ProgressLine, EndsTheShownLineOnce) {
  for (const bool terminal : {true, false}) {
    ProgressLine line(terminal);
    testing::internal::CaptureStderr();
    line.end();  // nothing shown yet
    line.show("a");
    line.end();
    line.end();
    EXPECT_EQ(testing::internal::GetCapturedStderr(), terminal ? "\ra\033[K\n" : "a\n");
  }
}

}  // namespace
}  // namespace ra::util
