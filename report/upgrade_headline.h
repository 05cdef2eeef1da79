// The driver upgrade report's first sentence (scripts/driver-upgrade.sh): what a new Mesa changed,
// said as a driver developer would say it, from the counts of the audits alone:
//
//   "llvmpipe 25.0.7 stops drawing 595 of 20,000 lines of the FOV-30 907 x 907 views; 799 lines
//    break GL's line rules, 595 of them not drawn at all; 1,210 of 80,000 triangles light other
//    pixels, as GL allows (identical through OSMesa and EGL); softpipe unchanged."
//
// "Not drawn" is a primitive that was true-visible (lit where it should be) and is now
// false-invisible (nothing lit where something should be, docs/records.md); a rule broken is a
// new GL violation (metrics/conformance.h: after "violation", before anything else). The two
// overlap, and the sentence says how: of the lines that break the rules, how many are among those
// not drawn ("595 of them not drawn at all"); a primitive not drawn that breaks no new rule (its
// rules were already broken, or not judged) is among the last clause's "more" ("1 more line
// changes where GL's rules were not judged or already broken (not drawn)"), so that the counts of
// a kind add up for a reader: not drawn = not drawn and breaking the rules + not drawn in the last
// clause. A summary written before it kept that overlap says the counts without it. Platforms
// are named BACKEND-DRIVER (osmesa-llvmpipe); the pairs of one driver whose changes are the same
// primitives drawn the same way (equal fingerprints and counts) are said once, "identical
// through OSMesa and EGL". No number is written here: every one comes from the summary.
//
// Where the audits judged drawing time (`audit --speed`), a second sentence says it:
//
//   "llvmpipe 25.0.7 draws the lines of the FOV-30 907 x 907 views 16% slower (95%: 9-24%) and
//    the triangles of the FOV-150 907 x 907 views 22% faster (95%: 20-25%); other drawing times
//    unchanged or not measurably different; the drawing time of 2 groups could not be judged at
//    this noise."
//
// Only the groups (a kind in a view group of a pair) the audit called faster or slower are said, in
// the summary's order, one clause per kind and verdict over the view groups it holds (named as the
// pixel part names them). The percentages are of the time ratio upgraded / installed: faster,
// 1 - ratio (its interval 1 - high .. 1 - low); slower, ratio - 1 (low - 1 .. high - 1); the
// estimate rounded, the interval rounded outwards so that it still holds the audit's; a clause
// over several groups gives the range of their estimates ("21-22% faster") and one interval
// holding all of theirs. Pairs of one driver that call the same groups faster and slower are said
// once, "llvmpipe 25.0.7 through OSMesa and EGL draws ...", their numbers held the same way; pairs
// that differ are said one by one, each through its back end. The groups judged the same and the
// unknown ones are counted over every pair. A summary without drawing times (from audits without
// --speed, or written before they were kept) gives the first sentence alone.
//
// The summary is the file scripts/upgrade_report.py writes (OUT/upgrade-summary-BUILD.json, schema
// "renderaudit-upgrade-summary" version 1): the run, the build's name, the view groups and per pair
// of platforms the counts below per kind and view group, and, where its audit judged drawing time,
// the verdicts (`speed`). `speed` and a stratum's `not_drawn_violations` are optional keys of
// version 1, not a version 2: no key that was there changed meaning, this reader takes summaries
// with and without them, and an older one, which checks the keys it reads and ignores others,
// reads a summary with them as before. A bisection of
// the run (RUN/bisect/bisect.json, RUN/../bisect/bisect.json or RUN/audit-*/bisect/bisect.json,
// schema "renderaudit-bisection" version 3, sealed, or 2, written by `renderaudit bisect`) adds its
// culprits. Both files are read field by field: a missing or mistyped field, counts that do not
// add up (more not drawn than changed, more changed than compared, more not drawn and breaking the
// rules than either), a total past 2^62, or a time
// ratio that contradicts its verdict (a faster group whose interval reaches 1) is a UserError
// naming the file and the key.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ra::report {

