// `renderaudit show`'s count of black pixels agrees with the record's violating_pixels: a line
// with two fragments in one column printed "black ... (2)" beside `violating_pixels 1`.
#include "triage/primitive_image.h"

#include <gtest/gtest.h>

namespace ra::triage {
namespace {

TEST(ForbiddenPixelsText, SaysTheRecordsCountAndHowManyAreMarkedWhenTheyDiffer) {
  EXPECT_EQ(forbidden_pixels_text(0, 0), "0");
  EXPECT_EQ(forbidden_pixels_text(3, 3), "3");
  const std::string column = forbidden_pixels_text(1, 2);
  EXPECT_EQ(column.rfind("1 (violating_pixels; 2 marked", 0), 0u) << column;
  EXPECT_EQ(forbidden_pixels_text(-1, 0), "0 marked; not judged");
}

}  // namespace
}  // namespace ra::triage
