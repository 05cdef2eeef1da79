#include "audit/audit.h"

#include "rundir/records_format.h"
#include "rundir/run_folder.h"
#include "util/dir_lock.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <regex>

#include "util/errors.h"
#include "rundir/manifest.h"

namespace fs = std::filesystem;

namespace ra::audit {
namespace {

bool has_records(const std::string& dir) {
  if (!fs::is_directory(rundir::run_folder::records(dir))) return false;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::records(dir)))
    if (ra::rundir::is_records_file_name(e.path().filename().string())) return true;
  return false;
}

// The records of a run for the distribution stage; empty when the run has none at all (every shard
// failed: the missing shards already make the verdict).
analysis::RunRecords load_records(const std::string& dir, unsigned jobs) {
  if (!has_records(dir)) return {};
  return analysis::load_run_records(dir, {jobs});
}

void require_platform(const RunIdentity& run, const std::string& platform) {
  const auto& p = run.experiment.platforms;
  if (std::find(p.begin(), p.end(), platform) == p.end())
    throw util::UserError("--between " + platform + ": not a platform of the run " + run.dir +
                          " (its platforms: " +
                          [&] {
                            std::string s;
                            for (const auto& x : p) s += (s.empty() ? "" : ", ") + x;
                            return s;
                          }() +
                          ")");
}

void check_renderers(AuditResult& r) {
  if (r.expect_renderer.empty()) return;
  std::regex re;
  try {
    re = std::regex(r.expect_renderer, std::regex::ECMAScript);
  } catch (const std::regex_error& e) {
    throw util::UserError("--expect-renderer '" + r.expect_renderer +
                          "': not a valid regular expression (" + e.what() + ")");
  }
  for (const DriverIdentity& d : r.current_drivers)
    if (!std::regex_search(d.renderer, re))
      r.renderer_mismatches.push_back(d.platform + ": GL_RENDERER '" + d.renderer +
                                      "' does not match --expect-renderer '" + r.expect_renderer +
                                      "'");
}

}  // namespace

bool AuditResult::self_audit() const {
  std::error_code ec;
  return mode == "runs" && fs::equivalent(baseline.dir, current.dir, ec);
}

std::size_t AuditResult::changed_count() const {
  return std::size_t(
      std::count_if(primitives.changed.begin(), primitives.changed.end(),
                    [](const ChangedPrimitive& c) { return c.recheck != Recheck::kFlake; }));
}

std::size_t AuditResult::flake_count() const { return primitives.changed.size() - changed_count(); }

std::size_t AuditResult::recovered_count() const {
  return std::size_t(std::count_if(
      manifest_failures.begin(), manifest_failures.end(),
      [](const ManifestFailure& m) { return m.outcome == FailureOutcome::kRecovered; }));
}

