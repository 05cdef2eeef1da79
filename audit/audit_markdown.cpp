// audit.md: the summary a person reads first (audit/audit_report.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "audit/audit_report.h"
#include "stats/table_writer.h"

namespace ra::audit {
namespace {

std::string upper(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return char(std::toupper(c)); });
  return s;
}

// A table cell: pipes escaped, line breaks flattened.
std::string cell(std::string s) {
  std::string out;
  for (char c : s)
    out += c == '|' ? std::string("\\|") : c == '\n' ? std::string(" ") : std::string(1, c);
  return out;
}

std::string views_text(const std::vector<int>& views) {
  std::string s;
  for (int v : views) s += (s.empty() ? "" : ", ") + std::to_string(v);
  return s;
}

std::string arrow(const std::string& a, const std::string& b) {
  return a == b ? a : a + " -> " + b;
}

// "violation (3 px: polygon-edge)", "within-spec", "n/a" (no verdict).
std::string verdict_text(const PrimitiveState& s) {
  if (s.conformance == metrics::Conformance::kNotCompared) return "n/a";
  std::string t = metrics::conformance_name(s.conformance);
  if (s.conformance == metrics::Conformance::kViolation)
    t += " (" + std::to_string(s.violating_pixels) + " px)";
  return t;
}

std::string state_line(const ChangedPrimitive& c) {
  const std::string metric = headline_metric(c.kind);
  auto diff = [](int64_t d) { return d >= 0 ? std::to_string(d) : std::string("n/a"); };
  return "status " +
         arrow(metrics::status_name(c.before.status), metrics::status_name(c.after.status)) +
         ", visibility " +
         arrow(metrics::visibility_name(c.before.visibility),
               metrics::visibility_name(c.after.visibility)) +
         ", pixels " + arrow(std::to_string(c.before.pixels), std::to_string(c.after.pixels)) +
         ", " + metric + " " +
         arrow(format_number(c.before.metric, 6), format_number(c.after.metric, 6)) +
         ", ref_diff " + arrow(diff(c.before.ref_diff), diff(c.after.ref_diff)) + ", conformance " +
         arrow(verdict_text(c.before), verdict_text(c.after));
}

// New GL violations first: the one thing a driver team must not miss.
void new_violations(std::ostream& md, const AuditResult& r) {
  md << "## New conformance violations\n\n";
  std::size_t total = 0;
  for (const ChangedPrimitive& c : r.primitives.changed) {
    if (c.recheck == Recheck::kFlake || !new_violation(c)) continue;
    if (++total > kMarkdownListed) continue;
    md << "- " << r.pairs[c.pair].label() << " " << geometry::kind_name(c.kind) << ", view "
       << c.view << " (group " << analysis::view_group_label(c.view_group) << "), index " << c.index
       << ": " << verdict_text(c.before) << " -> " << verdict_text(c.after) << "  \n  `"
       << show_command(r, c) << "`\n";
  }
  if (total == 0)
    md << "None: no primitive breaks a GL rasterization rule that did not break it in the "
          "baseline.\n\n";
  else
    md << "\n" << total << " primitives break a GL rasterization rule (metrics/conformance.h) "
       << "that their baseline records did not break" << (total > kMarkdownListed ? " (the first "
       + std::to_string(kMarkdownListed) + " above)" : "") << ".\n\n";
}

void list_primitives(std::ostream& md, const AuditResult& r, bool flakes) {
  std::size_t total = 0, shown = 0;
  for (const ChangedPrimitive& c : r.primitives.changed) {
    if ((c.recheck == Recheck::kFlake) != flakes) continue;
    if (++total > kMarkdownListed) continue;
    ++shown;
    md << "- " << r.pairs[c.pair].label() << " " << geometry::kind_name(c.kind) << ", view "
       << c.view << " (group " << analysis::view_group_label(c.view_group) << "), index " << c.index
       << ": " << state_line(c) << "; re-render: " << recheck_name(c.recheck) << "  \n  `"
       << show_command(r, c) << "`\n";
  }
  if (total == 0)
    md << "None.\n";
  else if (shown < total)
    md << "\n... and " << total - shown << " more: " << total
       << " in all (every one in `changed_primitives.csv`).\n";
  else
    md << "\n" << total << " in all.\n";
}

