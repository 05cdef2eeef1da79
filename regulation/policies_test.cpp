// Tests of the regulation policies (policies.h) and random instances (random_instances.h).
#include "regulation/policies.h"

#include <gtest/gtest.h>

#include <random>

#include "regulation/random_instances.h"

namespace ra::regulation {
namespace {

RandomInstanceSettings tiny(uint64_t seed) {
  RandomInstanceSettings s;
  s.objects_min = 1;
  s.objects_max = 5;
  s.levels_min = 1;
  s.levels_max = 4;
  s.max_cost = 40;
  s.adversarial_every = 0;
  s.seed = seed;
  return s;
}

// The DP must be the exact optimum: compare it with enumeration on many tiny random instances
// (costs small enough that ties and exact fits happen often).
TEST(Policies, DynamicProgrammeEqualsBruteForceOnTinyInstances) {
  int compared = 0;
  for (uint64_t seed = 1; seed <= 4; ++seed)
    for (uint64_t i = 0; i < 500; ++i) {
      const Instance inst = random_instance(tiny(seed), i);
      const Plan dp = optimal_plan(inst);
      const Plan brute = brute_force_plan(inst);
      ASSERT_NEAR(dp.loss, brute.loss, 1e-9) << "seed " << seed << " instance " << i;
      ASSERT_TRUE(dp.fits);
      ASSERT_LE(dp.cost, inst.budget);
      ++compared;
    }
  EXPECT_EQ(compared, 2000);
}

// Brute force itself, on a hand-solved instance: budget 10; item 0 (7, 0) / (2, 5); item 1
// (6, 0) / (3, 4) / (1, 9). Plans that fit: (7,3): loss 4; (2,6): 5; (2,3): 9; (2,1): 14;
// (7,1): 9. Best: item 0 full, item 1 middle, loss 4.
TEST(Policies, BruteForceHandSolved) {
  Instance inst;
  inst.items = {{{{7, 0.0}, {2, 5.0}}, 1.0}, {{{6, 0.0}, {3, 4.0}, {1, 9.0}}, 2.0}};
  inst.budget = 10;
  const Plan p = brute_force_plan(inst);
  EXPECT_EQ(p.choice, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(p.loss, 4.0);
  EXPECT_EQ(p.cost, 10);
  EXPECT_DOUBLE_EQ(p.value, 14.0 - 4.0);  // base: (2, 1), loss 5 + 9
  EXPECT_EQ(optimal_plan(inst).choice, p.choice);
}

// The factor-two guarantee in the quantity it covers (value saved over the all-base plan), on
// random instances of the study's shape, adversarial ones included; and every plan fits.
TEST(Policies, GreedyWithinFactorTwoOfOptimalValue) {
  RandomInstanceSettings s;
  s.instances = 3000;
  s.adversarial_every = 7;
  s.brute_force_max_plans = 0;  // DP alone here (the test above checks it)
  double worst = 1;
  for (const InstanceComparison& c : run_random_instances(s)) {
    ASSERT_LE(c.value_optimal, 2 * c.value_greedy + 1e-9) << "instance " << c.index;
    ASSERT_GE(c.value_optimal + 1e-9, c.value_greedy) << "greedy beat the optimum: DP wrong";
    ASSERT_TRUE(c.within_budget) << "instance " << c.index;
    worst = std::max(worst, c.value_ratio);
  }
  // the tight instances approach 2: the bound is not vacuous on this sample
  EXPECT_GT(worst, 1.9);
  EXPECT_LE(worst, 2.0);
}

// Without the best-single-item check the ratio is unbounded: the trap instance.
TEST(Policies, RatioOnlyGreedyFailsTheTrapTheCheckFixesIt) {
  const Instance inst = adversarial_instance(1, 1000);
  const Plan ratio_only = greedy_ratio_only_plan(inst);
  const Plan greedy = greedy_plan(inst);
  const Plan opt = optimal_plan(inst);
  EXPECT_DOUBLE_EQ(ratio_only.value, 2.0);         // took the cheap upgrade of Phi 2 only
  EXPECT_DOUBLE_EQ(opt.value, 1900.0);             // the big upgrade alone
  EXPECT_GT(opt.value / ratio_only.value, 2.0);    // 950: no factor two without the check
  EXPECT_DOUBLE_EQ(greedy.value, opt.value);       // the check finds it
  EXPECT_LE(greedy.cost, inst.budget);
}

// Greedy skips non-convex options: item with options cost/gain over base (0,0) (2,1) (4,10):
// the hull goes straight to (4,10) (Phi 2.5), and the intermediate level is never a step.
TEST(Policies, GreedyUsesTheConvexHull) {
  Instance inst;
  inst.items = {{{{5, 0.0}, {3, 9.0}, {1, 10.0}}, 1.0}};
  inst.budget = 5;
  EXPECT_EQ(greedy_plan(inst).choice, std::vector<int>{0});
  inst.budget = 4;  // the full level no longer fits: the middle one does, by the single check
  EXPECT_EQ(greedy_plan(inst).choice, std::vector<int>{1});
  EXPECT_EQ(optimal_plan(inst).choice, std::vector<int>{1});
}

TEST(Policies, InfeasibleBudgetGivesTheBasePlanMarkedOver) {
  Instance inst;
  inst.items = {{{{5, 0.0}, {3, 1.0}}, 1.0}, {{{5, 0.0}, {3, 1.0}}, 2.0}};
  inst.budget = 5;  // bases cost 6
  for (Policy p : kAllPolicies) {
    const Plan plan = plan_with(p, inst);
    EXPECT_EQ(plan.choice, (std::vector<int>{1, 1})) << policy_name(p);
    EXPECT_FALSE(plan.fits) << policy_name(p);
  }
}

TEST(Policies, UniformAndDistanceBaselines) {
  // three items at 10, 20, 40 m, three levels: costs 8 / 4 / 1, losses 0 / 1 / 3
  Instance inst;
  for (double d : {10.0, 20.0, 40.0}) inst.items.push_back({{{8, 0.0}, {4, 1.0}, {1, 3.0}}, d});
  inst.budget = 24;
  EXPECT_EQ(uniform_plan(inst).choice, (std::vector<int>{0, 0, 0}));
  inst.budget = 23;
  EXPECT_EQ(uniform_plan(inst).choice, (std::vector<int>{1, 1, 1}));  // 12
  inst.budget = 11;
  EXPECT_EQ(uniform_plan(inst).choice, (std::vector<int>{2, 2, 2}));  // 3
  // distance: band edges s and 2s; the scales where a level changes are 40, 20, 10, 5.
  // s = 20: (0, 0, 1) = 20; s = 10: (0, 1, 2) = 13; s = 5: (1, 2, 2) = 6.
  inst.budget = 20;
  EXPECT_EQ(distance_plan(inst).choice, (std::vector<int>{0, 0, 1}));
  inst.budget = 16;  // (0, 1, 1) would fit but no single band scale gives it
  EXPECT_EQ(distance_plan(inst).choice, (std::vector<int>{0, 1, 2}));
  inst.budget = 12;
  EXPECT_EQ(distance_plan(inst).choice, (std::vector<int>{1, 2, 2}));
  inst.budget = 2;   // nothing fits: the coarsest, over budget
  EXPECT_FALSE(distance_plan(inst).fits);
  EXPECT_EQ(distance_plan(inst).choice, (std::vector<int>{2, 2, 2}));
}

// Instances unlike random_instance()'s (whose costs fall and losses rise with the level, the
// cheapest option last): options in any order, the cheapest mid-list, equal-cost ties, dominated
// options (costlier and lossier than another), zero-cost options and options dearer than the
// whole budget, as the scene's frames can give (each level's cost uses its own measured #pix).
Instance irregular_instance(std::mt19937_64& rng) {
  auto pick = [&](int lo, int hi) { return int(std::uniform_int_distribution<int>(lo, hi)(rng)); };
  Instance inst;
  const int n = pick(1, 5);
  int64_t sum_max = 0;
  for (int j = 0; j < n; ++j) {
    Item item;
    const int levels = pick(1, 5);
    int64_t max_cost = 0;
    for (int k = 0; k < levels; ++k) {
      Option o;
      const int kind = pick(0, 9);
      o.cost = kind == 0 ? 0 : kind == 1 ? 40 + pick(0, 20) : pick(0, 12);  // zero, above budget
      o.loss = kind == 2 ? 0.0 : double(pick(0, 8)) * (pick(0, 3) == 0 ? 0.5 : 1.0);  // ties
      if (k > 0 && pick(0, 4) == 0) o.cost = item.options[pick(0, k - 1)].cost;  // equal-cost tie
      if (k > 0 && pick(0, 4) == 0) {  // dominated by an earlier option
        const Option& d = item.options[pick(0, k - 1)];
        o.cost = d.cost + pick(0, 3);
        o.loss = d.loss + double(pick(0, 2));
      }
      item.options.push_back(o);
      max_cost = std::max(max_cost, o.cost);
    }
    std::shuffle(item.options.begin(), item.options.end(), rng);
    item.distance = pick(1, 100);
    sum_max += max_cost;
    inst.items.push_back(std::move(item));
  }
  inst.budget = pick(0, int(std::min<int64_t>(sum_max, 40)));
  return inst;
}

TEST(Policies, IrregularInstancesHaveTheShapesTheyClaim) {
  std::mt19937_64 rng(7);
  int shuffled = 0, cheapest_mid = 0, ties = 0, zero = 0, above = 0, dominated = 0;
  for (int i = 0; i < 2000; ++i) {
    const Instance inst = irregular_instance(rng);
    for (const Item& it : inst.items) {
      const auto& o = it.options;
      const int m = int(o.size());
      bool inc = false, dec = false;
      int cheapest = 0;
      for (int k = 0; k < m; ++k) {
        if (k > 0) (o[k].cost > o[k - 1].cost ? inc : dec) |= o[k].cost != o[k - 1].cost;
        if (o[k].cost < o[cheapest].cost) cheapest = k;
        zero += o[k].cost == 0;
        above += o[k].cost > inst.budget;
        for (int l = 0; l < m; ++l)
          if (l != k) {
            ties += o[k].cost == o[l].cost;
            dominated += o[k].cost >= o[l].cost && o[k].loss >= o[l].loss && (o[k].cost > o[l].cost || o[k].loss > o[l].loss);
          }
      }
      shuffled += inc && dec;
      cheapest_mid += cheapest > 0 && cheapest < m - 1;
    }
  }
  EXPECT_GT(shuffled, 100);
  EXPECT_GT(cheapest_mid, 100);
  EXPECT_GT(ties, 100);
  EXPECT_GT(zero, 100);
  EXPECT_GT(above, 100);
  EXPECT_GT(dominated, 100);
}

// On those instances: the DP equals brute force, greedy stays within the budget and within a
// factor two of the optimal value, and no heuristic beats the optimum.
TEST(Policies, IrregularInstancesDynamicProgrammeAndFactorTwo) {
  std::mt19937_64 rng(11);
  int feasible = 0, positive = 0;
  for (int i = 0; i < 20000; ++i) {
    const Instance inst = irregular_instance(rng);
    const Plan base = base_plan(inst);
    const Plan dp = optimal_plan(inst);
    const Plan brute = brute_force_plan(inst);
    const Plan greedy = greedy_plan(inst);
    ASSERT_NEAR(dp.loss, brute.loss, 1e-9) << "instance " << i;
    if (!base.fits) {
      ASSERT_FALSE(greedy.fits);
      continue;
    }
    ++feasible;
    positive += dp.value > 0;
    ASSERT_TRUE(dp.fits) << "instance " << i;
    ASSERT_LE(dp.cost, inst.budget);
    ASSERT_TRUE(greedy.fits) << "instance " << i;
    ASSERT_LE(greedy.cost, inst.budget);
    ASSERT_LE(dp.value, 2 * greedy.value + 1e-9) << "instance " << i;
    ASSERT_GE(greedy.value, -1e-12) << "instance " << i;
    for (Policy p : kAllPolicies) {
      const Plan plan = plan_with(p, inst);
      ASSERT_TRUE(plan.fits) << policy_name(p) << " instance " << i;
      ASSERT_LE(plan.value, dp.value + 1e-9) << policy_name(p) << " instance " << i;
    }
  }
  EXPECT_GT(feasible, 10000);
  EXPECT_GT(positive, 5000);
}

// An instance whose exact DP would exceed dp_max_cells is recorded as "optimum not computed"
// (NaN optimal values and ratios), never thrown out of compare_policies.
TEST(Policies, CompareRecordsAnOptimumTooLargeToCompute) {
  Instance inst;
  for (int j = 0; j < 4; ++j) inst.items.push_back({{{100000, 0.0}, {1, 5.0}}, 1.0});
  inst.budget = 200002;  // bases 4, two upgrades of 99999
  const InstanceComparison c = compare_policies(inst, 0, false, 100, /*dp_max_cells=*/1000);
  EXPECT_FALSE(c.optimum_computed);
  EXPECT_TRUE(std::isnan(c.value_optimal));
  EXPECT_TRUE(std::isnan(c.value_ratio));
  EXPECT_FALSE(c.brute_forced);
  EXPECT_TRUE(c.within_budget);
  EXPECT_GT(c.value_greedy, 0);
  EXPECT_NE(instances_csv({c}).find(",1,0\n"), std::string::npos);  // within_budget, optimum_computed
  const InstanceComparison ok = compare_policies(inst, 0, false, 100, 4'000'000);
  EXPECT_TRUE(ok.optimum_computed);
  EXPECT_DOUBLE_EQ(ok.value_optimal, 10.0);
}

// random_instance_dp_cells bounds every instance's table (items x (residual + 1)).
TEST(Policies, RandomInstanceDpCellsIsAnUpperBound) {
  for (int adv : {0, 3}) {
    RandomInstanceSettings s = tiny(5);
    s.adversarial_every = adv;
    s.objects_max = 3;
    s.max_cost = 7;
    const int64_t bound = random_instance_dp_cells(s);
    for (uint64_t i = 0; i < 300; ++i) {
      const Instance inst = random_instance(s, i);
      const int64_t residual = inst.budget - base_plan(inst).cost;
      ASSERT_LE(int64_t(inst.items.size()) * (residual + 1), bound) << "instance " << i;
      ASSERT_NO_THROW(optimal_plan(inst, bound));
    }
  }
}

TEST(Policies, RandomInstancesAreDeterministic) {
  RandomInstanceSettings s;
  const Instance a = random_instance(s, 17), b = random_instance(s, 17);
  ASSERT_EQ(a.items.size(), b.items.size());
  EXPECT_EQ(a.budget, b.budget);
  for (std::size_t j = 0; j < a.items.size(); ++j) {
    ASSERT_EQ(a.items[j].options.size(), b.items[j].options.size());
    for (std::size_t k = 0; k < a.items[j].options.size(); ++k) {
      EXPECT_EQ(a.items[j].options[k].cost, b.items[j].options[k].cost);
      // costs never increase with the level
      if (k > 0) {
        EXPECT_LE(a.items[j].options[k].cost, a.items[j].options[k - 1].cost);
      }
    }
  }
}

}  // namespace
}  // namespace ra::regulation