AuditResult run_audit(const AuditOptions& o) {
  AuditResult r;
  r.date_utc = rundir::utc_now_iso8601();
  r.expect_renderer = o.expect_renderer;
  // 1. Identity.
  if (!o.between.empty()) {
    if (o.between.size() != 2 || o.between[0] == o.between[1])
      throw util::UserError("--between needs two different platforms of the run");
    r.mode = "between";
    r.current = load_run_identity(o.current_dir);
    r.baseline = r.current;
    for (const auto& p : o.between) require_platform(r.current, p);
    r.pairs.push_back({o.between[0], o.between[1]});
    r.out_dir = o.out_dir.empty()
                    ? rundir::run_folder::audit_between(o.current_dir, o.between[0], o.between[1])
                    : o.out_dir;
  } else {
    r.mode = "runs";
    r.baseline = load_run_identity(o.baseline_dir);
    r.current = load_run_identity(o.current_dir);
    require_same_experiment(r.baseline, r.current);
    for (const auto& p : r.current.experiment.platforms) r.pairs.push_back({p, p});
    r.out_dir = o.out_dir.empty() ? rundir::run_folder::audit(o.current_dir) : o.out_dir;
  }
  // The audited run must not change under us, and its audit/ has one writer (util/dir_lock.h).
  const util::DirLock lock(o.current_dir, "audit");
  for (const PlatformPair& p : r.pairs) {
    r.baseline_drivers.push_back(driver_of(r.baseline, p.baseline));
    r.current_drivers.push_back(driver_of(r.current, p.current));
  }
  check_renderers(r);

  // 2. Shards that never produced records, and what the manifests list.
  for (const PlatformPair& p : r.pairs) {
    for (auto& m : missing_shards(r.baseline, p.baseline, "baseline")) r.missing.push_back(m);
    for (auto& m : missing_shards(r.current, p.current, "current")) r.missing.push_back(m);
    for (auto& f : manifest_failures_of(r.baseline, p.baseline, "baseline"))
      r.manifest_failures.push_back(f);
    for (auto& f : manifest_failures_of(r.current, p.current, "current"))
      r.manifest_failures.push_back(f);
  }

  // 3. Per primitive.
  const bool same_rules = r.baseline.conformance_rules == r.current.conformance_rules;
  r.primitives = compare_primitives(r.baseline.dir, r.current.dir, r.pairs, o.jobs, same_rules);
  for (ManifestFailure& m : r.manifest_failures)  // a bisected shard: its primitives are named
    for (const FailedPrimitive& f : r.primitives.failed)
      if (m.outcome == FailureOutcome::kRecovered && f.side == m.side && f.platform == m.platform &&
          f.kind == m.kind && f.view == m.view && f.index >= m.begin && f.index < m.end)
        m.outcome = FailureOutcome::kPrimitivesFailed;

  // 4. Flakes, never re-rendering into a primitive or shard known to crash or hang.
  audit::KnownFailures avoid;
  for (const FailedPrimitive& f : r.primitives.failed)
    avoid.add(f.platform, f.kind, f.view, f.index, f.index + 1);
  for (const MissingShard& m : r.missing) avoid.add(m.platform, m.kind, m.view, m.begin, m.end);
  audit::RerenderOptions ro;
  ro.run_dir = r.current.dir;
  ro.program = o.program;
  ro.jobs = o.jobs;
  r.flakes =
      audit::apply_flake_check(r.primitives, r.pairs, r.mode == "between", avoid, o.max_rerenders, ro);

  // 5. Distributions and classes.
  const analysis::RunRecords current = load_records(r.current.dir, o.jobs);
  analysis::RunRecords baseline_storage;
  if (r.mode == "runs") baseline_storage = load_records(r.baseline.dir, o.jobs);
  const analysis::RunRecords& baseline = r.mode == "runs" ? baseline_storage : current;
  r.distributions = audit_distributions(baseline, current, r.pairs, o.alpha, o.jobs);
  r.classes = compare_class_counts(baseline, current, r.pairs);

  // 6. Drawing time, interleaved and judged. A baseline night compares nothing.
  if (o.speed.enabled && !r.self_audit()) {
    SpeedOptions so = o.speed;
    if (so.program.empty()) so.program = o.program;
    r.speed = audit_speed(r.baseline, r.current, r.pairs, avoid, so, o.progress);
  }

  // 7. Verdict, and the history record.
  decide_verdict(r, o.speed.warn_only);
  if (!same_rules)
    r.reasons.push_back("conformance classes not compared: the baseline was judged by conformance "
                        "rules " + std::to_string(r.baseline.conformance_rules) + ", the run by " +
                        std::to_string(r.current.conformance_rules) +
                        " (re-run the baseline with this renderaudit to compare them)");
  r.summary = make_summary(r, current);
  return r;
}

namespace {

// "triangles of view group D 1.31x [1.25, 1.38] slower" for each group that moved.
std::vector<std::string> speed_reasons(const AuditResult& r, bool warn_only) {
  std::vector<std::string> out;
  for (const SpeedComparison& c : r.speed.comparisons) {
    if (c.verdict != SpeedVerdict::kSlower && c.verdict != SpeedVerdict::kFaster) continue;
    char text[256];
    std::snprintf(text, sizeof text, "%s draws %ss of view group %s %s: %.3gx [%.3g, %.3g]%s",
                  c.platform.c_str(), geometry::kind_name(c.kind), c.group.c_str(),
                  speed_verdict_name(c.verdict), c.ratio, c.low, c.high,
                  c.verdict == SpeedVerdict::kSlower && warn_only ? " (a warning: --speed-warn-only)"
                                                                   : "");
    out.push_back(text);
  }
  for (const std::string& e : r.speed.errors) out.push_back("drawing time not compared: " + e);
  return out;
}

}  // namespace

