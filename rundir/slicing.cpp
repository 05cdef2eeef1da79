// Deterministic cost-balanced slices (see the header).
#include "rundir/slicing.h"

#include <algorithm>
#include <charconv>
#include <map>

#include "rundir/shard_cost.h"
#include "util/errors.h"

namespace ra::rundir {
namespace {

// Slice of each shard id (0-based), and each slice's expected cost.
struct Assignment {
  std::map<std::string, int> slice_of;
  std::vector<double> cost;
};

Assignment assign(const std::vector<Shard>& shards, const Experiment& exp, int count) {
  std::map<int, const geometry::View*> views;
  for (const geometry::View& v : exp.views) views[v.id] = &v;
  Assignment a;
  a.cost.assign(static_cast<std::size_t>(count), 0.0);
  for (const Shard& s : largest_expected_cost_first(shards, exp)) {
    const auto v = views.find(s.view);
    const double c = v == views.end() ? 0 : expected_shard_cost_us(s, *v->second);
    const auto lightest = std::min_element(a.cost.begin(), a.cost.end());  // first of equals
    *lightest += c;
    a.slice_of[s.id()] = static_cast<int>(lightest - a.cost.begin());
  }
  return a;
}

}  // namespace

Slice parse_slice(const std::string& text) {
  const std::size_t slash = text.find('/');
  Slice s;
  const auto number = [&](std::size_t from, std::size_t to, int* out) {
    const char* b = text.data() + from;
    const char* e = text.data() + to;
    const auto [end, ec] = std::from_chars(b, e, *out);
    return from < to && ec == std::errc() && end == e;
  };
  if (slash == std::string::npos || !number(0, slash, &s.index) ||
      !number(slash + 1, text.size(), &s.count) || s.count < 1 || s.count > 100000 ||
      s.index < 1 || s.index > s.count) {
    throw util::UserError("--slice '" + text +
                          "': expected K/N with 1 <= K <= N <= 100000, e.g. 2/8 (the second of 8)");
  }
  return s;
}

std::vector<Shard> shards_of_slice(const std::vector<Shard>& shards, const Experiment& exp,
                                   const Slice& slice) {
  const Assignment a = assign(shards, exp, slice.count);
  std::vector<Shard> out;
  for (const Shard& s : shards)
    if (a.slice_of.at(s.id()) == slice.index - 1) out.push_back(s);
  return out;
}

std::vector<double> slice_costs(const std::vector<Shard>& shards, const Experiment& exp,
                                int count) {
  return assign(shards, exp, count).cost;
}

}  // namespace ra::rundir