void drivers(std::ostream& md, const AuditResult& r) {
  md << "## Drivers\n\n";
  if (r.mode == "between") {
    md << "| | " << cell(r.pairs[0].baseline) << " (baseline role) | " << cell(r.pairs[0].current)
       << " |\n"
       << stats::markdown_rule({stats::Align::kLeft, stats::Align::kLeft, stats::Align::kLeft});
    md << "| GL_RENDERER | " << cell(r.baseline_drivers[0].renderer) << " | "
       << cell(r.current_drivers[0].renderer) << " |\n";
    md << "| GL_VERSION | " << cell(r.baseline_drivers[0].version) << " | "
       << cell(r.current_drivers[0].version) << " |\n";
  } else {
    md << stats::markdown_header({"platform", "baseline GL_RENDERER", "baseline GL_VERSION",
                                  "current GL_RENDERER", "current GL_VERSION"},
                                 std::vector<stats::Align>(5, stats::Align::kLeft));
    for (std::size_t p = 0; p < r.pairs.size(); ++p)
      md << "| " << cell(r.pairs[p].current) << " | " << cell(r.baseline_drivers[p].renderer)
         << " | " << cell(r.baseline_drivers[p].version) << " | "
         << cell(r.current_drivers[p].renderer) << " | " << cell(r.current_drivers[p].version)
         << " |\n";
  }
  if (!r.expect_renderer.empty())
    md << "\n--expect-renderer `" << r.expect_renderer << "`: "
       << (r.renderer_mismatches.empty()
               ? "every current driver matches."
               : std::to_string(r.renderer_mismatches.size()) + " mismatch(es), see Failures.")
       << "\n";
  md << "\n";
}

void counts(std::ostream& md, const AuditResult& r) {
  using stats::Align;
  md << "## Primitives compared (per platform, kind, view group)\n\n"
     << stats::markdown_header({"platform", "kind", "group", "views", "compared", "changed",
                                "flakes", "crash/timeout", "missing shards", "significant tests",
                                "outcome"},
                               {Align::kLeft, Align::kLeft, Align::kCenter, Align::kLeft,
                                Align::kRight, Align::kRight, Align::kRight, Align::kRight,
                                Align::kRight, Align::kRight, Align::kLeft});
  for (const GroupOutcome& g : group_outcomes(r))
    md << "| " << cell(r.pairs[g.pair].label()) << " | " << geometry::kind_name(g.kind) << " | "
       << g.label << " | " << views_text(g.views) << " | " << g.compared << " | " << g.changed
       << " | " << g.flakes << " | " << g.failed << " | " << g.missing_shards << " | "
       << g.significant_tests << " | " << verdict_name(g.verdict()) << " |\n";
  md << "\nPer view: `audit.json` key `views`. A primitive is changed when its lit pixels "
        "(records' "
        "`pixel_hash`), its status or its visibility class differ.\n\n";
}

