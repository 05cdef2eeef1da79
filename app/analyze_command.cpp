// `renderaudit analyze DIR`: the command line of analysis/run_analysis.h's analyze_run, and of
// the studies' analyses (app/study_dispatch.cpp) for a study folder.
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "analysis/run_analysis.h"
#include "analysis/run_completeness.h"
#include "app/commands.h"
#include "util/errors.h"
#include "util/number_text.h"

namespace ra::app {

void register_analyze_command(CLI::App& app, int& exit_code) {
  struct Options {
    std::string dir;
    double alpha = 0.05;
    std::vector<double> pitches;
    std::string quantiles = "hf6";
    unsigned jobs = 0;
    std::size_t box_cox_subsample = 10000;
    bool timings = false;
    bool allow_incomplete = false;
    int bootstrap = 2000;
    std::uint64_t seed = 2008;
    std::string paper;
    double point_margin_px = 0;
    bool quiet = false;
  };
  auto o = std::make_shared<Options>();
  auto* cmd = app.add_subcommand(
      "analyze",
      "The paper's section-4 analysis of a run directory, from its records alone: equivalence of "
      "orientation views (t, F, Levene; raw and Box-Cox), Tables 2-11 as CSV, Markdown and LaTeX, "
      "the cross-platform comparison, render time beside error, and figure data; writes "
      "DIR/analysis/ and prints the tables. For a study folder (study.json: the LOD or regulation "
      "study), that study's analysis.");
  cmd->add_option("dir", o->dir, "run directory written by `renderaudit run`")->required();
  cmd->add_option("--alpha", o->alpha, "significance level of the tests (default 0.05)");
  cmd->add_option("--pixel-pitch-mm", o->pitches,
                  "pixel pitch in mm for Table 11; a list for several displays, e.g. "
                  "0.255,0.294,1.5 (default 0.255, the paper's LCD)")
      ->delimiter(',');
  cmd->add_option("--quantiles", o->quantiles,
                  "quartile definition: hf6 (Hyndman-Fan 6, NIST e-Handbook / Dataplot; default) "
                  "or hf7 (R and NumPy default)")
      ->check(CLI::IsMember({"hf6", "hf7"}));
  cmd->add_option("--jobs", o->jobs, "threads (default: the number of cores)");
  cmd->add_option("--box-cox-subsample", o->box_cox_subsample,
                  "Box-Cox lambda is chosen on at most this many order statistics of the pooled "
                  "data (default 10000)");
  cmd->add_option("--bootstrap", o->bootstrap,
                  "bootstrap resamples for the standard error and 95% interval of every median "
                  "and IQR (uncertainty.md; default 2000, 0: none)")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--bootstrap-seed", o->seed, "seed of the bootstrap (default 2008)");
  cmd->add_option("--paper", o->paper,
                  "the paper's published values to set beside ours (paper_comparison.md; default "
                  "experiments/papers/nist2008-tables.toml; none: no comparison)");
  cmd->add_option("--point-margin-px", o->point_margin_px,
                  "count true-invisible points within this many pixels outside the window as "
                  "false-invisible, the paper's apparent convention (0.5 reproduces its Table 2; "
                  "default 0: the records' classes)")
      ->check(CLI::Range(0.0, 16.0));
  cmd->add_flag("--timings", o->timings, "print the time each stage took");
  cmd->add_flag("--quiet,-q", o->quiet,
                "print only where the files went, not the tables (they are in DIR/analysis/)");
  cmd->add_flag("--allow-incomplete", o->allow_incomplete,
                "analyse a run with missing or damaged shards (README.md and the summary say "
                "what is missing); without it such a run is refused with exit code 3");
  cmd->callback([o, &exit_code] {
    if (app::analyze_study_if_present(o->dir, exit_code)) return;
    analysis::AnalyzeOptions options;
    options.run_dir = o->dir;
    options.alpha = o->alpha;
    if (!o->pitches.empty()) options.pixel_pitches_mm = o->pitches;
    options.quantiles = o->quantiles == "hf7" ? stats::QuantileDefinition::kHyndmanFan7
                                              : stats::QuantileDefinition::kHyndmanFan6;
    options.jobs = o->jobs;
    options.box_cox_subsample = o->box_cox_subsample;
    options.allow_incomplete = o->allow_incomplete;
    if (o->bootstrap == 1)
      throw util::UserError("--bootstrap 1: use 0 (none) or at least 2 resamples");
    options.bootstrap_resamples = o->bootstrap;
    options.bootstrap_seed = o->seed;
    options.paper_values = o->paper;
    options.point_margin_px = o->point_margin_px;
    analysis::AnalyzeResult r;
    try {
      r = analysis::analyze_run(options);
    } catch (const analysis::IncompleteRunError& e) {
      std::fprintf(stderr, "renderaudit analyze: %s\n", e.what());
      exit_code = kExitIncomplete;
      return;
    }
    if (!o->quiet) std::cout << r.summary;
    if (o->timings) {
      std::cout << "Timings (s):";
      for (const auto& t : r.timings)
        std::cout << util::format_text(" %s %.3f", t.stage.c_str(), t.seconds);
      std::cout << "\n";
    }
    std::cout << "Wrote " << r.files.size() << " files to " << r.out_dir
              << " (README.md lists them; every table in report.md).\n";
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
