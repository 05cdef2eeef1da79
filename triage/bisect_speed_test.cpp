// Drawing time in a bisection: where a step's time lies between the ends' (place_step), the
// culprit lines, the plan giving up a group, and bisect.json keeping the times (the timing itself:
// tests/scripts/bisect-speed-test.sh, ctest bisect_speed, with real drawing).
#include "triage/bisect_speed.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>

#include "triage/bisect.h"
#include "triage/bisect_plan.h"
#include "triage/bisect_state.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_seal.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

// n primitives of times 10..100 us, `rounds` rounds; every time of round r multiplied by
// (1 + jitter_r) with jitter_r a fixed pattern of +-`jitter`, and by `factor`.
audit::RoundTimes times(double factor, int rounds, double jitter, int phase, std::size_t n = 40) {
  audit::RoundTimes t(n, std::vector<double>(rounds));
  for (std::size_t i = 0; i < n; ++i)
    for (int r = 0; r < rounds; ++r) {
      const double wobble = jitter * std::sin(1.7 * (r + phase) + 0.3);
      t[i][r] = (10.0 + 90.0 * double(i) / double(n - 1)) * factor * (1 + wobble);
    }
  return t;
}

TEST(PlaceStep, AStepDrawingAsEitherEndIsPlacedThereAndItsShareIsItsLogPosition) {
  // The bad ref draws twice as long. Without noise inside a round every paired log ratio of a
  // round is the same, so each round's Hodges-Lehmann estimate is exact: share = log f / log 2.
  const audit::RoundTimes good = times(1.0, 8, 0.05, 0), bad = times(2.0, 8, 0.05, 1);
  const StepTime as_good = place_step(good, times(1.0, 8, 0.05, 2), bad);
  EXPECT_EQ(as_good.place, TimePlace::kAsGood);
  EXPECT_EQ(as_good.repeats, 8);
  EXPECT_LT(as_good.share_high, 0.5);
  const StepTime as_bad = place_step(good, times(2.0, 8, 0.05, 3), bad);
  EXPECT_EQ(as_bad.place, TimePlace::kAsBad);
  EXPECT_GT(as_bad.share_low, 0.5);
  // The step draws exactly as the good ref in every round: ratio 1 and share 0, exactly.
  const StepTime same = place_step(good, good, times(2.0, 8, 0.0, 0));
  EXPECT_EQ(same.place, TimePlace::kAsGood);
  EXPECT_NEAR(same.ratio, 1.0, 1e-12);
  EXPECT_NEAR(same.share, 0.0, 1e-12);
  // Bad and step without jitter against a jitter-free good: a 1.5x step lies log 1.5 / log 2 of
  // the way (0.585), with an interval of zero width.
  const audit::RoundTimes flat_good = times(1.0, 6, 0.0, 0);
  const StepTime part = place_step(flat_good, times(1.5, 6, 0.0, 0), times(2.0, 6, 0.0, 0));
  EXPECT_NEAR(part.share, std::log(1.5) / std::log(2.0), 1e-9);
  EXPECT_NEAR(part.ratio, 1.5, 1e-9);
  EXPECT_EQ(part.place, TimePlace::kAsBad);
}

TEST(PlaceStep, AStepHalfWayOrTooNoisyIsUnknown) {
  const audit::RoundTimes good = times(1.0, 8, 0.05, 0), bad = times(2.0, 8, 0.05, 1);
  // The geometric middle: sqrt(2) times the good ref's time.
  const StepTime middle = place_step(good, times(std::sqrt(2.0), 8, 0.05, 2), bad);
  EXPECT_EQ(middle.place, TimePlace::kUnknown);
  EXPECT_LT(middle.share_low, 0.5);
  EXPECT_GT(middle.share_high, 0.5);
  // A step nearer the good ref, but rounds that disagree by +-60%.
  const StepTime noisy = place_step(good, times(1.2, 8, 0.6, 5), bad);
  EXPECT_EQ(noisy.place, TimePlace::kUnknown);
  // A faster bad ref is handled the same way, mirrored.
  const audit::RoundTimes fast = times(0.5, 8, 0.05, 1);
  EXPECT_EQ(place_step(good, times(0.5, 8, 0.05, 4), fast).place, TimePlace::kAsBad);
  EXPECT_EQ(place_step(good, times(1.0, 8, 0.05, 4), fast).place, TimePlace::kAsGood);
}

TEST(PlaceStep, NoIntervalWithoutTwoRoundsOrTimesOnEverySide) {
  const StepTime one = place_step(times(1, 1, 0, 0), times(2, 1, 0, 0), times(2, 1, 0, 0));
  EXPECT_EQ(one.place, TimePlace::kUnknown);
  EXPECT_NE(one.note.find("one round"), std::string::npos) << one.note;
  const StepTime none = place_step({}, {}, {});
  EXPECT_EQ(none.place, TimePlace::kUnknown);
  EXPECT_NE(none.note.find("no primitive"), std::string::npos) << none.note;
  const StepTime alike = place_step(times(1, 4, 0, 0), times(1, 4, 0, 0), times(1, 4, 0, 0));
  EXPECT_EQ(alike.place, TimePlace::kUnknown);
  EXPECT_NE(alike.note.find("alike"), std::string::npos) << alike.note;
}

