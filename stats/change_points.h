// Change points of a series (a nightly measurement): the nights where its distribution stepped,
// found by E-Divisive (Matteson and James, "A Nonparametric Approach for Multiple Change Point
// Analysis of Multivariate Data", JASA 109, 2014), the method Apache Otava (Hunter) and MongoDB's
// performance CI use on nightly benchmark series.
//
// - Divergence of a split of segment [a, b) at t: with X = x[a, t), Y = x[t, b),
//   Q(t) = |X||Y| / (|X| + |Y|) * (2 mean|x - y| - mean_{i<j}|x_i - x_j| - mean_{i<j}|y_i - y_j|),
//   the energy distance (alpha = 1) scaled by the sizes. It sees any change of distribution, not
//   only of the mean, and needs no model of the noise.
// - Binary segmentation: the split with the largest Q over all current segments is tested by a
//   permutation test (the segment's values shuffled `permutations` times, seeded: the answer is
//   reproducible), and kept when p = (1 + #{Q_perm >= Q}) / (1 + permutations) < alpha; then the
//   two halves are searched again, until no split is significant.
// - Every segment holds at least `min_segment` values: one noisy night cannot be a segment of its
//   own, so a change point is the night a step entered and stayed.
// This variant splits each segment at one point (the paper's kappa = the segment's end), as
// Otava does. O(n^2) per segment and permutation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace ra::stats {

struct ChangePointOptions {
  std::size_t min_segment = 3;  // values on each side of a change point, >= 2
  int permutations = 999;  // the smallest p-value is 1 / 1000
  double alpha = 0.01;          // significance of each split
  std::uint64_t seed = 2014;
};

struct ChangePoint {
  std::size_t index = 0;  // the first value after the change (1..n-1)
  double q = 0;           // the divergence statistic of the split (units of the data)
  double p_value = 1;     // the permutation test's
};

// Change points of `x` in increasing index order (none for fewer than 2 * min_segment values).
// Throws std::invalid_argument for non-finite values or min_segment < 2.
std::vector<ChangePoint> e_divisive(const std::vector<double>& x, const ChangePointOptions& options = {});

// Q(t) of the split of `x` (one whole segment) at every t in [min_segment, n - min_segment];
// element i is the split at min_segment + i. Exposed for tests.
std::vector<double> split_divergences(const std::vector<double>& x, std::size_t min_segment);

}  // namespace ra::stats
