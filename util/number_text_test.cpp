// Tests of the number texts (number_text.h). Expected texts are CPython's printf-style formatting
// ("%.4g" % x, with /usr/bin/python3), not this code's.
#include "util/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "util/cell_text.h"
#include "util/fnv1a.h"
#include "util/json_number.h"

namespace ra::util {
namespace {

TEST(NumberText, FormatDoubleIsPrintf) {
  EXPECT_EQ(format_double("%.4g", 0.000123456), "0.0001235");
  EXPECT_EQ(format_double("%.4g", 1234567), "1.235e+06");
  EXPECT_EQ(format_double("%.2f", 2.0 / 3), "0.67");
  EXPECT_EQ(format_double("%+.1f%%", 3.14159), "+3.1%");
  EXPECT_EQ(format_double("%.3f", -0.0004), "-0.000");
  EXPECT_EQ(format_double("%.0f", 2.5), "2");  // round half to even, as printf
  EXPECT_EQ(format_double("%.5g", std::nan("")), "nan");
  EXPECT_EQ(format_double("%.4g", -std::numeric_limits<double>::infinity()), "-inf");
}

// A long text is never cut at a buffer's end.
TEST(NumberText, FormatDoubleNeverTruncates) {
  EXPECT_EQ(format_double("%.2f", 1e300).size(), 304u);
  EXPECT_EQ(fixed(1e300, 2).size(), 304u);
}

TEST(NumberText, SignificantIsPercentStarG) {
  EXPECT_EQ(significant(0.1, 6), "0.1");
  EXPECT_EQ(significant(1e-5, 6), "1e-05");
  EXPECT_EQ(significant(100000.0, 6), "100000");
  EXPECT_EQ(significant(1e6, 6), "1e+06");
  EXPECT_EQ(significant(1.0 / 3, 10), "0.3333333333");
  EXPECT_EQ(significant(123456, 4), "1.235e+05");
  EXPECT_EQ(significant(1.5, 4), "1.5");
  EXPECT_EQ(significant(30, 6), format_double("%g", 30));  // "%g" is 6 significant digits
}

TEST(NumberText, FixedIsPercentStarF) {
  EXPECT_EQ(fixed(2.0 / 3, 2), "0.67");
  EXPECT_EQ(fixed(128, 0), "128");
  EXPECT_EQ(fixed(-1.25, 1), "-1.2");  // 1.25 is exact: half to even
}

TEST(NumberText, GroupedPutsCommasBetweenThousands) {
  EXPECT_EQ(grouped(0), "0");
  EXPECT_EQ(grouped(999), "999");
  EXPECT_EQ(grouped(64000), "64,000");
  EXPECT_EQ(grouped(1900000), "1,900,000");
}

// The small spellings every writer shares: printf into a string of any length, the empty cell of a
// missing number, a JSON null read as "n/a", a 64-bit hash as 16 hex digits.
TEST(NumberText, SharedSpellingsOfMissingNumbersAndHashes) {
  EXPECT_EQ(format_text("%s has %d", "a", 3), "a has 3");
  EXPECT_EQ(format_text("%s", std::string(600, 'x').c_str()).size(), 600u);
  EXPECT_EQ(format_double_or_empty("%.1f", std::nan("")), "");
  EXPECT_EQ(format_double_or_empty("%.1f", INFINITY), "inf");
  EXPECT_EQ(full_precision_if_finite(-INFINITY), "");
  EXPECT_EQ(full_precision_if_finite(0.5), "0.5");
  EXPECT_EQ(json_number_text(nlohmann::json()), "n/a");
  EXPECT_EQ(json_number_text(nlohmann::json(1234567.0)), "1.235e+06");
  EXPECT_EQ(json_number_text(nlohmann::json(2), "%.2f"), "2.00");
  EXPECT_TRUE(finite_or_null(std::nan("")).is_null());
  EXPECT_EQ(finite_or_null(1.5), nlohmann::json(1.5));
  EXPECT_EQ(hex64(0xc0ffee), "0000000000c0ffee");
}

}  // namespace
}  // namespace ra::util