// The changed primitives of one kind in one view group of one pair, counted by what changed.
struct UpgradeStratum {
  std::string kind;   // "point", "line", "triangle"
  std::string group;  // view group label, "A".."D"
  std::int64_t compared = 0;          // primitives drawn on both sides
  std::int64_t changed = 0;           // pixels, status or visibility differ
  std::int64_t not_drawn = 0;         // true-visible -> false-invisible
  std::int64_t newly_drawn = 0;       // false-invisible -> true-visible
  std::int64_t new_violations = 0;    // after a GL violation, before none
  std::int64_t fixed_violations = 0;  // before a violation, after none
  std::int64_t allowed = 0;           // before and after drawn as GL allows, other pixels
  // not drawn and a new violation (of both counts above); -1: the summary does not say (written
  // before its optional key `not_drawn_violations`)
  std::int64_t not_drawn_violations = -1;
};

// A view group: its label and what its views share (degrees, pixels).
struct UpgradeViewGroup {
  std::string label;  // "A"
  int fov_deg = 0;    // vertical field of view
  int window = 0;     // square window side
};

// The drawing time of one kind in one view group of one pair, as its audit judged it
// (audit/speed_audit.h): ratio = upgraded / installed time, dimensionless, with its 95% interval.
struct UpgradeTime {
  std::string kind;                     // "point", "line", "triangle"
  std::string group;                    // view group label, "A".."D"
  double ratio = 0, low = 0, high = 0;  // > 0; NaN where no interval could be formed (unknown)
  std::string verdict;  // "faster" (high < 1), "slower" (low > 1), "same", "unknown"
};

// One platform against its build: "osmesa-llvmpipe" against "osmesa-llvmpipe@backports".
struct UpgradePair {
  std::string platform, build_platform;
  std::string installed_version, build_version;  // GL_VERSION of each side
  std::string fingerprint;  // of the changed primitives and their pixels after (equal: identical)
  std::vector<UpgradeStratum> strata;
  bool timed = false;              // its audit judged drawing time (the summary has `speed`)
  std::vector<UpgradeTime> speed;  // per kind and view group, in the audit's order
};

struct UpgradeSummary {
  std::string run_dir;  // the run the audits read
  std::string build;    // "backports"
  std::vector<UpgradeViewGroup> groups;
  std::vector<UpgradePair> pairs;
};

// A culprit of a bisection: the first commit that drew some primitives otherwise.
struct UpgradeCulprit {
  std::string commit, subject;
  std::int64_t primitives = 0;
};

struct UpgradeBisection {
  std::string path;      // the bisect.json
  std::string platform;  // the platform it drew
  std::int64_t selected = 0;  // primitives it followed
  bool complete = false;
  std::vector<UpgradeCulprit> culprits;
};

// The sentence (see the header comment), ending with a full stop, and after it the sentence on
// drawing time where any pair was timed; "no platform was audited." for an empty summary.
std::string upgrade_headline(const UpgradeSummary& summary);

// "25.0.7" from a GL_VERSION ("4.5 (Compatibility Profile) Mesa 25.0.7-2~bpo12+1", without the
// distribution's revision; "26.0.0-devel" kept); "" if none.
std::string mesa_version(const std::string& gl_version);

// The summary in `path`. Throws util::UserError naming the file and the key of what is wrong.
UpgradeSummary read_upgrade_summary(const std::string& path);

// The bisections of the run beside or under it (see the header comment), each read from its
// file; a file of another schema is skipped, a damaged one (its seal, a field) is a UserError.
std::vector<UpgradeBisection> find_bisections(const std::string& run_dir);

// A bisection in words: "Bisection of egl-llvmpipe (FILE, 500 primitives): first bad commit
// `HASH` \"SUBJECT\" (412 primitives)." (the hash shortened to 12 digits).
std::string bisection_sentence(const UpgradeBisection& bisection);

// The report's opening in Markdown: the sentence in bold, then one line per bisection.
std::string upgrade_headline_markdown(const UpgradeSummary& summary);

}  // namespace ra::report
