// Random instances and the policy comparison (random_instances.h).
#include "regulation/random_instances.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "util/cell_text.h"
#include "util/counter_rng.h"

namespace ra::regulation {
namespace {

constexpr uint64_t kInstanceStream = 0x7E6101;

// A two-option item: the base (cost `base`, loss `gain`) and the full level (cost base + dcost,
// loss 0).
Item two_level(int64_t base, int64_t dcost, double gain, double distance) {
  Item it;
  it.options = {{base + dcost, 0.0}, {base, gain}};
  it.distance = distance;
  return it;
}

}  // namespace

Instance adversarial_instance(int k_small_items, int64_t budget) {
  // k cheap upgrades of Phi 2 (cost 1, gain 2) and one upgrade of the whole residual budget with
  // Phi 1.9: greedy by Phi takes the k cheap ones first, then the big one no longer fits.
  Instance inst;
  for (int i = 0; i < k_small_items; ++i) inst.items.push_back(two_level(1, 1, 2.0, 10.0 + i));
  inst.items.push_back(two_level(1, budget, 1.9 * double(budget), 100.0));
  inst.budget = int64_t(inst.items.size()) + budget;  // bases + the big upgrade alone
  return inst;
}

// The classic tight case of greedy + best single: a small item of Phi 1 + eps and two of Phi 1
// costing W each, residual budget 2W: greedy gets W + 1 + eps, the best single W, OPT 2W.
static Instance tight_instance(int64_t w) {
  Instance inst;
  inst.items.push_back(two_level(1, 1, 1.01, 5.0));
  inst.items.push_back(two_level(1, w, double(w), 50.0));
  inst.items.push_back(two_level(1, w, double(w), 60.0));
  inst.budget = 3 + 2 * w;
  return inst;
}

Instance random_instance(const RandomInstanceSettings& s, uint64_t index) {
  util::CounterRng rng(s.seed, kInstanceStream, index);
  if (s.adversarial_every > 0 && index % uint64_t(s.adversarial_every) == uint64_t(s.adversarial_every - 1)) {
    const uint64_t which = index / uint64_t(s.adversarial_every);
    const int64_t big = std::max<int64_t>(4, rng.integer(std::max<int64_t>(4, s.max_cost / 2), std::max<int64_t>(4, s.max_cost * 4)));
    if (which % 2 == 0) return adversarial_instance(int(1 + which / 2 % 5), big);
    return tight_instance(big);
  }
  Instance inst;
  const int n = int(rng.integer(s.objects_min, s.objects_max));
  int64_t base_cost = 0, full_cost = 0;
  for (int j = 0; j < n; ++j) {
    Item item;
    const int levels = int(rng.integer(s.levels_min, s.levels_max));
    const double weight = std::pow(10.0, rng.uniform(-1.0, 1.0));
    int64_t cost = rng.integer(1, s.max_cost);
    double loss = 0;
    for (int k = 0; k < levels; ++k) {
      item.options.push_back({cost, loss});
      cost = std::max<int64_t>(1, int64_t(std::lround(double(cost) * rng.uniform(0.25, 0.95))));
      loss += weight * rng.uniform01();
    }
    item.distance = rng.uniform(1.0, 500.0);
    full_cost += item.options.front().cost;
    base_cost += item.options.back().cost;
    inst.items.push_back(std::move(item));
  }
  inst.budget = base_cost + int64_t(std::floor(rng.uniform01() * double(full_cost - base_cost + 1)));
  return inst;
}

int64_t random_instance_dp_cells(const RandomInstanceSettings& s) {
  const int64_t n = s.objects_max, mc = s.max_cost;
  int64_t cells = n * (n * mc + 1);  // residual <= sum of finest costs - sum of base costs < n mc
  if (s.adversarial_every > 0) {
    const int64_t big = 4 * std::max<int64_t>(4, mc);  // random_instance: big <= max(4, 4 mc)
    cells = std::max(cells, 6 * (big + 1));             // adversarial_instance(<= 5, big)
    cells = std::max(cells, 3 * (2 * big + 1));         // tight_instance(big)
  }
  return cells;
}

InstanceComparison compare_policies(const Instance& inst, uint64_t index, bool adversarial,
                                    int64_t brute_force_max_plans, int64_t dp_max_cells) {
  InstanceComparison c;
  c.index = index;
  c.adversarial = adversarial;
  c.items = int(inst.items.size());
  for (const Item& it : inst.items) c.options += int(it.options.size());
  c.budget = inst.budget;
  const Plan base = base_plan(inst);
  c.residual = inst.budget - base.cost;
  c.base_loss = base.loss;
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  Plan opt;
  try {
    opt = optimal_plan(inst, dp_max_cells);
  } catch (const std::length_error&) {  // the table would exceed dp_max_cells
    c.optimum_computed = false;
    opt.value = opt.loss = kNaN;
  }
  const Plan greedy = greedy_plan(inst);
  const Plan ratio_only = greedy_ratio_only_plan(inst);
  const Plan single = best_single_plan(inst);
  const Plan uniform = uniform_plan(inst);
  const Plan distance = distance_plan(inst);
  c.value_optimal = opt.value;
  c.value_greedy = greedy.value;
  c.value_ratio_only = ratio_only.value;
  c.value_single = single.value;
  c.value_uniform = uniform.value;
  c.value_distance = distance.value;
  c.loss_optimal = opt.loss;
  c.loss_greedy = greedy.loss;
  c.loss_ratio_only = ratio_only.loss;
  auto ratio = [](double num, double den) {
    if (den > 0) return num / den;
    return num > 0 ? std::numeric_limits<double>::infinity() : 1.0;
  };
  if (c.optimum_computed) {
    c.value_ratio = ratio(opt.value, greedy.value);
    c.value_ratio_ratio_only = ratio(opt.value, ratio_only.value);
    c.loss_ratio = opt.loss > 0 ? greedy.loss / opt.loss : (greedy.loss > 0 ? kNaN : 1.0);
  } else {
    c.value_ratio = c.value_ratio_ratio_only = c.loss_ratio = kNaN;
  }
  if (c.residual >= 0)
    c.within_budget = (!c.optimum_computed || opt.fits) && greedy.fits && ratio_only.fits && single.fits;
  int64_t plans = 1;
  for (const Item& it : inst.items) {
    plans *= int64_t(it.options.size());
    if (plans > brute_force_max_plans) break;
  }
  if (c.optimum_computed && plans <= brute_force_max_plans) {
    const Plan brute = brute_force_plan(inst, brute_force_max_plans);
    c.brute_forced = true;
    c.dp_matches_brute_force = std::abs(brute.loss - opt.loss) <= 1e-9 * std::max(1.0, brute.loss);
  }
  return c;
}

std::vector<InstanceComparison> run_random_instances(const RandomInstanceSettings& s) {
  std::vector<InstanceComparison> out;
  out.reserve(std::size_t(s.instances));
  for (int i = 0; i < s.instances; ++i) {
    const bool adv = s.adversarial_every > 0 && i % s.adversarial_every == s.adversarial_every - 1;
    out.push_back(compare_policies(random_instance(s, uint64_t(i)), uint64_t(i), adv,
                                   s.brute_force_max_plans, s.dp_max_cells));
  }
  return out;
}

std::string instances_csv(const std::vector<InstanceComparison>& rows) {
  std::ostringstream o;
  o << "instance,adversarial,items,options,budget,residual,base_loss,value_optimal,value_greedy,"
       "value_greedy_ratio_only,value_best_single,value_uniform,value_distance,loss_optimal,"
       "loss_greedy,loss_greedy_ratio_only,value_ratio_opt_over_greedy,"
       "value_ratio_opt_over_ratio_only,loss_ratio_greedy_over_opt,brute_forced,"
       "dp_matches_brute_force,within_budget,optimum_computed\n";
  for (const InstanceComparison& c : rows)
    o << c.index << ',' << int(c.adversarial) << ',' << c.items << ',' << c.options << ','
      << c.budget << ',' << c.residual << ',' << util::full_precision(c.base_loss) << ','
      << util::full_precision(c.value_optimal) << ',' << util::full_precision(c.value_greedy) << ','
      << util::full_precision(c.value_ratio_only) << ',' << util::full_precision(c.value_single)
      << ',' << util::full_precision(c.value_uniform) << ','
      << util::full_precision(c.value_distance) << ',' << util::full_precision(c.loss_optimal)
      << ',' << util::full_precision(c.loss_greedy) << ','
      << util::full_precision(c.loss_ratio_only) << ',' << util::full_precision(c.value_ratio)
      << ',' << util::full_precision(c.value_ratio_ratio_only) << ','
      << util::full_precision(c.loss_ratio) << ',' << int(c.brute_forced) << ','
      << int(c.dp_matches_brute_force) << ',' << int(c.within_budget) << ','
      << int(c.optimum_computed) << '\n';
  return o.str();
}

}  // namespace ra::regulation
