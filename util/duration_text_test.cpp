// The two spellings of a duration: a clock for progress lines and tables, words for summaries.
#include "util/duration_text.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ra::util {
namespace {

TEST(DurationText, ClockWithHoursMinutesSeconds) {
  EXPECT_EQ(duration_text(7), "0:00:07");
  EXPECT_EQ(duration_text(3723), "1:02:03");
  EXPECT_EQ(duration_text(59.6), "0:01:00");  // rounded to whole seconds first
  EXPECT_EQ(duration_text(90000), "25:00:00");  // hours are not wrapped into days
}

// A time left that cannot be told yet (negative, NaN) is a placeholder, not a number.
TEST(DurationText, ClockOfAnUnknownTime) {
  EXPECT_EQ(duration_text(-1), "--:--");
  EXPECT_EQ(duration_text(std::nan("")), "--:--");
  EXPECT_EQ(duration_text(INFINITY, "?"), "?");
}

TEST(DurationText, ElapsedTextReadsAsMinutesPastAMinute) {
  EXPECT_EQ(elapsed_text(0.42), "0.4 s");
  EXPECT_EQ(elapsed_text(9.94), "9.9 s");
  EXPECT_EQ(elapsed_text(9.96), "10 s");  // "10.0 s" would say more than it knows
  EXPECT_EQ(elapsed_text(13.2), "13 s");
  EXPECT_EQ(elapsed_text(161), "2 min 41 s");
  EXPECT_EQ(elapsed_text(3900), "1 h 05 min");
  EXPECT_EQ(elapsed_text(-1), "?");
  EXPECT_EQ(elapsed_text(std::nan("")), "?");
}

}  // namespace
}  // namespace ra::util
