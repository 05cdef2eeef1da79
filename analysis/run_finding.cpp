// What a run found, in one line (see the header).
#include "analysis/run_finding.h"

#include <cstdint>
#include <map>

#include "analysis/run_records.h"
#include "rundir/run_folder.h"
#include "util/number_text.h"

namespace ra::analysis {
namespace {

std::string plural_kind(const std::string& kind) { return kind + "s"; }

std::string count_of(std::uint64_t n, const char* one, const char* many) {
  return util::grouped(n) + " " + (n == 1 ? one : many);
}

}  // namespace

std::string run_finding_line(const RunTally& tally, const std::string& run_dir) {
  std::uint64_t judged = 0, exact = 0, violations = 0;
  // platform -> kind -> "2 (group B: 150 deg, 128x128)" parts, in the tally's order
  std::map<std::string, std::map<std::string, std::pair<std::uint64_t, std::string>>> where;
  for (const auto& [key, n] : tally.verdicts) {
    judged += n.compared, exact += n.exact, violations += n.violation;
    if (n.violation == 0) continue;
    const auto& [platform, kind, group] = key;
    auto& [count, groups] = where[platform][kind];
    count += n.violation;
    const auto label = tally.group_labels.find(key);
    groups += (groups.empty() ? "" : ", ") + std::string("group ") + view_group_label(group) +
              (label == tally.group_labels.end() ? "" : ": " + label->second);
  }
  std::uint64_t not_ok = 0;
  for (const auto& [key, n] : tally.non_ok_counts) not_ok += n;
  const std::string failures =
      not_ok ? "; " + count_of(not_ok, "record", "records") + " not drawn (crash, timeout or invalid)"
             : "";

  if (judged == 0)
    return "finding: no primitive judged by GL's rules (the reference platform, or antialiased): " +
           count_of(tally.records, "record", "records") + failures;
  if (violations == 0)
    return "finding: no violation (no GL rule broken) in " + util::grouped(judged) +
           " primitives; " + util::fixed(100.0 * double(exact) / double(judged), 1) +
           "% drawn exactly as the reference rasterizer" + failures;
  std::string line = "finding: " + count_of(violations, "violation", "violations") +
                     " (GL rules broken) in " + util::grouped(judged) + " primitives:";
  bool first_platform = true;
  for (const auto& [platform, kinds] : where) {
    line += (first_platform ? " " : "; ") + platform;
    first_platform = false;
    bool first_kind = true;
    for (const auto& [kind, entry] : kinds) {
      line += (first_kind ? " " : ", ") + plural_kind(kind) + " " + util::grouped(entry.first) +
              " (" + entry.second + ")";
      first_kind = false;
    }
  }
  return line + failures + "; each in " + rundir::run_folder::analysis(run_dir) + "/violations.md";
}

}  // namespace ra::analysis
