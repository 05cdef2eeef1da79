// Regulation policies (policies.h; Horvitz & Lengyel 1997, section 7).
#include "regulation/policies.h"

#include <algorithm>
#include <cassert>
#include <limits>
#include <stdexcept>

namespace ra::regulation {
namespace {

int base_option(const Item& item) {
  int b = 0;
  for (int k = 1; k < int(item.options.size()); ++k) {
    const Option& o = item.options[k];
    const Option& best = item.options[b];
    if (o.cost < best.cost || (o.cost == best.cost && o.loss < best.loss)) b = k;
  }
  return b;
}

void check(const Instance& instance) {
  for (const Item& item : instance.items) {
    if (item.options.empty()) throw std::invalid_argument("an item without options");
    for (const Option& o : item.options)
      if (o.cost < 0 || !(o.loss >= 0)) throw std::invalid_argument("an option with cost < 0 or loss < 0");
  }
}

struct Bases {
  std::vector<int> option;
  int64_t cost = 0;
  double loss = 0;
};

Bases bases_of(const Instance& instance) {
  check(instance);
  Bases b;
  for (const Item& item : instance.items) {
    const int k = base_option(item);
    b.option.push_back(k);
    b.cost += item.options[k].cost;
    b.loss += item.options[k].loss;
  }
  return b;
}

// One LP-efficient increment of an item's upgrade chain (step 2).
struct Increment {
  int item = 0, step = 0;  // step s moves the item from hull point s to s + 1
  int option = 0;          // the option at hull point s + 1
  int64_t dcost = 0;       // > 0
  double dgain = 0;        // > 0
};

// Per item, the upper convex hull of (extra cost, gain) over options with extra cost <= residual
// and positive gain, starting at the base (0, 0); returns its increments in order.
std::vector<Increment> hull_increments(const Instance& instance, const Bases& b, int64_t residual) {
  std::vector<Increment> out;
  for (int j = 0; j < int(instance.items.size()); ++j) {
    const Item& item = instance.items[j];
    const Option& base = item.options[b.option[j]];
    struct P { int64_t c; double g; int k; };
    std::vector<P> pts;
    for (int k = 0; k < int(item.options.size()); ++k) {
      const int64_t dc = item.options[k].cost - base.cost;
      const double g = base.loss - item.options[k].loss;
      if (k == b.option[j] || dc > residual || !(g > 0) || dc <= 0) continue;  // dc == 0: base is better
      pts.push_back({dc, g, k});
    }
    std::sort(pts.begin(), pts.end(), [](const P& a, const P& c) {
      return a.c != c.c ? a.c < c.c : a.g > c.g;
    });
    std::vector<P> hull = {{0, 0.0, b.option[j]}};
    for (const P& p : pts) {
      if (p.g <= hull.back().g) continue;  // dominated: costs more, gains no more
      // pop while the last hull point lies on or below the chord from its predecessor to p
      while (hull.size() >= 2) {
        const P& a = hull[hull.size() - 2];
        const P& m = hull.back();
        // slope(a, m) <= slope(a, p)  <=>  m not strictly above the chord
        if ((m.g - a.g) * double(p.c - a.c) <= (p.g - a.g) * double(m.c - a.c))
          hull.pop_back();
        else
          break;
      }
      hull.push_back(p);
    }
    for (int s = 0; s + 1 < int(hull.size()); ++s)
      out.push_back({j, s, hull[s + 1].k, hull[s + 1].c - hull[s].c, hull[s + 1].g - hull[s].g});
  }
  // decreasing Phi; ties by item then step (keeps each item's steps in order, deterministic)
  std::stable_sort(out.begin(), out.end(), [](const Increment& a, const Increment& c) {
    const double lhs = a.dgain * double(c.dcost), rhs = c.dgain * double(a.dcost);
    if (lhs != rhs) return lhs > rhs;
    if (a.item != c.item) return a.item < c.item;
    return a.step < c.step;
  });
  return out;
}

Plan infeasible_or_base(const Instance& instance, const Bases& b) {
  return evaluate(instance, b.option);
}

}  // namespace

Plan evaluate(const Instance& instance, std::vector<int> choice) {
  if (choice.size() != instance.items.size()) throw std::invalid_argument("plan size differs from the items");
  const Bases b = bases_of(instance);
  Plan p;
  for (std::size_t j = 0; j < choice.size(); ++j) {
    const Option& o = instance.items[j].options.at(choice[j]);
    p.cost += o.cost;
    p.loss += o.loss;
  }
  p.choice = std::move(choice);
  p.value = b.loss - p.loss;
  p.fits = p.cost <= instance.budget;
  return p;
}

Plan base_plan(const Instance& instance) { return evaluate(instance, bases_of(instance).option); }

Plan greedy_ratio_only_plan(const Instance& instance) {
  const Bases b = bases_of(instance);
  const int64_t residual = instance.budget - b.cost;
  if (residual < 0) return infeasible_or_base(instance, b);
  std::vector<int> choice = b.option;
  std::vector<int> next_step(instance.items.size(), 0);  // -1: blocked
  int64_t used = 0;
  for (const Increment& inc : hull_increments(instance, b, residual)) {
    if (next_step[inc.item] != inc.step) continue;  // blocked, or (never) out of order
    if (used + inc.dcost <= residual) {
      used += inc.dcost;
      choice[inc.item] = inc.option;
      ++next_step[inc.item];
    } else {
      next_step[inc.item] = -1;  // its later increments need this one
    }
  }
  Plan p = evaluate(instance, std::move(choice));
  assert(p.fits);
  return p;
}

Plan best_single_plan(const Instance& instance) {
  const Bases b = bases_of(instance);
  const int64_t residual = instance.budget - b.cost;
  if (residual < 0) return infeasible_or_base(instance, b);
  int best_j = -1, best_k = -1;
  double best_gain = 0;
  for (int j = 0; j < int(instance.items.size()); ++j) {
    const Item& item = instance.items[j];
    const Option& base = item.options[b.option[j]];
    for (int k = 0; k < int(item.options.size()); ++k) {
      const double gain = base.loss - item.options[k].loss;
      if (item.options[k].cost - base.cost <= residual && gain > best_gain) {
        best_gain = gain;
        best_j = j;
        best_k = k;
      }
    }
  }
  std::vector<int> choice = b.option;
  if (best_j >= 0) choice[best_j] = best_k;
  return evaluate(instance, std::move(choice));
}

Plan greedy_plan(const Instance& instance) {
  Plan by_ratio = greedy_ratio_only_plan(instance);
  Plan single = best_single_plan(instance);
  return single.value > by_ratio.value ? single : by_ratio;
}

Plan optimal_plan(const Instance& instance, int64_t max_cells) {
  const Bases b = bases_of(instance);
  const int64_t residual = instance.budget - b.cost;
  if (residual < 0) return infeasible_or_base(instance, b);
  const int64_t n = int64_t(instance.items.size());
  if (n > 0 && (residual + 1) > max_cells / n)
    throw std::length_error("dynamic programme too large: " + std::to_string(n) + " items x " +
                            std::to_string(residual + 1) + " budget units");
  for (const Item& item : instance.items)
    if (item.options.size() > 127) throw std::length_error("more than 127 options per item");
  const std::size_t width = std::size_t(residual) + 1;
  // best[w]: largest value of the items so far with extra cost <= w (0 with no upgrade: the base)
  std::vector<double> best(width, 0.0), next(width);
  std::vector<int8_t> choice(std::size_t(n) * width);
  for (int64_t j = 0; j < n; ++j) {
    const Item& item = instance.items[j];
    const Option& base = item.options[b.option[j]];
    int8_t* row = &choice[std::size_t(j) * width];
    for (std::size_t w = 0; w < width; ++w) {
      next[w] = best[w];
      row[w] = int8_t(b.option[j]);
    }
    for (int k = 0; k < int(item.options.size()); ++k) {
      if (k == b.option[j]) continue;
      const int64_t dc = item.options[k].cost - base.cost;
      const double g = base.loss - item.options[k].loss;
      if (!(g > 0) || dc > residual) continue;
      for (std::size_t w = std::size_t(dc); w < width; ++w) {
        const double v = best[w - std::size_t(dc)] + g;
        if (v > next[w]) {
          next[w] = v;
          row[w] = int8_t(k);
        }
      }
    }
    best.swap(next);
  }
  std::vector<int> plan(static_cast<std::size_t>(n));
  std::size_t w = width - 1;
  for (int64_t j = n - 1; j >= 0; --j) {
    const int k = choice[std::size_t(j) * width + w];
    plan[std::size_t(j)] = k;
    w -= std::size_t(instance.items[j].options[k].cost - instance.items[j].options[b.option[j]].cost);
  }
  return evaluate(instance, std::move(plan));
}

Plan brute_force_plan(const Instance& instance, int64_t max_plans) {
  const Bases b = bases_of(instance);
  if (instance.budget < b.cost) return infeasible_or_base(instance, b);
  int64_t plans = 1;
  for (const Item& item : instance.items) {
    plans *= int64_t(item.options.size());
    if (plans > max_plans) throw std::length_error("too many plans for brute force");
  }
  const std::size_t n = instance.items.size();
  std::vector<int> cur(n, 0), best;
  double best_loss = std::numeric_limits<double>::infinity();
  for (int64_t i = 0; i < plans; ++i) {
    int64_t cost = 0;
    double loss = 0;
    for (std::size_t j = 0; j < n; ++j) {
      cost += instance.items[j].options[cur[j]].cost;
      loss += instance.items[j].options[cur[j]].loss;
    }
    if (cost <= instance.budget && loss < best_loss) {
      best_loss = loss;
      best = cur;
    }
    for (std::size_t j = n; j-- > 0;) {  // odometer, last item fastest
      if (++cur[j] < int(instance.items[j].options.size())) break;
      cur[j] = 0;
    }
  }
  return evaluate(instance, best);
}

Plan uniform_plan(const Instance& instance) {
  check(instance);
  int levels = 1;
  for (const Item& item : instance.items) levels = std::max(levels, int(item.options.size()));
  Plan p;
  for (int k = 0; k < levels; ++k) {
    std::vector<int> choice;
    for (const Item& item : instance.items) choice.push_back(std::min(k, int(item.options.size()) - 1));
    p = evaluate(instance, std::move(choice));
    if (p.fits) return p;
  }
  // none fits: the all-base plan (each item's cheapest option, which need not be its last level
  // when costs do not fall with the level); over budget only when no plan fits
  return base_plan(instance);
}

Plan distance_plan(const Instance& instance) {
  check(instance);
  int levels = 1;
  for (const Item& item : instance.items) levels = std::max(levels, int(item.options.size()));
  auto plan_at = [&](double s) {  // s = +inf: all finest
    std::vector<int> choice;
    for (const Item& item : instance.items) {
      int level = 0;
      for (int i = 0; i + 1 < levels; ++i)
        if (s * double(int64_t(1) << i) < item.distance) ++level;
      choice.push_back(std::min(level, int(item.options.size()) - 1));
    }
    return evaluate(instance, std::move(choice));
  };
  std::vector<double> scales = {std::numeric_limits<double>::infinity()};
  for (const Item& item : instance.items)
    for (int i = 0; i + 1 < levels; ++i) scales.push_back(item.distance / double(int64_t(1) << i));
  std::sort(scales.begin(), scales.end(), std::greater<double>());
  scales.erase(std::unique(scales.begin(), scales.end()), scales.end());
  for (double s : scales) {
    Plan p = plan_at(s);
    if (p.fits) return p;
  }
  // no band scale fits (costs need not fall with the level): the all-base plan, over budget only
  // when no plan fits
  return base_plan(instance);
}

const char* policy_name(Policy p) {
  switch (p) {
    case Policy::kGreedy: return "greedy";
    case Policy::kGreedyRatioOnly: return "greedy_ratio_only";
    case Policy::kOptimal: return "optimal";
    case Policy::kUniform: return "uniform";
    case Policy::kDistance: return "distance";
  }
  return "?";
}

Plan plan_with(Policy p, const Instance& instance) {
  switch (p) {
    case Policy::kGreedy: return greedy_plan(instance);
    case Policy::kGreedyRatioOnly: return greedy_ratio_only_plan(instance);
    case Policy::kOptimal: return optimal_plan(instance);
    case Policy::kUniform: return uniform_plan(instance);
    case Policy::kDistance: return distance_plan(instance);
  }
  throw std::invalid_argument("unknown policy");
}

}  // namespace ra::regulation