void decide_verdict(AuditResult& r, bool speed_warn_only) {
  r.reasons.clear();
  const std::size_t failed = r.primitives.failed.size();
  if (failed) r.reasons.push_back(std::to_string(failed) + " crash/timeout record(s)");
  if (!r.missing.empty())
    r.reasons.push_back(std::to_string(r.missing.size()) + " shard(s) without records");
  const std::size_t unknown = std::size_t(std::count_if(
      r.manifest_failures.begin(), r.manifest_failures.end(),
      [](const ManifestFailure& m) { return m.outcome == FailureOutcome::kUnknown; }));
  if (unknown)
    r.reasons.push_back(std::to_string(unknown) +
                        " manifest failure(s) of shards the experiment does not plan");
  if (!r.flakes.failed_batches.empty())
    r.reasons.push_back(std::to_string(r.flakes.failed_batches.size()) +
                        " re-render process(es) crashed or timed out");
  for (const auto& m : r.renderer_mismatches) r.reasons.push_back(m);
  if (!r.reasons.empty()) {
    r.verdict = Verdict::kFailed;
    return;
  }
  if (r.self_audit()) {
    r.verdict = Verdict::kBaseline;
    r.reasons.push_back("the baseline and the current run are one directory: this run is the "
                        "baseline that later runs are audited against");
    return;
  }
  const std::size_t changed = r.changed_count();
  const std::size_t slower = r.speed.count(SpeedVerdict::kSlower);
  if (changed || (slower && !speed_warn_only)) {
    r.verdict = Verdict::kChanged;
    if (changed)
      r.reasons.push_back(std::to_string(changed) + " primitive(s) changed" +
                          (r.flake_count() ? " (and " + std::to_string(r.flake_count()) +
                                                 " flake(s))"
                                           : std::string()));
    else
      r.reasons.push_back("no primitive changed, but drawing time did");
    for (const std::string& s : speed_reasons(r, speed_warn_only)) r.reasons.push_back(s);
    if (r.distributions.significant)
      r.reasons.push_back(std::to_string(r.distributions.significant) +
                          " distribution test(s) significant after Holm correction");
    if (r.recovered_count())
      r.reasons.push_back(std::to_string(r.recovered_count()) +
                          " worker failure(s) in the manifest did not recur on re-run");
    return;
  }
  r.verdict = Verdict::kUnchanged;
  r.reasons.push_back("no primitive changed" +
                      (r.flake_count() ? " (" + std::to_string(r.flake_count()) +
                                             " difference(s) disappeared on re-render: flakes)"
                                       : std::string()));
  for (const std::string& s : speed_reasons(r, speed_warn_only)) r.reasons.push_back(s);
  if (r.distributions.significant)
    r.reasons.push_back(std::to_string(r.distributions.significant) +
                        " distribution test(s) significant after Holm correction, caused by the "
                        "flakes alone");
  if (r.recovered_count())
    r.reasons.push_back(std::to_string(r.recovered_count()) +
                        " worker failure(s) in the manifest did not recur on re-run");
}

AuditSummary make_summary(const AuditResult& r, const analysis::RunRecords& current) {
  AuditSummary s;
  s.date_utc = r.date_utc;
  s.experiment = r.current.name;
  s.experiment_hash = r.current.hash;
  s.seed = r.current.seed;
  auto absolute = [](const std::string& d) { return fs::absolute(d).lexically_normal().string(); };
  s.baseline_run = absolute(r.baseline.dir);
  s.current_run = absolute(r.current.dir);
  s.baseline_drivers = r.baseline_drivers;
  s.current_drivers = r.current_drivers;
  s.verdict = r.verdict;
  s.changed_primitives = int64_t(r.changed_count());
  s.flaky_primitives = int64_t(r.flake_count());
  s.failed_primitives = int64_t(r.primitives.failed.size());
  s.significant_tests = int64_t(r.distributions.significant);
  for (const SpeedComparison& c : r.speed.comparisons)
    s.speed.push_back({c.platform, c.baseline_platform, geometry::kind_name(c.kind),
                       c.view_group + 1, int64_t(c.n), c.ratio, c.low, c.high,
                       c.baseline_median_us, c.current_median_us,
                       speed_verdict_name(c.verdict)});
  const auto hf6 = stats::QuantileDefinition::kHyndmanFan6;
  for (const PlatformPair& pair : r.pairs) {
    const std::size_t p = platform_index(current, pair.current);
    if (p == current.platforms.size()) continue;
    for (geometry::Kind kind : analysis::kAllKinds)
      for (const analysis::ViewGroup* g : current.groups_of(p, kind)) {
        const auto& metrics = analysis::kind_metrics(kind);
        for (std::size_t m = 0; m < metrics.size(); ++m) {
          MetricSummary ms{pair.current,
                           analysis::kind_name(kind),
                           metrics[m].column,
                           g->view_group + 1,
                           0,
                           metrics::kNA,
                           metrics::kNA};
          const std::vector<double> v = g->pooled(m);
          ms.n = int64_t(v.size());
          if (!v.empty()) {
            const stats::Description d = analysis::describe_sorted(v, hf6);
            ms.median = d.median, ms.iqr = d.iqr;
          }
          s.metrics.push_back(ms);
        }
        for (const auto& [name, count] : class_counts(g->counts()))
          s.classes.push_back(
              {pair.current, analysis::kind_name(kind), name, g->view_group + 1, int64_t(count)});
      }
  }
  return s;
}

}  // namespace ra::audit
