// Table 6 and the system-task constant c over repeated, independent runs of the whole study
// measurement (the [timing] key study_runs; Wimmer & Wonka 2003, Table 6 and section 4.2): each
// Table 6 cell and c as mean, standard deviation, min-max and a Student-t interval of the mean
// across the runs; per run and scene the methods ranked by average squared error, and how often
// each was the best.
//
// Why: Table 6 rests on one measurement of wall-clock times, and its ranking of the heuristics
// moved between two runs on the same machine; one table cannot say by how much it can move.
//
// Pure (no GL, no files): the study (timing_run.cpp) hands it what each run's analysis gave, so it
// is tested on hand-made numbers.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace ra::timing {

// One platform's result in one run of the study.
struct RunOutcome {
  bool ok = false;  // false: the run's measurement failed; it is left out of every aggregate
  std::map<std::string, std::map<std::string, double>> table6_ms2;  // scene -> method -> ms^2
  double c_us = 0;    // system-task constant c = q_0.99 - min of that run, microseconds
  double wall_s = 0;  // seconds the run's measurement of the platform took
};

// One quantity across the runs, in the units of its values. Non-finite values (a method that
// could not be evaluated in a run) are left out and not counted in n.
struct RunSpread {
  std::vector<double> values;  // per aggregated run, in run order (as given, NaN included)
  std::size_t n = 0;           // finite values aggregated
  double mean = 0;             // NaN when n = 0
  double sd = 0;               // sample standard deviation (n - 1); NaN when n < 2
  double min = 0, max = 0;     // NaN when n = 0
  double confidence = 0.95;    // of the interval below
  double ci_low = 0;           // mean -+ t_{(1+confidence)/2, n-1} sd / sqrt(n); NaN when n < 2
  double ci_high = 0;
};

// Mean, SD, min-max and the two-sided Student-t interval of the mean of `values`.
// confidence in (0, 1).
RunSpread spread_over_runs(const std::vector<double>& values, double confidence = 0.95);

// `methods` ordered from the lowest to the highest error in `errors` (method -> ms^2); a method
// missing from `errors` or with a non-finite error goes last; ties keep the order of `methods`.
std::vector<std::string> rank_methods(const std::map<std::string, double>& errors,
                                      const std::vector<std::string>& methods);

// True for the columns of the paper's own Table 6: h1..h4 without intercept and pos.
bool is_paper_method(const std::string& method);

// Per scene: the ranking of every run and how often each method won (ranked first).
struct SceneRanking {
  std::vector<std::vector<std::string>> per_run;  // per aggregated run: methods, best first
  std::map<std::string, int> wins;        // method -> runs it had the lowest error of all methods
  std::map<std::string, int> paper_wins;  // the same among the paper's forms (is_paper_method)
  int runs_without_winner = 0;            // runs where no method had a finite error
};

// One platform over the repeated runs.
struct RepeatedPlatform {
  std::string platform;
  int runs = 0;    // runs whose measurement succeeded (aggregated)
  int failed = 0;  // runs whose measurement failed (left out)
  std::vector<std::string> methods;                                     // Table 6's columns
  std::map<std::string, std::map<std::string, RunSpread>> table6_ms2;  // scene -> method, ms^2
  std::map<std::string, SceneRanking> ranking;                          // per scene
  RunSpread c_us;                // the system-task constant c, microseconds
  std::vector<double> wall_s;    // every run's measuring time, failed runs included, seconds
};

// Aggregates `runs` (one per run of the study, in order) of `platform`. `methods` are Table 6's
// columns in their order (every method counted in wins, with 0 when it never won); the scenes are
// those of the successful runs.
RepeatedPlatform aggregate_runs(const std::string& platform, const std::vector<std::string>& methods,
                                const std::vector<RunOutcome>& runs, double confidence = 0.95);

}  // namespace ra::timing