TEST(SpeedCulpritLines, OneLinePerDirectionWithTheConfirmedRatio) {
  SpeedCulprit c;
  c.commit = std::string(40, 'a');
  c.subject = "llvmpipe: faster triangles";
  SpeedCulprit::Move tri{{geometry::Kind::kTriangle, 3}, audit::SpeedVerdict::kFaster, {}, ""};
  tri.confirmation.ratio = 0.775, tri.confirmation.low = 0.75, tri.confirmation.high = 0.8;
  SpeedCulprit::Move line{{geometry::Kind::kLine, 2}, audit::SpeedVerdict::kSlower, {}, ""};
  line.confirmation.ratio = 1.161, line.confirmation.low = 1.086, line.confirmation.high = 1.241;
  SpeedCulprit::Move point{{geometry::Kind::kPoint, 0}, audit::SpeedVerdict::kSlower, {}, "gone"};
  c.moves = {tri, line, point};
  const std::vector<std::string> lines = speed_culprit_lines(c);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], "first slower commit: " + c.commit +
                          " llvmpipe: faster triangles (lines, view group C: 1.161x [1.086, "
                          "1.241]; points, view group A: not confirmed, gone)");
  EXPECT_EQ(lines[1], "first faster commit: " + c.commit +
                          " llvmpipe: faster triangles (triangles, view group D: 0.775x [0.750, "
                          "0.800])");
  EXPECT_EQ(speed_culprit_lines(c, "egl-llvmpipe: ")[1].find("(egl-llvmpipe: triangles"),
            lines[1].find("(triangles"));
}

TEST(AttributionPlan, AForgottenLabelAsksForNoMoreBuilds) {
  AttributionPlan plan(8);
  plan.observe(0, {{"drawing time of lines, view group A", 1}});
  plan.observe(8, {{"drawing time of lines, view group A", 2}});
  plan.observe(4, {});  // unknown there: the plan asks for a neighbour
  ASSERT_TRUE(plan.next().has_value());
  EXPECT_NE(*plan.next(), 4u);
  plan.forget("drawing time of lines, view group A");
  EXPECT_FALSE(plan.next().has_value());
  EXPECT_TRUE(plan.changes().empty());
}

std::string temp_file() {
  return (fs::temp_directory_path() / ("bisect-speed-state-" + std::to_string(::getpid()) + ".json"))
      .string();
}

BisectState state_with_times() {
  BisectState st;
  st.inputs = {{"speed", {{"repeats", 8}}}};
  st.result.original_head = "main";
  BisectStep s;
  s.role = "step";
  s.commit = std::string(40, 'b');
  s.position = 2;
  StepTime t;
  t.group = {geometry::Kind::kTriangle, 1};
  t.place = TimePlace::kAsBad;
  t.ratio = 2.5, t.low = 2.25, t.high = 2.75, t.share = 0.98;
  t.share_low = std::nan(""), t.share_high = 1.1, t.repeats = 16;
  s.speed = {t};
  s.time_s = 3.5;
  st.result.steps = {s};
  SpeedAtEnds e;
  e.group = {geometry::Kind::kLine, 0};
  e.comparison.n = 60;
  e.comparison.repeats = 8;
  e.comparison.ratio = 0.5, e.comparison.low = 0.45, e.comparison.high = 0.55;
  e.comparison.control_ratio = std::nan("");
  e.comparison.verdict = audit::SpeedVerdict::kFaster;
  st.result.speed_ends = {e};
  return st;
}

TEST(BisectState, KeepsTheStepsTimesAndTheEndsVerdicts) {
  const std::string path = temp_file();
  save_bisect_state(path, state_with_times());
  const BisectState back = load_bisect_state(path);
  ASSERT_EQ(back.result.steps.size(), 1u);
  ASSERT_EQ(back.result.steps[0].speed.size(), 1u);
  const StepTime& t = back.result.steps[0].speed[0];
  EXPECT_EQ(t.group, (SpeedGroup{geometry::Kind::kTriangle, 1}));
  EXPECT_EQ(t.place, TimePlace::kAsBad);
  EXPECT_DOUBLE_EQ(t.ratio, 2.5);
  EXPECT_TRUE(std::isnan(t.share_low));
  EXPECT_EQ(t.repeats, 16);
  EXPECT_DOUBLE_EQ(back.result.steps[0].time_s, 3.5);
  ASSERT_EQ(back.result.speed_ends.size(), 1u);
  EXPECT_TRUE(back.result.speed_ends[0].moved());
  EXPECT_EQ(back.result.speed_ends[0].comparison.n, 60u);
  EXPECT_DOUBLE_EQ(back.result.speed_ends[0].comparison.high, 0.55);
  EXPECT_TRUE(std::isnan(back.result.speed_ends[0].comparison.control_ratio));
  fs::remove(path);
}

TEST(BisectState, AMistypedTimeIsNamedWithItsFileAndKey) {
  const std::string path = temp_file();
  for (const auto& [where, value] : std::vector<std::pair<std::string, nlohmann::json>>{
           {"place", "as fast"}, {"view_group", 26}, {"kind", "quad"}, {"ratio", "fast"}}) {
    nlohmann::json j = bisect_state_json(state_with_times());
    j["steps"][0]["speed"][0][where] = value;
    util::write_file_atomic(path, util::sealed(j).dump());
    try {
      load_bisect_state(path);
      ADD_FAILURE() << where << " = " << value << " was accepted";
    } catch (const util::UserError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(path + ": 'steps[0].speed[0]." + where + "'"), std::string::npos) << m;
    }
  }
  nlohmann::json j = bisect_state_json(state_with_times());
  j["speed_ends"][0]["verdict"] = "quicker";
  util::write_file_atomic(path, util::sealed(j).dump());
  EXPECT_THROW(load_bisect_state(path), util::UserError);
  fs::remove(path);
}

}  // namespace
}  // namespace ra::triage
