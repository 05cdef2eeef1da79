#include "audit/distribution_audit.h"

#include <algorithm>
#include <numeric>
#include <set>

namespace ra::audit {
namespace {

using geometry::Kind;

struct Task {
  std::size_t pair;
  geometry::Kind kind;
  int view_group;
  std::size_t metric;
};

const analysis::ViewGroup* group_of(const analysis::RunRecords& run, const std::string& platform,
                                    geometry::Kind kind, int view_group) {
  const std::size_t p = platform_index(run, platform);
  return p < run.platforms.size() ? run.find_group(p, kind, view_group) : nullptr;
}

// The view groups of a kind present for either platform of a pair.
std::vector<std::pair<int, std::string>> groups_of_pair(const analysis::RunRecords& baseline,
                                                        const analysis::RunRecords& current,
                                                        const PlatformPair& pair,
                                                        geometry::Kind kind) {
  std::set<std::pair<int, std::string>> out;
  for (const auto& [run, platform] :
       {std::pair{&baseline, &pair.baseline}, std::pair{&current, &pair.current}}) {
    const std::size_t p = platform_index(*run, *platform);
    if (p == run->platforms.size()) continue;
    for (const analysis::ViewGroup* g : run->groups_of(p, kind))
      out.insert({g->view_group, g->label});
  }
  return {out.begin(), out.end()};
}

analysis::TestOutcome not_applicable(const std::string& reason) {
  analysis::TestOutcome o;
  o.reason = reason;
  return o;
}

DistributionComparison compare(const analysis::RunRecords& baseline,
                               const analysis::RunRecords& current, const PlatformPair& pair,
                               const Task& t, const std::string& label) {
  DistributionComparison c;
  c.pair = t.pair;
  c.kind = t.kind;
  c.view_group = t.view_group;
  c.label = label;
  c.metric = t.metric;
  const auto* gb = group_of(baseline, pair.baseline, t.kind, t.view_group);
  const auto* ga = group_of(current, pair.current, t.kind, t.view_group);
  const std::vector<double> before = gb ? gb->pooled(t.metric) : std::vector<double>{};
  const std::vector<double> after = ga ? ga->pooled(t.metric) : std::vector<double>{};
  c.n_before = before.size();
  c.n_after = after.size();
  const auto hf6 = stats::QuantileDefinition::kHyndmanFan6;
  if (!before.empty()) {
    const stats::Description d = analysis::describe_sorted(before, hf6);
    c.median_before = d.median, c.iqr_before = d.iqr;
  }
  if (!after.empty()) {
    const stats::Description d = analysis::describe_sorted(after, hf6);
    c.median_after = d.median, c.iqr_after = d.iqr;
  }
  const analysis::SampleComparison s = analysis::compare_samples({before, after});
  c.box_cox = s.box_cox;
  c.tests.push_back({"welch_t", "raw", s.raw.welch});
  c.tests.push_back({"levene_median", "raw", s.raw.levene_median});
  if (s.box_cox.applicable && !s.box_cox.shifted) {
    c.tests.push_back({"welch_t", "box_cox", s.transformed.welch});
    c.tests.push_back({"levene_median", "box_cox", s.transformed.levene_median});
  } else {
    const std::string why = s.box_cox.applicable ? "Box-Cox not applied: a value <= 0 (minimum " +
                                                       std::to_string(s.box_cox.pooled_min) +
                                                       "); the transform needs y > 0"
                                                 : "Box-Cox not applicable: " + s.box_cox.reason;
    if (s.box_cox.applicable) c.box_cox.applicable = false, c.box_cox.reason = why;
    c.tests.push_back({"welch_t", "box_cox", not_applicable(why)});
    c.tests.push_back({"levene_median", "box_cox", not_applicable(why)});
  }
  return c;
}

}  // namespace

bool DistributionComparison::significant() const {
  return std::any_of(tests.begin(), tests.end(),
                     [](const DistributionTest& t) { return t.significant; });
}

std::vector<double> holm_adjust(const std::vector<double>& p) {
  const std::size_t m = p.size();
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return p[a] < p[b]; });
  std::vector<double> out(m);
  double running = 0;
  for (std::size_t i = 0; i < m; ++i) {
    running = std::max(running, std::min(1.0, double(m - i) * p[order[i]]));
    out[order[i]] = running;
  }
  return out;
}

