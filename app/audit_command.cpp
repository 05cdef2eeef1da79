// `renderaudit audit BASELINE_DIR CURRENT_DIR` / `renderaudit audit RUN_DIR --between P1 P2`: a
// run against its baseline, or two platforms of one run; a verdict, its files and a history entry.
// The procedure is audit/audit.h's; the files audit/audit_report.h's.
//
// Exit codes: the verdict (0 unchanged, 1 changed, 2 failed). 2 is also bad input (nothing
// compared: not run directories, different experiments, an unknown platform), as for every command
// (app/commands.h), and a history database that could not be appended (the audit files are written
// first, so the verdict is not lost; the message says so).
#include <cmath>
#include <cstdio>

#include "app/commands.h"
#include "audit/audit.h"
#include "audit/audit_report.h"
#include "audit/history_db.h"
#include "rundir/run_folder.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::app {
namespace {

struct AuditCli {
  std::vector<std::string> dirs;
  audit::AuditOptions options;
  std::string db;
  bool no_history = false;
  bool brief = false;
};

// Primitives compared (recorded, on a baseline night), changed and flaky per platform pair.
struct PairCounts {
  uint64_t compared = 0, changed = 0, flakes = 0, failed = 0;
};

PairCounts pair_counts(const audit::AuditResult& r, std::size_t p) {
  PairCounts n;
  for (const auto& v : r.primitives.views)
    if (v.pair == p) n.compared += v.compared;
  for (const auto& c : r.primitives.changed)
    if (c.pair == p) ++(c.recheck == audit::Recheck::kFlake ? n.flakes : n.changed);
  for (const auto& f : r.primitives.failed) n.failed += f.pair == p;
  return n;
}

std::string audit_md_path(const audit::AuditResult& r) {
  return rundir::run_folder::audit_md(r.out_dir);
}

// A baseline night compares nothing: it says what was recorded and where, and no count of
// changes or tests (they would be of the run against itself).
void print_baseline(const audit::AuditResult& r, const std::vector<std::string>& files,
                    bool brief) {
  uint64_t recorded = 0;
  for (std::size_t p = 0; p < r.pairs.size(); ++p) recorded += pair_counts(r, p).compared;
  if (brief) {
    std::printf("audit: baseline established: %s is the baseline (%s primitives); later runs are "
                "audited against it; %s\n",
                r.current.dir.c_str(), util::grouped(recorded).c_str(), audit_md_path(r).c_str());
    return;
  }
  std::printf("audit: %s (exit %d): %s is the baseline that later runs are audited against\n",
              audit::verdict_text(r.verdict).c_str(), audit::verdict_exit_code(r.verdict),
              r.current.dir.c_str());
  for (std::size_t p = 0; p < r.pairs.size(); ++p)
    std::printf("  %s: %s primitives recorded, drawn by %s | %s\n", r.pairs[p].current.c_str(),
                util::grouped(pair_counts(r, p).compared).c_str(),
                r.current_drivers[p].renderer.c_str(), r.current_drivers[p].version.c_str());
  for (const auto& f : files) std::printf("  wrote %s\n", f.c_str());
}

// --brief: the verdict and its counts in one line, and where audit.md is.
void print_brief(const audit::AuditResult& r) {
  PairCounts all;
  for (std::size_t p = 0; p < r.pairs.size(); ++p) {
    const PairCounts n = pair_counts(r, p);
    all.compared += n.compared, all.changed += n.changed, all.flakes += n.flakes;
    all.failed += n.failed;
  }
  std::printf("audit: %s: %s of %s primitives changed, %s flake(s), %s crash/timeout record(s), "
              "%zu of %zu distribution tests significant; %s\n",
              audit::verdict_text(r.verdict).c_str(), util::grouped(all.changed).c_str(),
              util::grouped(all.compared).c_str(), util::grouped(all.flakes).c_str(),
              util::grouped(all.failed).c_str(), r.distributions.significant,
              r.distributions.family_size, audit_md_path(r).c_str());
  if (r.speed.performed)
    std::printf("  drawing time: %zu slower, %zu faster, %zu same, %zu unknown of %zu groups\n",
                r.speed.count(audit::SpeedVerdict::kSlower),
                r.speed.count(audit::SpeedVerdict::kFaster),
                r.speed.count(audit::SpeedVerdict::kSame),
                r.speed.count(audit::SpeedVerdict::kUnknown), r.speed.comparisons.size());
  for (const auto& m : r.renderer_mismatches) std::printf("  FAILED %s\n", m.c_str());
}

// One line per timed group: "  drawing time osmesa-llvmpipe triangle D: 0.742x [0.71, 0.77] faster".
void print_speed(const audit::AuditResult& r) {
  if (!r.speed.performed) return;
  std::printf("  drawing time (current / baseline, 95%% interval; %d repeats, %llu primitives per "
              "kind and view):\n",
              r.speed.options.repeats, static_cast<unsigned long long>(r.speed.options.per_view));
  for (const auto& c : r.speed.comparisons) {
    std::printf("    %s %s %s: ", r.pairs[c.pair].label().c_str(), geometry::kind_name(c.kind),
                c.group.c_str());
    if (std::isfinite(c.ratio))
      std::printf("%.3fx [%.3f, %.3f] %s", c.ratio, c.low, c.high,
                  audit::speed_verdict_name(c.verdict));
    else
      std::printf("%s", audit::speed_verdict_name(c.verdict));
    if (c.verdict == audit::SpeedVerdict::kUnknown && c.repeats_to_settle > 0)
      std::printf(" (about %d repeats would settle it: --speed-repeats %d)", c.repeats_to_settle,
                  c.repeats_to_settle);
    else if (!c.reason.empty())
      std::printf(" (%s)", c.reason.c_str());
    std::printf("\n");
  }
}

void print_result(const audit::AuditResult& r, const std::vector<std::string>& files,
                  bool brief) {
  if (r.verdict == audit::Verdict::kBaseline) return print_baseline(r, files, brief);
  if (brief) return print_brief(r);
  std::printf("audit: %s (exit %d)", audit::verdict_text(r.verdict).c_str(),
              audit::verdict_exit_code(r.verdict));
  for (std::size_t i = 0; i < r.reasons.size(); ++i)
    std::printf("%s%s", i ? "; " : ": ", r.reasons[i].c_str());
  std::printf("\n");
  for (std::size_t p = 0; p < r.pairs.size(); ++p) {
    const PairCounts n = pair_counts(r, p);
    std::printf(
        "  %s: %llu of %llu primitives changed, %llu flake(s), %llu crash/timeout record(s)\n",
        r.pairs[p].label().c_str(), static_cast<unsigned long long>(n.changed),
        static_cast<unsigned long long>(n.compared), static_cast<unsigned long long>(n.flakes),
        static_cast<unsigned long long>(n.failed));
    std::printf("    baseline %s: %s | %s\n    current  %s: %s | %s\n", r.pairs[p].baseline.c_str(),
                r.baseline_drivers[p].renderer.c_str(), r.baseline_drivers[p].version.c_str(),
                r.pairs[p].current.c_str(), r.current_drivers[p].renderer.c_str(),
                r.current_drivers[p].version.c_str());
  }
  for (const auto& m : r.renderer_mismatches) std::printf("  FAILED %s\n", m.c_str());
  if (r.flakes.not_checked)
    std::printf("  flake check capped: %zu changed primitive(s) not re-rendered\n",
                r.flakes.not_checked);
  std::printf("  significant distribution tests: %zu of %zu (Holm, alpha %g)\n",
              r.distributions.significant, r.distributions.family_size, r.distributions.alpha);
  print_speed(r);
  for (const auto& f : files) std::printf("  wrote %s\n", f.c_str());
}

}  // namespace

