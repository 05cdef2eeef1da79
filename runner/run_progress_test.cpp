// progress.json and `status --json` say null for a time left that is not known, never -1.
#include "runner/run_progress.h"

#include <gtest/gtest.h>

#include "runner/run_status.h"

namespace ra::runner {
namespace {

TEST(RunProgress, AnUnknownTimeLeftIsNullAndReadsBackAsUnknown) {
  RunProgress p;  // no rate yet
  const nlohmann::json j = to_json(p);
  ASSERT_TRUE(j.contains("left_s"));
  EXPECT_TRUE(j.at("left_s").is_null()) << j.dump();
  EXPECT_LT(run_progress_from_json(j).left_s, 0);
  p.left_s = 100;
  EXPECT_EQ(to_json(p).at("left_s"), 100.0);
  EXPECT_EQ(run_progress_from_json(to_json(p)).left_s, 100.0);
  p.left_s = 0;  // finished: known, zero
  EXPECT_EQ(to_json(p).at("left_s"), 0.0);
}

TEST(RunStatus, JsonSaysNullForAnUnknownTimeLeft) {
  RunStatus s;
  EXPECT_TRUE(to_json(s).at("left_s").is_null()) << to_json(s).dump();
  s.left_s = 12.5;
  EXPECT_EQ(to_json(s).at("left_s"), 12.5);
}

}  // namespace
}  // namespace ra::runner