void speed(std::ostream& md, const AuditResult& r) {
  const SpeedAudit& s = r.speed;
  if (!s.performed) return;
  md << "## Drawing time\n\n"
     << "Per platform, kind and view group: the current side's drawing time over the "
        "baseline's. The first "
     << s.options.per_view << " primitives of each kind and view were drawn alone by the "
     << "baseline, the current side and a control (the baseline again), in " << s.options.repeats
     << " rounds of fresh processes (" << s.processes << " processes, "
     << format_number(s.seconds, 3)
     << " s), the sides taking turns range by range within a round after a warm-up pass. Each "
        "round gives one estimate, the Hodges-Lehmann median of its paired per-primitive log "
        "ratios; the ratio is exp of their mean, the interval Student's t over the rounds (the "
        "rounds are the replicates: a process's luck is shared by all its primitives). A change "
        "counts only when its whole interval lies beyond the band: "
     << format_number(100 * s.options.threshold, 3)
     << "%, or the control's ratio where the control (two identical sides) moved more. Welch's t "
        "and Levene's test on Box-Cox transformed per-primitive times (one lambda), "
        "Holm-adjusted over these tests, are shown beside it; they do not decide.\n\n";
  for (const std::string& e : s.errors) md << "- Not timed: " << e << "\n";
  if (!s.errors.empty()) md << "\n";
  using stats::Align;
  md << stats::markdown_header({"platform", "kind", "group", "n", "median us before -> after",
                                "ratio [95%]", "control [95%]", "band", "Welch p (Holm)",
                                "Levene p (Holm)", "verdict"},
                               {Align::kLeft, Align::kLeft, Align::kCenter, Align::kRight,
                                Align::kRight, Align::kRight, Align::kRight, Align::kRight,
                                Align::kRight, Align::kRight, Align::kLeft});
  for (const SpeedComparison& c : s.comparisons) {
    std::string verdict = speed_verdict_name(c.verdict);
    if (c.verdict == SpeedVerdict::kUnknown)
      verdict += c.repeats_to_settle > 0
                     ? ": about " + std::to_string(c.repeats_to_settle) +
                           " repeats would settle it (--speed-repeats)"
                     : (c.reason.empty() ? ": at the band's edge" : ": " + c.reason);
    md << "| " << cell(r.pairs[c.pair].label()) << " | " << geometry::kind_name(c.kind) << " | "
       << c.group << " | " << c.n << " | " << format_number(c.baseline_median_us, 3) << " -> "
       << format_number(c.current_median_us, 3) << " | " << speed_ratio_text(c.ratio, c.low, c.high)
       << " | " << speed_ratio_text(c.control_ratio, c.control_low, c.control_high) << " | "
       << (std::isfinite(c.band) ? format_number(c.band, 4) + "x" : std::string("-")) << " | "
       << (c.welch.defined ? format_number(c.welch_p_holm, 3) : std::string("-")) << " | "
       << (c.levene.defined ? format_number(c.levene_p_holm, 3) : std::string("-")) << " | "
       << cell(verdict) << " |\n";
  }
  md << "\n";
}

void tests(std::ostream& md, const AuditResult& r) {
  const DistributionAudit& d = r.distributions;
  md << "## Distribution tests\n\n"
     << "Per platform, kind, view group and metric, baseline against current: Welch's t test "
        "(location) and Levene's test with median centre (spread), on the raw values and, where "
        "every value is > 0, on Box-Cox transformed values (one lambda, by maximum PPCC on both "
        "samples pooled). Holm-Bonferroni correction over all "
     << d.family_size << " defined tests of this audit, alpha = " << format_number(d.alpha)
     << ". Effect sizes: differences (current - baseline) of medians and IQRs (Hyndman-Fan 6), "
        "in the metric's units.\n\n";
  if (!d.significant) {
    md << "No test is significant after correction.\n\n";
    return;
  }
  using stats::Align;
  md << d.significant << " significant:\n\n"
     << stats::markdown_header({"platform", "kind", "group", "metric", "unit", "n before / after",
                                "median before -> after (diff)", "IQR before -> after (diff)",
                                "test", "data", "p", "p (Holm)"},
                               {Align::kLeft, Align::kLeft, Align::kCenter, Align::kLeft,
                                Align::kLeft, Align::kRight, Align::kRight, Align::kRight,
                                Align::kLeft, Align::kLeft, Align::kRight, Align::kRight});
  for (const DistributionComparison& c : d.comparisons)
    for (const DistributionTest& t : c.tests) {
      if (!t.significant) continue;
      const analysis::MetricSpec& m = analysis::kind_metrics(c.kind)[c.metric];
      md << "| " << cell(r.pairs[c.pair].label()) << " | " << analysis::kind_name(c.kind) << " | "
         << c.label << " | " << m.column << " | " << analysis::unit_name(m.unit) << " | "
         << c.n_before << " / " << c.n_after << " | " << format_number(c.median_before) << " -> "
         << format_number(c.median_after) << " (" << format_number(c.median_difference(), 3)
         << ") | " << format_number(c.iqr_before) << " -> " << format_number(c.iqr_after) << " ("
         << format_number(c.iqr_difference(), 3) << ") | "
         << (t.test == "welch_t" ? "Welch t" : "Levene (median)") << " | "
         << (t.data == "raw" ? std::string("raw")
                             : "Box-Cox lambda " + format_number(c.box_cox.lambda, 3))
         << " | " << format_number(t.outcome.p_value, 3) << " | " << format_number(t.p_adjusted, 3)
         << " |\n";
    }
  md << "\n";
}

