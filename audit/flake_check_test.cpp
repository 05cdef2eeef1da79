// The flake check's batching, and re-rendering in child processes (the real program, RA_BINARY).
#include "audit/flake_check.h"

#include <gtest/gtest.h>

#include "audit/audit_testing.h"

namespace ra::audit {
namespace {

std::vector<std::pair<uint64_t, uint64_t>> ranges(const std::vector<RerenderBatch>& b) {
  std::vector<std::pair<uint64_t, uint64_t>> out;
  for (const auto& x : b) out.push_back({x.begin, x.end});
  return out;
}

// Neighbours closer than max_gap share a child; duplicates collapse; platforms, kinds and views
// never share one.
TEST(PlanRerender, MergesNeighboursWithinTheGap) {
  std::vector<RerenderRequest> req;
  for (uint64_t i : {40, 3, 5, 5, 20, 100})
    req.push_back({"reference", geometry::Kind::kPoint, 1, i});
  req.push_back({"reference", geometry::Kind::kLine, 1, 6});
  req.push_back({"faulty", geometry::Kind::kPoint, 1, 4});
  const auto plan = plan_rerender(req, {}, 15);
  ASSERT_EQ(plan.size(), 5u);
  EXPECT_EQ(plan[0].platform, "faulty");
  EXPECT_EQ(plan[1].kind, geometry::Kind::kPoint);
  EXPECT_EQ(ranges(plan)[1], (std::pair<uint64_t, uint64_t>{3, 21}));   // 3, 5, 20: gaps 1, 14
  EXPECT_EQ(ranges(plan)[2], (std::pair<uint64_t, uint64_t>{40, 41}));  // gap 19 from 21
  EXPECT_EQ(ranges(plan)[3], (std::pair<uint64_t, uint64_t>{100, 101}));
  EXPECT_EQ(plan[4].kind, geometry::Kind::kLine);
}

// A range never spans a primitive known to crash or hang.
TEST(PlanRerender, NeverSpansAKnownFailure) {
  KnownFailures avoid;
  avoid.add("reference", geometry::Kind::kPoint, 1, 8, 9);
  EXPECT_TRUE(avoid.hits("reference", geometry::Kind::kPoint, 1, 5, 10));
  EXPECT_FALSE(avoid.hits("reference", geometry::Kind::kPoint, 1, 9, 10));
  EXPECT_FALSE(avoid.hits("reference", geometry::Kind::kPoint, 2, 5, 10));
  std::vector<RerenderRequest> req = {{"reference", geometry::Kind::kPoint, 1, 2},
                                      {"reference", geometry::Kind::kPoint, 1, 6},
                                      {"reference", geometry::Kind::kPoint, 1, 12}};
  EXPECT_EQ(ranges(plan_rerender(req, avoid, 100)),
            (std::vector<std::pair<uint64_t, uint64_t>>{{2, 7}, {12, 13}}));
}

// Children render what run would have rendered; a crashing child is recorded in its batch.
TEST(Rerender, RendersInChildrenAndSurvivesACrash) {
  const std::string dir = audit::testing::fresh_dir("rerender");
  audit::testing::write_run(dir, audit::testing::experiment_text("\"reference\", \"faulty\"", 10, 10) +
                              "[faults]\ncrash = [4]\n");
  RerenderOptions o;
  o.run_dir = dir;
  o.program = RA_BINARY;
  o.jobs = 2;
  const RerenderResult r = rerender({{"reference", geometry::Kind::kPoint, 1, 2, 6, ""},
                                     {"faulty", geometry::Kind::kPoint, 1, 3, 5, ""}},
                                    o);
  ASSERT_EQ(r.batches.size(), 2u);
  EXPECT_EQ(r.batches[0].error, "");
  EXPECT_NE(r.batches[1].error.find("crashed (signal 11"), std::string::npos) << r.batches[1].error;
  EXPECT_EQ(r.hashes.size(), 4u);  // indices 2-5 of the reference platform
  EXPECT_TRUE(r.hashes.count({"reference", int(geometry::Kind::kPoint), 1, 5}));
}

}  // namespace
}  // namespace ra::audit
