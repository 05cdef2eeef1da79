#include "audit/audit_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/number_text.h"
#include "util/program_name.h"
#include "util/shell_quote.h"

namespace fs = std::filesystem;

namespace ra::audit {
Verdict GroupOutcome::verdict() const {
  if (failed || missing_shards || rerender_failures) return Verdict::kFailed;
  return changed ? Verdict::kChanged : Verdict::kUnchanged;
}

std::vector<GroupOutcome> group_outcomes(const AuditResult& r) {
  std::map<std::tuple<std::size_t, int, int>, GroupOutcome> groups;
  auto at = [&](std::size_t pair, geometry::Kind kind, int group) -> GroupOutcome& {
    GroupOutcome& g = groups[{pair, int(kind), group}];
    g.pair = pair, g.kind = kind, g.view_group = group;
    g.label = analysis::view_group_label(group);
    return g;
  };
  for (const ViewCounts& v : r.primitives.views) {
    GroupOutcome& g = at(v.pair, v.kind, v.view_group);
    g.views.push_back(v.view);
    g.compared += v.compared, g.unmatched += v.unmatched;
  }
  for (const ChangedPrimitive& c : r.primitives.changed) {
    GroupOutcome& g = at(c.pair, c.kind, c.view_group);
    ++(c.recheck == Recheck::kFlake ? g.flakes : g.changed);
    if (c.recheck != Recheck::kFlake && new_violation(c)) ++g.new_violations;
  }
  // Crash / timeout records of either side (those without a partner, too).
  for (const FailedPrimitive& f : r.primitives.failed) ++at(f.pair, f.kind, f.view_group).failed;
  for (const MissingShard& m : r.missing)
    for (std::size_t p = 0; p < r.pairs.size(); ++p)
      if (m.platform == (m.side == "baseline" ? r.pairs[p].baseline : r.pairs[p].current))
        ++at(p, m.kind, m.view_group).missing_shards;
  for (const audit::RerenderBatch& b : r.flakes.failed_batches)
    for (const ChangedPrimitive& c : r.primitives.changed)
      if (c.recheck == Recheck::kRerenderFailed && c.kind == b.kind && c.view == b.view &&
          c.index >= b.begin && c.index < b.end &&
          (r.pairs[c.pair].current == b.platform || r.pairs[c.pair].baseline == b.platform)) {
        ++at(c.pair, c.kind, c.view_group).rerender_failures;
        break;
      }
  for (const DistributionComparison& c : r.distributions.comparisons)
    for (const DistributionTest& t : c.tests)
      at(c.pair, geometry::Kind(int(c.kind)), c.view_group).significant_tests += t.significant;
  std::vector<GroupOutcome> out;
  for (auto& [k, g] : groups) {
    std::sort(g.views.begin(), g.views.end());
    out.push_back(g);
  }
  return out;
}

std::string show_command(const AuditResult& r, const ChangedPrimitive& c) {
  return util::program_for_commands() + " show " + util::shell_quote(r.current.dir) + " --platform " +
         util::shell_quote(r.pairs[c.pair].current) + " --kind " + geometry::kind_name(c.kind) +
         " --view " + std::to_string(c.view) + " --index " + std::to_string(c.index);
}

std::string format_number(double v, int significant) {
  if (!std::isfinite(v)) return "n/a";
  return util::significant(v, significant);
}

std::string changed_primitives_csv(const AuditResult& r) {
  std::ostringstream out;
  out << "baseline_platform,platform,kind,view,view_group,index,recheck,status_before,status_after,"
         "visibility_before,visibility_after,pixels_before,pixels_after,metric,value_before,"
         "value_after,ref_diff_before,ref_diff_after,pixel_hash_before,pixel_hash_after,"
         "pixel_hash_rerender\n";
  auto diff = [](int64_t d) { return d >= 0 ? std::to_string(d) : std::string(); };
  for (const ChangedPrimitive& c : r.primitives.changed) {
    const bool rerendered = c.recheck == Recheck::kStillDifferent || c.recheck == Recheck::kFlake;
    out << r.pairs[c.pair].baseline << ',' << r.pairs[c.pair].current << ','
        << geometry::kind_name(c.kind) << ',' << c.view << ',' << c.view_group << ',' << c.index
        << ',' << recheck_name(c.recheck) << ',' << metrics::status_name(c.before.status) << ','
        << metrics::status_name(c.after.status) << ','
        << metrics::visibility_name(c.before.visibility) << ','
        << metrics::visibility_name(c.after.visibility) << ',' << c.before.pixels << ','
        << c.after.pixels << ',' << headline_metric(c.kind) << ','
        << util::full_precision_if_finite(c.before.metric) << ','
        << util::full_precision_if_finite(c.after.metric) << ',' << diff(c.before.ref_diff) << ','
        << diff(c.after.ref_diff) << ',' << c.before.pixel_hash << ',' << c.after.pixel_hash << ','
        << (rerendered ? std::to_string(c.rerender_hash) : "") << '\n';
  }
  return out.str();
}

std::vector<std::string> write_audit_outputs(const AuditResult& r) {
  fs::create_directories(r.out_dir);
  const std::vector<std::pair<std::string, std::string>> files = {
      {rundir::run_folder::kAuditJsonFile, audit_json(r).dump(2) + "\n"},
      {rundir::run_folder::kAuditMdFile, audit_markdown(r)},
      {rundir::run_folder::kAuditJunitFile, audit_junit(r)},
      {"changed_primitives.csv", changed_primitives_csv(r)}};
  std::vector<std::string> paths;
  for (const auto& [name, content] : files) {
    paths.push_back(r.out_dir + "/" + name);
    util::write_file_atomic(paths.back(), content);
  }
  return paths;
}

}  // namespace ra::audit