void classes(std::ostream& md, const AuditResult& r) {
  md << "## Visibility classes\n\n";
  std::ostringstream rows;
  std::size_t n = 0;
  for (const ClassCountChange& c : r.classes) {
    if (c.before == c.after) continue;
    ++n;
    rows << "| " << cell(r.pairs[c.pair].label()) << " | " << analysis::kind_name(c.kind) << " | "
         << c.label << " | " << c.visibility << " | " << c.before << " | " << c.after << " | "
         << (c.after >= c.before ? "+" : "") << int64_t(c.after) - int64_t(c.before) << " |\n";
  }
  if (!n) {
    md << "Every class count is the same on both sides.\n\n";
    return;
  }
  using stats::Align;
  md << "Counts that differ (all of them: `audit.json` key `visibility`):\n\n"
     << stats::markdown_header(
            {"platform", "kind", "group", "class", "before", "after", "difference"},
            {Align::kLeft, Align::kLeft, Align::kCenter, Align::kLeft, Align::kRight, Align::kRight,
             Align::kRight})
     << rows.str() << "\n";
}

void flakes(std::ostream& md, const AuditResult& r) {
  const audit::FlakeCheckSummary& f = r.flakes;
  md << "## Flakes\n\n";
  if (!f.performed) {
    md << "The flake check was off (--max-rerenders 0): every difference counts as a change.\n\n";
    return;
  }
  md << "Every changed primitive (at most " << f.cap << ") was rendered once more in a child "
     << "process with RA_RENDER_ATTEMPT=2; a difference that disappears is a flake and does not "
     << "count as a change. "
     << (f.both_sides ? "Both platforms were rendered again (they are two platforms of one run); "
                        "a flake when the two re-renders agree.\n\n"
                      : "Only the current run was rendered again (the baseline's driver may be "
                        "gone); a flake when the re-render equals the baseline.\n\n")
     << f.checked << " re-checked in " << f.processes << " process(es), "
     << format_number(f.seconds, 3) << " s: " << f.flakes << " flake(s), " << f.still_different
     << " still different, " << f.rerender_failed << " re-render(s) failed.\n";
  if (f.not_checked)
    md << "\n**Capped**: " << f.not_checked << " changed primitive(s) beyond the cap of " << f.cap
       << " were not re-rendered; they count as changed.\n";
  md << "\n";
  list_primitives(md, r, true);
  if (r.recovered_count()) {
    md << "\nWorker failures that did not recur (the manifest lists them; the shard's re-run "
          "completed without a crash or timeout record):\n\n";
    for (const ManifestFailure& m : r.manifest_failures)
      if (m.outcome == FailureOutcome::kRecovered)
        md << "- " << m.side << " " << m.shard << ": " << m.reason << "\n";
  }
  md << "\n";
}

void failures(std::ostream& md, const AuditResult& r) {
  md << "## Failures\n\n";
  const bool none =
      r.primitives.failed.empty() && r.missing.empty() && r.flakes.failed_batches.empty() &&
      r.renderer_mismatches.empty() &&
      std::none_of(r.manifest_failures.begin(), r.manifest_failures.end(),
                   [](const ManifestFailure& m) { return m.outcome == FailureOutcome::kUnknown; });
  if (none) {
    md << "None: no crash or timeout record, no missing shard, no re-render failure.\n";
    return;
  }
  for (const auto& m : r.renderer_mismatches) md << "- driver: " << m << "\n";
  std::size_t shown = 0;
  for (const FailedPrimitive& f : r.primitives.failed)
    if (shown++ < kMarkdownListed)
      md << "- " << metrics::status_name(f.status) << ": " << f.side << " " << f.platform << " "
         << geometry::kind_name(f.kind) << ", view " << f.view << ", index " << f.index << "\n";
  if (shown > kMarkdownListed)
    md << "- ... " << shown - kMarkdownListed << " more crash/timeout records (`audit.json`)\n";
  for (const MissingShard& m : r.missing)
    md << "- missing shard: " << m.side << " " << m.id << " (" << geometry::kind_name(m.kind)
       << ", view " << m.view << ", indices " << m.begin << " to " << m.end - 1 << "): " << m.reason
       << "\n";
  for (const ManifestFailure& m : r.manifest_failures)
    if (m.outcome == FailureOutcome::kUnknown)
      md << "- manifest: " << m.side << " " << m.shard
         << " (not a shard of the experiment): " << m.reason << "\n";
  for (const audit::RerenderBatch& b : r.flakes.failed_batches)
    md << "- re-render of " << b.platform << " " << geometry::kind_name(b.kind) << ", view "
       << b.view << ", indices " << b.begin << " to " << b.end - 1 << ": " << b.error << "\n";
}

