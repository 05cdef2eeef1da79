#include "stats/change_points.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>

namespace ra::stats {
namespace {

struct Split {
  std::size_t at = 0;  // index into the segment
  double q = -1;
};

// The best split of `x` (one segment): Q(t) maximised over t in [m, n - m].
Split best_split(const std::vector<double>& x, std::size_t m) {
  const std::vector<double> q = split_divergences(x, m);
  Split best;
  for (std::size_t i = 0; i < q.size(); ++i)
    if (q[i] > best.q) best = {m + i, q[i]};
  return best;
}

struct Segment {
  std::size_t begin = 0, end = 0;
  Split split;
  double p_value = 1;
};

}  // namespace

std::vector<double> split_divergences(const std::vector<double>& x, std::size_t m) {
  const std::size_t n = x.size();
  if (m < 2 || n < 2 * m) return {};  // a side of one value has no pairs
  // Row sums of |x_i - x_j| below and above i, so that moving the split by one is O(n).
  std::vector<double> below(n, 0), above(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      const double d = std::fabs(x[i] - x[j]);
      (j < i ? below : above)[i] += j == i ? 0 : d;
    }
  double total = 0;  // sum over pairs i < j
  for (std::size_t i = 0; i < n; ++i) total += below[i];
  std::vector<double> out;
  double left = 0;   // pairs inside [0, t)
  double cross = 0;  // pairs i < t <= j
  for (std::size_t t = 1; t <= n - m; ++t) {
    // moving value t - 1 from the right side to the left
    left += below[t - 1];
    cross += above[t - 1] - below[t - 1];
    if (t < m) continue;
    const double a = double(t), b = double(n - t);
    const double right = total - left - cross;
    const double e = 2 * cross / (a * b) - left / (a * (a - 1) / 2) - right / (b * (b - 1) / 2);
    out.push_back(a * b / (a + b) * e);
  }
  return out;
}

std::vector<ChangePoint> e_divisive(const std::vector<double>& x, const ChangePointOptions& o) {
  if (o.min_segment < 2)
    throw std::invalid_argument("change points: min_segment must be at least 2");
  for (double v : x)
    if (!std::isfinite(v)) throw std::invalid_argument("change points: a value is not finite");
  std::mt19937_64 rng(o.seed);
  auto evaluate = [&](Segment& s) {
    const std::vector<double> part(x.begin() + long(s.begin), x.begin() + long(s.end));
    s.split = best_split(part, o.min_segment);
    s.p_value = 1;
    if (s.split.q < 0) return;
    std::vector<double> shuffled = part;
    int as_large = 0;
    for (int r = 0; r < o.permutations; ++r) {
      std::shuffle(shuffled.begin(), shuffled.end(), rng);
      as_large += best_split(shuffled, o.min_segment).q >= s.split.q;
    }
    s.p_value = double(1 + as_large) / double(1 + o.permutations);
  };
  std::vector<Segment> segments(1);
  segments[0].end = x.size();
  evaluate(segments[0]);
  std::vector<ChangePoint> out;
  for (;;) {
    // the segment whose best split diverges most
    std::size_t pick = segments.size();
    for (std::size_t i = 0; i < segments.size(); ++i)
      if (segments[i].split.q >= 0 &&
          (pick == segments.size() || segments[i].split.q > segments[pick].split.q))
        pick = i;
    if (pick == segments.size() || !(segments[pick].p_value < o.alpha)) break;
    const Segment s = segments[pick];
    const std::size_t at = s.begin + s.split.at;
    out.push_back({at, s.split.q, s.p_value});
    Segment left{s.begin, at, {}, 1}, right{at, s.end, {}, 1};
    evaluate(left);
    evaluate(right);
    segments[pick] = left;
    segments.push_back(right);
  }
  std::sort(out.begin(), out.end(),
            [](const ChangePoint& a, const ChangePoint& b) { return a.index < b.index; });
  return out;
}

}  // namespace ra::stats
