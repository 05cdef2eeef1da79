// The decisions of a watch night (see the header).
#include "triage/watch_plan.h"

#include <algorithm>
#include <cctype>
#include <cstdio>

namespace ra::triage {
namespace {

std::string short_hash(const std::string& c) { return c.substr(0, 12); }

// A night's end whose exit code and baseline follow from its verdict.
NightEnd end(const std::string& verdict, const std::string& note,
             const std::vector<std::string>& not_bisected = {}) {
  NightEnd e;
  e.verdict = verdict;
  e.note = note;
  e.exit_code = night_exit_code(verdict);
  e.moves_baseline = night_moves_baseline(verdict, not_bisected);
  return e;
}

}  // namespace

NightKind night_kind(const std::string& last_commit, const std::string& head, bool head_descends) {
  if (head == last_commit) return NightKind::nothing_new;
  if (last_commit.empty()) return NightKind::first_night;
  return head_descends ? NightKind::compare : NightKind::moved_backwards;
}

int night_exit_code(const std::string& verdict) {
  if (verdict == "nothing new" || verdict == "unchanged" || verdict == "baseline established")
    return 0;
  if (verdict == "changed" || verdict == "moved backwards") return 1;
  return 2;
}

bool night_moves_baseline(const std::string& verdict,
                          const std::vector<std::string>& not_bisected) {
  if (verdict == "changed") return not_bisected.empty();
  return verdict == "baseline established" || verdict == "moved backwards" ||
         verdict == "unchanged";
}

NightEnd unseen_night(const std::string& verdict, const std::string& why) {
  return end(verdict, why);
}

NightEnd nothing_new_night() {
  return end("nothing new", "the branch head is last night's commit");
}

NightEnd build_failed_night(const std::string& commit, const std::string& error,
                            const std::string& error_file, bool has_baseline) {
  // One line: the error's first line; meson's and ninja's whole output is in the file.
  std::string first = error.substr(0, error.find('\n'));
  if (first.size() > 160) first = first.substr(0, 157) + "...";
  return end("build failed", "the build of " + short_hash(commit) + " failed (" + first +
                                 "; the whole error: " + error_file + ")" +
                                 (has_baseline ? "; last night's build stays the baseline" : ""));
}

bool run_finished(int run_exit_code) { return run_exit_code == 0 || run_exit_code == 1; }

NightEnd run_failed_night(int run_exit_code, const std::string& log) {
  return end("run failed", "the run exited " + std::to_string(run_exit_code) + " (" + log + ")");
}

NightEnd uncompared_night(NightKind kind, const std::string& last_commit) {
  if (kind == NightKind::moved_backwards)
    return end("moved backwards", "the branch no longer holds last night's commit " +
                                      short_hash(last_commit) + ": tonight is the new baseline");
  return end("baseline established", "tonight's build is the baseline from now on");
}

std::vector<std::string> run_arguments(const std::string& experiment, const std::string& run_dir,
                                       unsigned jobs) {
  return {
      "run", experiment, "--out", run_dir, "--quiet", "--jobs", std::to_string(jobs ? jobs : 2)};
}

std::vector<std::string> audit_arguments(const std::string& platform, const std::string& run_dir,
                                         const std::string& out, const std::string& db,
                                         unsigned jobs, const BisectSpeedOptions& speed) {
  std::vector<std::string> args = {"audit",
                                   run_dir,
                                   "--between",
                                   platform + "@" + kLastBuild,
                                   platform + "@" + kTonightBuild,
                                   "--out",
                                   out,
                                   "--db",
                                   db,
                                   "--jobs",
                                   std::to_string(jobs ? jobs : 2)};
  if (speed.enabled) {
    char threshold[32];
    std::snprintf(threshold, sizeof threshold, "%g", speed.threshold);
    args.insert(args.end(), {"--speed", "--speed-warn-only", "--speed-repeats",
                             std::to_string(speed.repeats), "--speed-primitives",
                             std::to_string(speed.per_view), "--speed-threshold", threshold});
  }
  return args;
}

bool audit_failed(int audit_exit_code) { return audit_exit_code >= 2; }

bool audit_judged(int audit_exit_code) { return audit_exit_code == 0 || audit_exit_code == 1; }

bool platform_needs_bisection(int audit_exit_code, std::size_t time_moved) {
  return audit_exit_code == 1 || time_moved > 0;
}

NightBisection night_bisection(const std::string& platform, const std::string& last_commit,
                               const std::string& head) {
  return {platform + "@" + kLastBuild, platform + "@" + kTonightBuild, last_commit, head};
}

std::string changed_night_note(const NightCounts& n) {
  const std::string time = n.time_moved == 0
                               ? std::string()
                               : "drawing time of " + std::to_string(n.time_moved) +
                                     (n.time_moved == 1 ? " group" : " groups") + " moved, " +
                                     std::to_string(n.speed_culprit_commits) + " commit(s) named";
  if (n.changed == 0 && n.time_moved > 0) return "no primitive changed; " + time;
  std::string note =
      std::to_string(n.changed) + (n.changed == 1 ? " primitive changed" : " primitives changed");
  if (n.bisected < n.changed)
    note += " (" + std::to_string(n.bisected) +
            " of them bisected: a sample, see the bisection's report)";
  note += ", " + std::to_string(n.culprit_commits) + " culprit commit(s)";
  if (n.unattributed > 0)
    note += ", " + std::to_string(n.unattributed) +
            " change(s) not attributed (only commits that failed to build lie between)";
  if (!time.empty()) note += "; " + time;
  return note;
}

NightEnd compared_night(const ComparedNight& n) {
  if (n.audit_failed)
    return end("run failed", "a driver crashed or the audit failed (" + n.night_dir + ")");
  if (!n.changed)
    return end("unchanged",
               n.speed ? "no primitive changed, no drawing time moved" : "no primitive changed");
  // When no bisection ran, the counts hold nothing: the note says only that primitives changed.
  std::string note = n.counts.bisected > 0 || n.not_bisected.empty()
                         ? changed_night_note(n.counts)
                         : std::string("primitives changed");
  NightEnd e = end("changed", note, n.not_bisected);
  if (!e.moves_baseline)
    e.note += "; " + std::to_string(n.not_bisected.size()) + " platform(s) not bisected: their " +
              "changes are kept, last night's commit " + short_hash(n.last_commit) +
              " stays the baseline and the next night bisects them with its own";
  e.baseline_kept = !e.moves_baseline;
  return e;
}

std::string night_folder_name(const std::string& date_utc) {
  std::string name = date_utc;
  std::replace(name.begin(), name.end(), ':', '-');
  return name;
}

std::vector<std::string> nights_to_prune(std::vector<std::string> names, std::size_t keep,
                                         const std::string& tonight) {
  // A night's stamp: 2026-11-29T02-00-00Z (night_folder_name of rundir::utc_now_iso8601).
  const auto stamp = [](const std::string& n) {
    if (n.size() != 20 || n[4] != '-' || n[7] != '-' || n[10] != 'T' || n[13] != '-' ||
        n[16] != '-' || n[19] != 'Z')
      return false;
    for (std::size_t i : {0, 1, 2, 3, 5, 6, 8, 9, 11, 12, 14, 15, 17, 18})
      if (!std::isdigit(static_cast<unsigned char>(n[i]))) return false;
    return true;
  };
  std::vector<std::string> nights;
  for (const std::string& n : names)
    if (stamp(n)) nights.push_back(n);
  std::sort(nights.begin(), nights.end());
  std::vector<std::string> out;
  if (keep == 0 || nights.size() <= keep) return out;
  for (std::size_t i = 0; i + keep < nights.size(); ++i)
    if (nights[i] != tonight) out.push_back(nights[i]);
  return out;
}

}  // namespace ra::triage
