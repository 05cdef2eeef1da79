// audit.json: everything the audit found, machine-readable (audit/audit_report.h; keys in
// docs/nightly-audit.md). Numbers that are undefined are null; 64-bit pixel hashes are decimal strings.
#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>

#include "audit/audit_report.h"
#include "rundir/manifest.h"
#include "util/json_number.h"

namespace ra::audit {
namespace {

using nlohmann::json;

json state_json(const PrimitiveState& s, geometry::Kind kind) {
  return {{"status", metrics::status_name(s.status)},
          {"visibility", metrics::visibility_name(s.visibility)},
          {"pixels", s.pixels},
          {"pixel_hash", std::to_string(s.pixel_hash)},  // a string: JSON readers lose 64-bit ints
          {"metric", headline_metric(kind)},
          {"value", util::finite_or_null(s.metric)},
          {"ref_diff", s.ref_diff >= 0 ? json(s.ref_diff) : json(nullptr)},
          {"conformance", s.conformance == metrics::Conformance::kNotCompared
                              ? json(nullptr)
                              : json(metrics::conformance_name(s.conformance))},
          {"violating_pixels", s.violating_pixels >= 0 ? json(s.violating_pixels) : json(nullptr)}};
}

json changed_json(const AuditResult& r, const ChangedPrimitive& c) {
  const PlatformPair& p = r.pairs[c.pair];
  json j = {{"baseline_platform", p.baseline},      {"platform", p.current},
            {"kind", geometry::kind_name(c.kind)},  {"view", c.view},
            {"view_group", c.view_group},           {"index", c.index},
            {"recheck", recheck_name(c.recheck)},   {"before", state_json(c.before, c.kind)},
            {"after", state_json(c.after, c.kind)}, {"show", show_command(r, c)}};
  j["rerender_pixel_hash"] = c.recheck == Recheck::kStillDifferent || c.recheck == Recheck::kFlake
                                 ? json(std::to_string(c.rerender_hash))
                                 : json(nullptr);
  return j;
}

json test_json(const DistributionTest& t) {
  json j = {{"test", t.test}, {"data", t.data}, {"defined", t.outcome.defined}};
  if (t.outcome.defined) {
    j["statistic"] = t.outcome.statistic;
    j["df1"] = t.outcome.df1;
    if (t.test == "levene_median") j["df2"] = t.outcome.df2;
    j["p_value"] = t.outcome.p_value;
    j["p_adjusted"] = t.p_adjusted;
    j["significant"] = t.significant;
  } else {
    j["reason"] = t.outcome.reason;
  }
  return j;
}

json outcome_json(const analysis::TestOutcome& t, double p_holm) {
  if (!t.defined) return {{"defined", false}, {"reason", t.reason}};
  return {{"defined", true},       {"statistic", t.statistic}, {"df1", t.df1},
          {"df2", t.df2},          {"p_value", t.p_value},     {"p_adjusted", p_holm}};
}

// One object per platform pair, kind and view group (docs/nightly-audit.md): ratio = current /
// baseline drawing time, its 95% interval, the verdict.
json speed_json(const SpeedComparison& c) {
  json box_cox = c.box_cox.applicable ? json{{"applied", true}, {"lambda", c.box_cox.lambda}}
                                      : json{{"applied", false}, {"reason", c.box_cox.reason}};
  return {{"platform", c.platform},
          {"baseline_platform", c.baseline_platform},
          {"kind", geometry::kind_name(c.kind)},
          {"group", c.group},
          {"ratio", util::finite_or_null(c.ratio)},
          {"low", util::finite_or_null(c.low)},
          {"high", util::finite_or_null(c.high)},
          {"verdict", speed_verdict_name(c.verdict)},
          {"n", c.n},
          {"repeats", c.repeats},
          {"baseline_median_us", util::finite_or_null(c.baseline_median_us)},
          {"current_median_us", util::finite_or_null(c.current_median_us)},
          {"control", {{"ratio", util::finite_or_null(c.control_ratio)},
                       {"low", util::finite_or_null(c.control_low)},
                       {"high", util::finite_or_null(c.control_high)}}},
          {"band", util::finite_or_null(c.band)},
          {"repeats_to_settle", c.repeats_to_settle > 0 ? json(c.repeats_to_settle) : json(nullptr)},
          {"reason", c.reason.empty() ? json(nullptr) : json(c.reason)},
          {"box_cox", box_cox},
          {"welch_t", outcome_json(c.welch, c.welch_p_holm)},
          {"levene_median", outcome_json(c.levene, c.levene_p_holm)}};
}

// `speed` (one object per pair, kind and view group) and `speed_measurement` (how).
void add_speed(json& j, const SpeedAudit& s) {
  json speed = json::array();
  for (const SpeedComparison& c : s.comparisons) speed.push_back(speed_json(c));
  j["speed"] = speed;
  j["speed_measurement"] = {
      {"performed", s.performed},
      {"repeats", s.options.repeats},
      {"primitives_per_view", s.options.per_view},
      {"threshold", s.options.threshold},
      {"warn_only", s.options.warn_only},
      {"interval", "student t over rounds of hodges-lehmann paired log ratios, 95%"},
      {"tests", "welch_t and levene_median on box-cox, holm-bonferroni"},
      {"processes", s.processes},
      {"seconds", s.seconds},
      {"errors", s.errors}};
}

json comparison_json(const AuditResult& r, const DistributionComparison& c) {
  const analysis::MetricSpec& m = analysis::kind_metrics(c.kind)[c.metric];
  json bc = {{"applied", c.box_cox.applicable}};
  if (c.box_cox.applicable) {
    bc["lambda"] = c.box_cox.lambda;
    bc["ppcc"] = c.box_cox.ppcc;
    bc["at_boundary"] = c.box_cox.at_boundary;
  } else {
    bc["reason"] = c.box_cox.reason;
  }
  json tests = json::array();
  for (const auto& t : c.tests) tests.push_back(test_json(t));
  return {{"baseline_platform", r.pairs[c.pair].baseline},
          {"platform", r.pairs[c.pair].current},
          {"kind", analysis::kind_name(c.kind)},
          {"view_group", c.view_group},
          {"group", c.label},
          {"metric", m.column},
          {"symbol", m.symbol},
          {"unit", analysis::unit_name(m.unit)},
          {"n_before", c.n_before},
          {"n_after", c.n_after},
          {"median_before", util::finite_or_null(c.median_before)},
          {"median_after", util::finite_or_null(c.median_after)},
          {"median_difference", util::finite_or_null(c.median_difference())},
          {"iqr_before", util::finite_or_null(c.iqr_before)},
          {"iqr_after", util::finite_or_null(c.iqr_after)},
          {"iqr_difference", util::finite_or_null(c.iqr_difference())},
          {"box_cox", bc},
          {"tests", tests},
          {"significant", c.significant()}};
}

}  // namespace

json audit_json(const AuditResult& r) {
  json j = rundir::document_header("audit", kAuditSchemaVersion, false);
  j["tool"] = {{"name", "renderaudit"},
               {"version", rundir::project_version()},
               {"commit", rundir::project_commit()}};
  j["date_utc"] = r.date_utc;
  j["mode"] = r.mode;
  j["verdict"] = verdict_name(r.verdict);
  j["exit_code"] = int(r.verdict);
  j["reasons"] = r.reasons;
  j["experiment"] = {{"name", r.current.name}, {"hash", r.current.hash}, {"seed", r.current.seed}};
  j["baseline"] = {{"run_dir", r.baseline.dir}, {"manifest_status", r.baseline.status}};
  j["current"] = {{"run_dir", r.current.dir}, {"manifest_status", r.current.status}};
  json pairs = json::array();
  for (std::size_t p = 0; p < r.pairs.size(); ++p)
    pairs.push_back({{"label", r.pairs[p].label()},
                     {"baseline_platform", r.pairs[p].baseline},
                     {"current_platform", r.pairs[p].current},
                     {"baseline_driver",
                      {{"renderer", r.baseline_drivers[p].renderer},
                       {"version", r.baseline_drivers[p].version}}},
                     {"current_driver",
                      {{"renderer", r.current_drivers[p].renderer},
                       {"version", r.current_drivers[p].version}}}});
  j["pairs"] = pairs;
  j["expect_renderer"] = r.expect_renderer.empty() ? json(nullptr)
                                                   : json{{"regex", r.expect_renderer},
                                                          {"mismatches", r.renderer_mismatches}};
  uint64_t compared = 0, unmatched = 0;
  for (const ViewCounts& v : r.primitives.views) compared += v.compared, unmatched += v.unmatched;
  j["counts"] = {{"compared", compared},
                 {"changed", r.changed_count()},
                 {"flakes", r.flake_count()},
                 {"failed_primitives", r.primitives.failed.size()},
                 {"missing_shards", r.missing.size()},
                 {"unmatched", unmatched},
                 {"significant_tests", r.distributions.significant},
                 {"new_violations", std::count_if(r.primitives.changed.begin(),
                                                  r.primitives.changed.end(),
                                                  [](const ChangedPrimitive& c) {
                                                    return c.recheck != Recheck::kFlake &&
                                                           new_violation(c);
                                                  })}};
  json views = json::array();
  std::map<std::tuple<std::size_t, int, int>, uint64_t> flakes;
  for (const ChangedPrimitive& c : r.primitives.changed)
    if (c.recheck == Recheck::kFlake) ++flakes[{c.pair, int(c.kind), c.view}];
  for (const ViewCounts& v : r.primitives.views) {
    const uint64_t f = flakes[{v.pair, int(v.kind), v.view}];
    views.push_back({{"baseline_platform", r.pairs[v.pair].baseline},
                     {"platform", r.pairs[v.pair].current},
                     {"kind", geometry::kind_name(v.kind)},
                     {"view", v.view},
                     {"view_group", v.view_group},
                     {"group", analysis::view_group_label(v.view_group)},
                     {"compared", v.compared},
                     {"changed", v.changed - f},
                     {"flakes", f},
                     {"failed", v.failed},
                     {"unmatched", v.unmatched}});
  }
  j["views"] = views;
  json changed = json::array(), flaky = json::array();
  std::size_t n_changed = 0, n_flaky = 0;
  for (const ChangedPrimitive& c : r.primitives.changed) {
    const bool flake = c.recheck == Recheck::kFlake;
    json& list = flake ? flaky : changed;
    if (list.size() < kJsonListed) list.push_back(changed_json(r, c));
    ++(flake ? n_flaky : n_changed);
  }
  j["changed_primitives"] = {{"total", n_changed}, {"listed", changed.size()}, {"items", changed}};
  j["flakes"] = {{"total", n_flaky}, {"listed", flaky.size()}, {"items", flaky}};
  json batches = json::array();
  for (const audit::RerenderBatch& b : r.flakes.failed_batches)
    batches.push_back({{"platform", b.platform},
                       {"kind", geometry::kind_name(b.kind)},
                       {"view", b.view},
                       {"begin", b.begin},
                       {"end", b.end},
                       {"error", b.error}});
  j["flake_check"] = {{"performed", r.flakes.performed},
                      {"both_sides", r.flakes.both_sides},
                      {"attempt", 2},
                      {"cap", r.flakes.cap},
                      {"checked", r.flakes.checked},
                      {"not_checked", r.flakes.not_checked},
                      {"flakes", r.flakes.flakes},
                      {"still_different", r.flakes.still_different},
                      {"rerender_failed", r.flakes.rerender_failed},
                      {"processes", r.flakes.processes},
                      {"seconds", r.flakes.seconds},
                      {"failed_processes", batches}};
  json failed = json::array(), missing = json::array();
  for (const FailedPrimitive& f : r.primitives.failed)
    failed.push_back({{"side", f.side},
                      {"platform", f.platform},
                      {"kind", geometry::kind_name(f.kind)},
                      {"view", f.view},
                      {"view_group", f.view_group},
                      {"index", f.index},
                      {"status", metrics::status_name(f.status)}});
  for (const MissingShard& m : r.missing)
    missing.push_back({{"side", m.side},
                       {"platform", m.platform},
                       {"kind", geometry::kind_name(m.kind)},
                       {"view", m.view},
                       {"view_group", m.view_group},
                       {"begin", m.begin},
                       {"end", m.end},
                       {"shard", m.id},
                       {"reason", m.reason}});
  json manifest = json::array();
  for (const ManifestFailure& m : r.manifest_failures)
    manifest.push_back({{"side", m.side},
                        {"platform", m.platform},
                        {"shard", m.shard},
                        {"reason", m.reason},
                        {"outcome", failure_outcome_name(m.outcome)}});
  j["failures"] = {{"primitives", failed},
                   {"missing_shards", missing},
                   {"manifest", manifest},
                   {"rerender", batches},
                   {"renderer_mismatches", r.renderer_mismatches}};
  json comparisons = json::array();
  for (const DistributionComparison& c : r.distributions.comparisons)
    comparisons.push_back(comparison_json(r, c));
  j["distribution_tests"] = {{"alpha", r.distributions.alpha},
                             {"location_test", "welch_t"},
                             {"spread_test", "levene_median"},
                             {"correction", "holm-bonferroni"},
                             {"family_size", r.distributions.family_size},
                             {"significant", r.distributions.significant},
                             {"quantiles", "hyndman_fan_6"},
                             {"comparisons", comparisons}};
  json classes = json::array();
  for (const ClassCountChange& c : r.classes)
    classes.push_back({{"baseline_platform", r.pairs[c.pair].baseline},
                       {"platform", r.pairs[c.pair].current},
                       {"kind", analysis::kind_name(c.kind)},
                       {"view_group", c.view_group},
                       {"group", c.label},
                       {"class", c.visibility},
                       {"before", c.before},
                       {"after", c.after},
                       {"difference", int64_t(c.after) - int64_t(c.before)}});
  j["visibility"] = classes;
  add_speed(j, r.speed);
  return j;
}

}  // namespace ra::audit