void register_audit_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "audit",
      "Compare a run with its baseline (same experiment), or two platforms of one run\n"
      "(--between), primitive by primitive and in distribution, and give a verdict:\n"
      "exit 0 unchanged, 1 changed, 2 failed (crash/timeout records, missing or failed shards,\n"
      "a driver not matching --expect-renderer) or bad input; a run audited against itself\n"
      "establishes a baseline (exit 0, nothing compared; recorded in the history as\n"
      "'baseline'). Changed primitives are rendered\n"
      "once more first: a difference that disappears is reported as a flake, not a change.\n"
      "Writes audit.json, audit.md, junit.xml and changed_primitives.csv into --out and appends\n"
      "a summary to the history database (with --between only when --db names one).");
  struct Options {
    AuditCli cli;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("runs", opts->cli.dirs, "BASELINE_DIR CURRENT_DIR, or RUN_DIR with --between")
      ->required()
      ->expected(1, 2)
      ->check(CLI::ExistingDirectory);
  cmd->add_option("--between", opts->cli.options.between,
                  "compare two platforms of one run: P1 (baseline role) and P2")
      ->expected(2);
  cmd->add_option("--alpha", opts->cli.options.alpha,
                  "family-wise error rate of the distribution tests (Holm), default 0.05")
      ->check(CLI::Range(1e-12, 0.5));
  cmd->add_option("--out,-o", opts->cli.options.out_dir,
                  "output directory (default CURRENT_DIR/audit, or RUN_DIR/audit-P1-vs-P2)");
  cmd->add_option("--db", opts->cli.db,
                  "history database (default: history.sqlite beside CURRENT_DIR, e.g. "
                  "outputs/history.sqlite for outputs/RUN; with --between none unless --db names "
                  "one)");
  cmd->add_flag("--no-history", opts->cli.no_history, "do not append to the history database");
  cmd->add_flag("--brief", opts->cli.brief,
                "print the verdict and its counts in one line and where audit.md is (the files "
                "hold the rest; `make nightly` runs with it)");
  cmd->add_option("--expect-renderer", opts->cli.options.expect_renderer,
                  "regular expression (ECMAScript, searched) every current GL_RENDERER must "
                  "match; otherwise the verdict is failed");
  cmd->add_option("--max-rerenders", opts->cli.options.max_rerenders,
                  "changed primitives re-rendered by the flake check, default 2000 (0: no check)");
  cmd->add_flag("--speed", opts->cli.options.speed.enabled,
                "also judge drawing time: both sides drawn again alone, interleaved with an A/A "
                "control, per kind and view group (docs/nightly-audit.md)");
  cmd->add_option("--speed-repeats", opts->cli.options.speed.repeats,
                  "rounds of fresh processes per side, default 4 (an even number: the sides take turns first and last equally often)")
      ->check(CLI::Range(1, 1000));
  cmd->add_option("--speed-primitives", opts->cli.options.speed.per_view,
                  "primitives of each kind and view timed, default 100")
      ->check(CLI::Range(uint64_t(6), uint64_t(1000000)));
  cmd->add_option("--speed-threshold", opts->cli.options.speed.threshold,
                  "a time change counts only when its whole 95% interval lies beyond this "
                  "fraction, default 0.05")
      ->check(CLI::Range(0.0, 10.0));
  cmd->add_flag("--speed-warn-only", opts->cli.options.speed.warn_only,
                "a slower group is reported but does not make the verdict 'changed'");
  cmd->add_option("--jobs,-j", opts->cli.options.jobs,
                  "threads and re-render processes (default: number of cores)")
      ->check(CLI::Range(1, 1024));
  cmd->callback([opts, &exit_code] {
    if (opts->cli.options.between.empty() && opts->cli.dirs.size() != 2)
      throw util::UserError("audit needs BASELINE_DIR CURRENT_DIR, or RUN_DIR --between P1 P2");
    if (!opts->cli.options.between.empty() && opts->cli.dirs.size() != 1)
      throw util::UserError("audit --between compares two platforms of one run: give one RUN_DIR");
    opts->cli.options.current_dir = opts->cli.dirs.back();
    if (opts->cli.options.speed.enabled && !opts->cli.brief)  // --brief: the verdict alone
      opts->cli.options.progress = [](const std::string& line) {
        std::fprintf(stderr, "audit: %s\n", line.c_str());
      };
    if (opts->cli.dirs.size() == 2) opts->cli.options.baseline_dir = opts->cli.dirs.front();

    // Any error is exit 2 here: main() maps other exceptions to 1, which an audit reads as
    // "changed".
    audit::AuditResult r;
    std::vector<std::string> files;
    try {
      r = audit::run_audit(opts->cli.options);
      files = audit::write_audit_outputs(r);
    } catch (const util::UserError&) {
      throw;
    } catch (const std::exception& e) {
      throw util::UserError(std::string("audit failed: ") + e.what());
    }
    print_result(r, files, opts->cli.brief);
    exit_code = audit::verdict_exit_code(r.verdict);
    // Two platforms of one run are an ad-hoc comparison, not a night of a series: their history
    // is kept only where asked.
    if (!opts->cli.options.between.empty() && opts->cli.db.empty() && !opts->cli.no_history) {
      std::printf("  history: none kept for --between (--db FILE keeps one)\n");
      return;
    }
    if (opts->cli.no_history) return;
    const std::string db = opts->cli.db.empty()
                               ? audit::default_history_path(opts->cli.options.current_dir)
                               : opts->cli.db;
    try {
      audit::append_history(db, r.summary);
      // A baseline night is a night of the series: its row says so, and its metrics are the first
      // point of every trend.
      std::printf(r.verdict == audit::Verdict::kBaseline ? "  history: the baseline recorded in %s\n"
                                                         : "  history: appended to %s\n",
                  db.c_str());
    } catch (const std::exception& e) {
      std::fprintf(stderr,
                   "renderaudit: the audit files are written, but the history could not be "
                   "appended: %s\n",
                   e.what());
      exit_code = kExitUsage;
    }
  });
}

}  // namespace ra::app
