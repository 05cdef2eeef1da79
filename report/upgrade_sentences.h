// The driver upgrade report's opening sentences (scripts/driver-upgrade.sh). The first says what a
// new Mesa changed, as a driver developer would say it, from the counts of the audits alone:
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
// The summary is report/upgrade_summary.h's document (RUN/upgrade-summary-BUILD.json). A bisection
// of the run (RUN/bisect/bisect.json, RUN/../bisect/bisect.json or RUN/audit-*/bisect/bisect.json,
// written by `renderaudit bisect`) adds its culprits, read by rundir/bisection_document.h: a
// missing or mistyped field is a UserError naming the file and the key.
#pragma once

#include <string>
#include <vector>

#include "report/upgrade_summary.h"
#include "rundir/bisection_document.h"

namespace ra::report {

// The sentence (see the header comment), ending with a full stop, and after it the sentence on
// drawing time where any pair was timed; "no platform was audited." for an empty summary.
std::string upgrade_sentences(const UpgradeSummary& summary);

// "25.0.7" from a GL_VERSION ("4.5 (Compatibility Profile) Mesa 25.0.7-2~bpo12+1", without the
// distribution's revision; "26.0.0-devel" kept); "" if none.
std::string mesa_version(const std::string& gl_version);

// The bisections of the run beside or under it (see the header comment), each read from its file
// (rundir/bisection_document.h); a file of another schema is skipped, a damaged one (its seal, a
// field) is a UserError.
std::vector<rundir::BisectionDocument> find_bisections(const std::string& run_dir);

// A bisection in words: "Bisection of egl-llvmpipe (FILE, 500 primitives): first bad commit
// `HASH` \"SUBJECT\" (412 primitives)." (the hash shortened to 12 digits).
std::string bisection_sentence(const rundir::BisectionDocument& bisection);

// The report's opening in Markdown: the sentence in bold, then one line per bisection.
std::string upgrade_sentences_markdown(const UpgradeSummary& summary);

}  // namespace ra::report
