// A run's conformance verdicts judged for CI against an expectations file: the violations of GL's
// (or Vulkan's) rasterization rules already known for each platform, kept beside the driver as
// deqp-runner's users keep `*-fails.txt`. A violation the file lists is known (passes), one it
// does not list is new (fails), and a listed primitive now drawn without violation is fixed
// (reported, as deqp-runner's UnexpectedImprovement, so that the list is kept true).
//
// The file is plain text, one primitive per line, sorted, so that a merge request shows each
// change as one line:
//
//   # Known violations of GL's rasterization rules (renderaudit conformance --expectations).
//   osmesa-softpipe line 5 721  # 3 px: line-column
//   osmesa-softpipe triangle 7 88  # 1 px: polygon-edge
//
// The fields are PLATFORM KIND VIEW INDEX: the platform as the experiment names it, the kind
// (point, line, triangle), the view's id (1-based, as records, `show` and violations.md give it)
// and the primitive's index under the experiment's seed. '#' starts a comment to the end of the
// line; blank lines are skipped. The indices mean something only for the experiment (seed, views,
// counts) of the run the file was written from: a line naming a platform, view or index that
// experiment does not have is an error (FILE:LINE), not a silent pass.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::analysis {

// One line of an expectations file.
struct ExpectedViolation {
  std::string platform, kind;  // kind: "point", "line", "triangle"
  int view = 0;                // 1-based view id
  std::uint64_t index = 0;
  int line = 0;  // 1-based line of the file
  // "osmesa-softpipe line 5 721": the line's fields, as the file writes them
  std::string name() const;
};

struct Expectations {
  std::string path;
  std::vector<ExpectedViolation> entries;  // in file order
};

// Parses an expectations file's text. Every malformed line (fields missing or extra, an unknown
// kind, a view or index that is not a number, a primitive listed twice) is reported, each as
// "PATH:LINE: what is wrong; what to do", in one util::UserError.
Expectations parse_expectations(const std::string& text, const std::string& path);
// The same, reading the file (a file that cannot be read is a util::UserError naming it).
Expectations read_expectations(const std::string& path);

// A primitive of the run whose verdict is `violation`.
struct FoundViolation {
  std::string platform, kind;
  int view = 0;
  std::uint64_t index = 0;
  std::int64_t violating_pixels = 0;
  std::string rules;         // violated_rules as recorded, e.g. "line-column"
  int expected_at = 0;       // its line in the expectations file; 0: not listed (new)
  std::string name() const;  // "faulty line 1 17"
};

// A listed primitive that is no longer a violation, or could not be judged.
struct ListedOutcome {
  ExpectedViolation listed;
  std::string now;  // its class now ("exact", "snapped", "within-spec"), or why it has no verdict
};

// One platform x kind x view of the run: the unit of a CI test case.
struct ConformanceCase {
  std::string platform, kind;
  int view = 0;
  std::string view_label;     // "150 deg, 64x64"
  std::uint64_t records = 0;  // records of it in the run
  std::uint64_t judged = 0;   // of them, with a verdict (status ok, not the reference platform)
  std::vector<FoundViolation> violations;  // every one, known and new, by index
  std::vector<ListedOutcome> fixed;        // listed, and judged without violation now
  std::vector<ListedOutcome> not_judged;   // listed, and the record has no verdict (crash, ...)
  std::size_t new_count() const;
};

struct ConformanceCheck {
  std::string run_dir;
  std::string experiment, experiment_hash;
  std::string expectations_path;       // "" when none was given
  std::vector<ConformanceCase> cases;  // platform (experiment order), kind, view
  // Listed primitives of a platform of the experiment that this run did not draw (`run
  // --platform`): not judged, said.
  std::vector<ExpectedViolation> platform_not_run;
  std::uint64_t judged() const;
  std::size_t violations() const;
  std::size_t new_violations() const;
  std::size_t fixed() const;
  std::size_t not_judged() const;  // not_judged of every case and platform_not_run
};

// Reads every records file of `run_dir` (its verdicts only) and judges them against
// `expectations` (nullptr: nothing is known, every violation is new). A line of the file that
// names a platform, view or index the run's experiment does not have is an error
// "PATH:LINE: ...; remove the line or ..." (every such line, in one util::UserError).
ConformanceCheck check_conformance(const std::string& run_dir, const Expectations* expectations);

// The run's violations as an expectations file (every one, known or new, sorted by platform,
// kind, view and index; a header comment naming the experiment it belongs to).
std::string expectations_text(const ConformanceCheck& c);

// JUnit XML for CI: one test suite per platform, one test case per platform x kind x view
// (classname "renderaudit.conformance.PLATFORM.KIND", name "view V (150 deg, 64x64)"), failing
// when it holds violations the expectations do not list; the new ones in the failure's text, each
// with the `renderaudit show` command that draws it; the known and fixed ones in system-out. A
// case without a verdict (the reference platform) is skipped.
std::string conformance_junit(const ConformanceCheck& c);

// What the command prints: one line with the counts, then the new violations (at most `limit`,
// each with its show command), the fixed and the not-judged listed ones, and the verdict line
// "conformance: PASS ..." or "conformance: FAIL ..." (the first line alone when not `verdict`).
std::string conformance_text(const ConformanceCheck& c, bool verdict = true,
                             std::size_t limit = 20);

}  // namespace ra::analysis
