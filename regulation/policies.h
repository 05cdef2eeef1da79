// Regulation policies under a frame-time budget (Horvitz & Lengyel, "Perception, Attention, and
// Resources: A Decision-Theoretic Approach to Graphics Rendering", UAI 1997, section 7): choose
// one level of detail per object so that the summed rendering cost fits the budget and the summed
// expected perceptual cost is least. This is the multiple-choice knapsack problem (MCKP).
//
// The instance. Item j has options k (its levels of detail, index 0 the finest); option k costs
// cost[j][k] integer units (the study uses whole microseconds of predicted rendering time, rounded
// up, so that the dynamic programme below is exact) and leaves loss[j][k] expected perceptual cost
// (dimensionless, equations 4-7 of the paper; 0 at full detail). Every item must be drawn at some
// level, so the cheapest option of each item (its *base*; ties broken by the smaller loss) is
// paid first: the residual budget R = budget - sum of base costs is what the policies spend.
//
// Value. The quantity the knapsack maximises, and the one the factor-two guarantee is about, is
// the perceptual cost *saved over the all-base plan*:
//   value(plan) = sum_j loss[j][base_j] - sum_j loss[j][plan_j]  (>= 0 for a sensible plan).
// Expected perceptual cost = sum_j loss[j][base_j] - value, so minimising the one maximises the
// other; but ratios differ: the guarantee is value(OPT) <= 2 value(greedy), and the ratio of the
// expected costs loss(greedy) / loss(OPT) has no bound (OPT may reach loss 0).
//
// The greedy policy (the paper's "order sprites for re-rendering by Phi(S_i) [= gain / cost,
// equation 10] until reaching the computational deadline and compare the perceptual cost of this
// policy with the policy of rendering only the sprite with the highest marginal value"),
// generalised from the paper's two options (re-render or warp) to a chain of levels:
//   1. options whose extra cost over the base exceeds R are dropped (no plan can use them);
//   2. per item, the upgrades from the base are reduced to the upper convex hull of the points
//      (extra cost, gain) starting at (0, 0): the LP-efficient upgrades, whose increments have
//      strictly decreasing Phi = delta gain / delta cost; dominated and non-convex options are
//      never taken step by step (Sinha & Zoltners 1979);
//   3. all increments of all items, in decreasing Phi, are taken while they fit; an increment
//      that does not fit blocks the later increments of its item, and the scan goes on with the
//      other items (taking more only adds value);
//   4. best single item: the plan that spends R on one item alone, its largest gain option;
//   5. the better of 3 and 4 (by value).
// Why two: the LP relaxation of the instance of step 1 is solved by the increments of 3 taken in
// order up to the first that does not fit (the split increment, taken fractionally), so
//   value(OPT) <= value(LP) <= value(prefix) + gain of the split increment
//              <= value(prefix) + value(best single)        (the split option fits alone, step 1)
//              <= 2 max(value(step 3), value(step 4)).
// Without step 4 the ratio is unbounded: one item whose only upgrade costs the whole budget, of
// Phi just below a cheap small upgrade that greedy takes first (see policies_test.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::regulation {

struct Option {
  int64_t cost = 0;  // integer cost units (the study: microseconds, rounded up), >= 0
  double loss = 0;   // expected perceptual cost left when the item is drawn at this option, >= 0
};

struct Item {
  std::vector<Option> options;  // levels of detail, index 0 the finest; at least one
  double distance = 0;          // eye to object, metres (the distance-only baseline reads it)
};

struct Instance {
  std::vector<Item> items;
  int64_t budget = 0;  // cost units
};

struct Plan {
  std::vector<int> choice;  // option index per item
  int64_t cost = 0;         // sum of the chosen options' costs, cost units
  double loss = 0;          // sum of the chosen options' losses (expected perceptual cost)
  double value = 0;         // base loss - loss: perceptual cost saved over the all-base plan
  bool fits = true;         // cost <= budget (false only when even the all-base plan is over)
};

// Fills cost, loss, value and fits of `choice` on `instance`.
Plan evaluate(const Instance& instance, std::vector<int> choice);

// The all-base plan: every item at its cheapest option (ties: the smaller loss).
Plan base_plan(const Instance& instance);

// Greedy by Phi with the best-single-item check (steps 1-5 above): value >= value(OPT) / 2.
Plan greedy_plan(const Instance& instance);
// Steps 1-3 alone: the ordering by Phi without the check (no guarantee; for comparison).
Plan greedy_ratio_only_plan(const Instance& instance);
// Step 4 alone: the best plan that upgrades a single item.
Plan best_single_plan(const Instance& instance);

// The exact optimum by dynamic programming over the integer residual budget:
// best[w] = largest value of the items so far with extra cost <= w, O(options x R) time and
// items x (R + 1) bytes for the choices. Throws std::length_error when items x (R + 1) exceeds
// `max_cells` (the caller reports the optimum as not computed).
Plan optimal_plan(const Instance& instance, int64_t max_cells = 400'000'000);

// The exact optimum by enumerating every combination of options (least loss among those that
// fit; ties: the first in lexicographic order). Throws std::length_error above `max_plans`.
Plan brute_force_plan(const Instance& instance, int64_t max_plans = 2'000'000);

// Baseline: the same level k for every item (an item with fewer levels uses its last), the
// finest k whose plan fits; when none does, the all-base plan (each item's cheapest option: the
// coarsest level when costs fall with the level), which fits whenever any plan does.
Plan uniform_plan(const Instance& instance);

// Baseline: levels by distance bands, level = #{i >= 0 : s * 2^i < distance} (clamped to the
// item's last level): each doubling of the distance one level coarser. The band scale s is the
// largest for which the plan fits (candidates: where some item changes level); the all-base plan
// (as uniform) when none fits.
Plan distance_plan(const Instance& instance);

// The policies the study compares, in report order.
enum class Policy { kGreedy, kGreedyRatioOnly, kOptimal, kUniform, kDistance };
constexpr Policy kAllPolicies[] = {Policy::kGreedy, Policy::kGreedyRatioOnly, Policy::kOptimal,
                                   Policy::kUniform, Policy::kDistance};
const char* policy_name(Policy p);  // "greedy", "greedy_ratio_only", "optimal", "uniform", "distance"
Plan plan_with(Policy p, const Instance& instance);

}  // namespace ra::regulation
