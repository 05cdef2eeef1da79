// The bisection's verdicts and selection syntax (the loop itself: scripts/bisect-test.sh, ctest
// bisect_faulty, with real drawing).
#include "triage/bisect.h"

#include <gtest/gtest.h>

#include "util/errors.h"

namespace ra::triage {
namespace {

std::vector<BisectPrimitive> selection() {
  return {parse_primitive("line:5:721"), parse_primitive("line:6:6920"),
          parse_primitive("triangle:1:3")};
}

Drawing drawing(uint64_t a, uint64_t b, uint64_t c) {
  Drawing d;
  const auto s = selection();
  for (std::size_t i = 0; i < s.size(); ++i) {
    d.hashes[s[i].label()] = i == 0 ? a : i == 1 ? b : c;
    d.pixels[s[i].label()] = int64_t(i == 0 ? a : i == 1 ? b : c) * 10;
  }
  return d;
}

TEST(Bisect, PrimitivesAreNamedAsKindViewIndex) {
  const BisectPrimitive p = parse_primitive("line:5:721");
  EXPECT_EQ(p.kind, geometry::Kind::kLine);
  EXPECT_EQ(p.view, 5);
  EXPECT_EQ(p.index, 721u);
  EXPECT_EQ(p.label(), "line 721 of view 5");
  EXPECT_EQ(parse_primitive("triangles:2:0").kind, geometry::Kind::kTriangle);
  for (const char* bad : {"line:5", "line:0:1", "lines:5:-1", "quad:1:1", "line:5:1x",
                          "line:x:1", "line:5:99999999999999999999", ""})
    EXPECT_THROW(parse_primitive(bad), util::UserError) << bad;
}

TEST(Bisect, AStepIsGoodOrBadOnlyWhenEveryPrimitiveAgrees) {
  const auto s = selection();
  const Drawing good = drawing(1, 2, 3), bad = drawing(11, 12, 13);
  EXPECT_EQ(judge_drawing(s, drawing(1, 2, 3), good, bad).first, StepVerdict::kGood);
  EXPECT_EQ(judge_drawing(s, drawing(11, 12, 13), good, bad).first, StepVerdict::kBad);
  const auto [mixed, why] = judge_drawing(s, drawing(1, 12, 99), good, bad);
  EXPECT_EQ(mixed, StepVerdict::kSkip);
  EXPECT_EQ(why, "pixels are neither: 1 like the good ref, 1 like the bad ref, 1 like neither "
                 "(triangle 3 of view 1: 990 pixels (good ref 30, bad ref 130))");
  Drawing failed = drawing(1, 2, 3);
  failed.error = "lines 700-721 of view 5: crashed (signal 11)";
  EXPECT_EQ(judge_drawing(s, failed, good, bad),
            std::pair(StepVerdict::kSkip,
                      std::string("drawing failed: lines 700-721 of view 5: crashed (signal 11)")));
  Drawing missing = drawing(1, 2, 3);
  missing.hashes.erase("line 721 of view 5");
  EXPECT_EQ(judge_drawing(s, missing, good, bad).first, StepVerdict::kSkip);
  EXPECT_NE(judge_drawing(s, missing, good, bad).second.find("line 721 of view 5: not drawn"),
            std::string::npos);
}

}  // namespace
}  // namespace ra::triage
