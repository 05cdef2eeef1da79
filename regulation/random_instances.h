// Random multiple-choice knapsack instances for the greedy / optimal comparison (policies.h), and
// the per-instance comparison the study reports (instances.csv).
//
// An instance (a pure function of seed and index, util/counter_rng.h): n items, n uniform in
// [objects_min, objects_max]; item j has L levels, L uniform in [levels_min, levels_max]; the
// finest costs c0 ~ U{1..max_cost} units and each coarser level a factor U(0.25, 0.95) of the one
// before (rounded, >= 1, so costs never increase); the loss of level 0 is 0 and each coarser level
// adds weight * U(0, 1), weight ~ log-uniform over two decades (objects of very different
// importance), so chains may be non-convex. The budget is base cost + U(0, 1) x (finest cost -
// base cost). Every `adversarial_every`-th instance (0: none) is the trap of the single-item check:
// one item whose only upgrade costs the whole residual budget with a gain a bit below the residual
// budget's worth of Phi of many cheap upgrades that greedy takes first.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "regulation/policies.h"

namespace ra::regulation {

struct RandomInstanceSettings {
  int instances = 1000;
  int objects_min = 2, objects_max = 10;
  int levels_min = 2, levels_max = 5;
  int64_t max_cost = 300;     // cost units of the finest level, >= 1
  int adversarial_every = 10; // every k-th instance is adversarial; 0: none
  int64_t brute_force_max_plans = 20000;  // instances with at most this many plans are also brute forced
  uint64_t seed = 1;
  int64_t dp_max_cells = 400'000'000;  // the exact DP's table limit (regulation.dp_max_cells)
};

// The largest DP table (items x (residual budget + 1) cells, policies.h optimal_plan) that any
// instance of `s` can need: objects_max x (objects_max x max_cost + 1) for the random instances,
// and the trap / tight instances' (at most 6 items, residual <= 4 max(4, max_cost); 3 items,
// residual <= 8 max(4, max_cost)) when adversarial_every > 0.
int64_t random_instance_dp_cells(const RandomInstanceSettings& s);

Instance random_instance(const RandomInstanceSettings& s, uint64_t index);
// The trap instance: greedy by Phi alone gets about 1/k of the optimum's value.
Instance adversarial_instance(int k_small_items, int64_t budget);

struct InstanceComparison {
  uint64_t index = 0;
  bool adversarial = false;
  int items = 0, options = 0;
  int64_t budget = 0, residual = 0;
  double base_loss = 0;  // expected perceptual cost of the all-base plan
  // value (perceptual cost saved over the all-base plan) and loss of each policy
  double value_optimal = 0, value_greedy = 0, value_ratio_only = 0, value_single = 0;
  double value_uniform = 0, value_distance = 0;
  double loss_optimal = 0, loss_greedy = 0, loss_ratio_only = 0;
  // value(OPT) / value(policy); 1 when both are 0
  double value_ratio = 1, value_ratio_ratio_only = 1;
  // loss(greedy) / loss(OPT); NaN when loss(OPT) == 0 < loss(greedy), 1 when both 0
  double loss_ratio = 1;
  bool brute_forced = false;  // the DP was checked against brute force
  bool dp_matches_brute_force = true;
  bool within_budget = true;  // every policy's plan fits (given a feasible instance)
  // false: the exact DP's table would exceed dp_max_cells ("optimum not computed"): the optimal
  // value / loss and the ratios to it are NaN, and the DP is not checked against brute force
  bool optimum_computed = true;
};

InstanceComparison compare_policies(const Instance& inst, uint64_t index, bool adversarial,
                                    int64_t brute_force_max_plans,
                                    int64_t dp_max_cells = 400'000'000);

std::vector<InstanceComparison> run_random_instances(const RandomInstanceSettings& s);

std::string instances_csv(const std::vector<InstanceComparison>& rows);

}  // namespace ra::regulation