std::size_t platform_index(const analysis::RunRecords& run, const std::string& platform) {
  return std::size_t(std::find(run.platforms.begin(), run.platforms.end(), platform) -
                     run.platforms.begin());
}

DistributionAudit audit_distributions(const analysis::RunRecords& baseline,
                                      const analysis::RunRecords& current,
                                      const std::vector<PlatformPair>& pairs, double alpha,
                                      unsigned jobs) {
  DistributionAudit audit;
  audit.alpha = alpha;
  std::vector<Task> tasks;
  std::vector<std::string> labels;
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (geometry::Kind kind : analysis::kAllKinds)
      for (const auto& [group, label] : groups_of_pair(baseline, current, pairs[p], kind))
        for (std::size_t m = 0; m < analysis::kind_metrics(kind).size(); ++m) {
          tasks.push_back({p, kind, group, m});
          labels.push_back(label);
        }
  std::vector<DistributionComparison> results(tasks.size());
  util::run_in_parallel(tasks.size(), jobs, [&](std::size_t i) {
    results[i] = compare(baseline, current, pairs[tasks[i].pair], tasks[i], labels[i]);
  });
  for (auto& r : results)
    if (r.n_before + r.n_after > 0) audit.comparisons.push_back(std::move(r));

  // Holm over every defined test of the audit.
  std::vector<DistributionTest*> family;
  std::vector<double> p;
  for (auto& c : audit.comparisons)
    for (auto& t : c.tests)
      if (t.outcome.defined) family.push_back(&t), p.push_back(t.outcome.p_value);
  const std::vector<double> adjusted = holm_adjust(p);
  audit.family_size = family.size();
  for (std::size_t i = 0; i < family.size(); ++i) {
    family[i]->p_adjusted = adjusted[i];
    family[i]->significant = adjusted[i] < alpha;
    audit.significant += family[i]->significant;
  }
  return audit;
}

std::vector<std::pair<std::string, uint64_t>> class_counts(const analysis::VisibilityCounts& c) {
  std::vector<std::pair<std::string, uint64_t>> out;
  for (int v = 0; v < int(c.by_class.size()); ++v)
    out.push_back({metrics::visibility_name(metrics::Visibility(v)), c.by_class[std::size_t(v)]});
  out.push_back({"invalid", c.invalid});
  out.push_back({"crash", c.crash});
  out.push_back({"timeout", c.timeout});
  return out;
}

std::vector<ClassCountChange> compare_class_counts(const analysis::RunRecords& baseline,
                                                   const analysis::RunRecords& current,
                                                   const std::vector<PlatformPair>& pairs) {
  std::vector<ClassCountChange> out;
  for (std::size_t p = 0; p < pairs.size(); ++p)
    for (geometry::Kind kind : analysis::kAllKinds)
      for (const auto& [group, label] : groups_of_pair(baseline, current, pairs[p], kind)) {
        const auto* gb = group_of(baseline, pairs[p].baseline, kind, group);
        const auto* ga = group_of(current, pairs[p].current, kind, group);
        const auto before = class_counts(gb ? gb->counts() : analysis::VisibilityCounts{});
        const auto after = class_counts(ga ? ga->counts() : analysis::VisibilityCounts{});
        for (std::size_t i = 0; i < before.size(); ++i)
          out.push_back(
              {p, kind, group, label, before[i].first, before[i].second, after[i].second});
      }
  return out;
}

}  // namespace ra::audit