// A run audited against itself (the first night of a series) compares nothing: its page says
// what was recorded as the baseline, and no line of it reads as a comparison (no "compared",
// "unchanged", tests or class counts, which would all be of the run against itself).
std::string baseline_markdown(const AuditResult& r) {
  std::ostringstream md;
  md << "# renderaudit audit: " << upper(verdict_text(r.verdict)) << "\n\n";
  md << "**Verdict: baseline established** (exit code " << verdict_exit_code(r.verdict)
     << "): run `" << r.current.dir << "` is recorded as the baseline that later runs of this "
     << "experiment are audited "
     << "against; with nothing compared tonight, there are no changes, tests or "
     << "class counts below.\n\n";
  md << "Experiment `" << r.current.name << "` (hash " << r.current.hash << ", seed "
     << r.current.seed << "); recorded " << r.date_utc << ".\n\n";
  md << "## Drivers recorded\n\n"
     << stats::markdown_header({"platform", "GL_RENDERER", "GL_VERSION"},
                               std::vector<stats::Align>(3, stats::Align::kLeft));
  for (std::size_t p = 0; p < r.pairs.size(); ++p)
    md << "| " << cell(r.pairs[p].current) << " | " << cell(r.current_drivers[p].renderer)
       << " | " << cell(r.current_drivers[p].version) << " |\n";
  using stats::Align;
  md << "\n## Primitives recorded (per platform, kind, view group)\n\n"
     << stats::markdown_header({"platform", "kind", "group", "views", "primitives", "outcome"},
                               {Align::kLeft, Align::kLeft, Align::kCenter, Align::kLeft,
                                Align::kRight, Align::kLeft});
  for (const GroupOutcome& g : group_outcomes(r))
    md << "| " << cell(r.pairs[g.pair].current) << " | " << geometry::kind_name(g.kind) << " | "
       << g.label << " | " << views_text(g.views) << " | " << g.compared
       << " | baseline recorded |\n";
  md << "\n";
  failures(md, r);
  md << "\nFiles: `audit.json` (everything), `junit.xml` (every case skipped: nothing was "
        "judged).\n";
  return md.str();
}

}  // namespace

std::string audit_markdown(const AuditResult& r) {
  if (r.verdict == Verdict::kBaseline) return baseline_markdown(r);
  std::ostringstream md;
  md << "# renderaudit audit: " << upper(verdict_text(r.verdict)) << "\n\n";
  md << "**Verdict: " << verdict_text(r.verdict) << "** (exit code " << verdict_exit_code(r.verdict)
     << ")";
  for (std::size_t i = 0; i < r.reasons.size(); ++i) md << (i ? "; " : ": ") << r.reasons[i];
  md << ".\n\n";
  if (r.mode == "between")
    md << "Platforms `" << r.pairs[0].baseline << "` (baseline role) and `" << r.pairs[0].current
       << "` of run `" << r.current.dir << "`";
  else
    md << "Baseline `" << r.baseline.dir << "`, current `" << r.current.dir << "`";
  md << "; experiment `" << r.current.name << "` (hash " << r.current.hash << ", seed "
     << r.current.seed << "); audited " << r.date_utc << ".\n\n";
  new_violations(md, r);
  drivers(md, r);
  counts(md, r);
  speed(md, r);
  md << "## Changed primitives\n\n";
  list_primitives(md, r, false);
  md << "\n";
  tests(md, r);
  classes(md, r);
  flakes(md, r);
  failures(md, r);
  md << "\nFiles: `audit.json` (everything), `junit.xml`, `changed_primitives.csv`.\n";
  return md.str();
}

}  // namespace ra::audit
