// Drawing time in a bisection (`bisect --speed`): which kinds and view groups draw faster or
// slower at the bad ref than at the good ref, where each step's drawing time lies between the
// two, and the commits that moved it, each confirmed by drawing it beside the commit before it.
//
// Every timing is audit/speed_timing.h's: the first `per_view` primitives of each kind and view
// of the groups asked for, drawn alone by fresh processes of each side (a build drawn through the
// bisection's platform), the sides taking turns, `repeats` rounds. Times are microseconds.
//
// - The ends: the good ref, the bad ref and the good ref again (an A/A control) are timed over
//   every kind and view group of the run (less --kind/--view); audit/speed_audit.h's verdict of
//   bad over good says which groups moved (`faster`, `slower`); `same` is nothing to attribute,
//   `unknown` is reported but not bisected (the noise hides whether it moved).
// - A step: the good ref, the step and the bad ref are timed together over the groups whose
//   unresolved range holds the step. Per group (place_step) the step is "as good" or "as bad"
//   when the 95% interval of where its time lies between the ends' times, on a log scale, lies
//   wholly on one side of the middle; else it is timed again once (the rounds pooled) and, still
//   undecided, "unknown" there: the plan (bisect_plan.h) then builds a neighbour instead. A group
//   unknown at 3 steps is given up and reported unattributed (its time moved in small steps, or
//   the machine is too noisy): a group whose time moved in several commits is attributed to the
//   one that carries it past the middle of its ends' times.
// - The culprit: the commit where a group's time changes from "as good" to "as bad" between
//   neighbouring built commits; its confirmation is the commit over its git parent, timed with
//   an A/A control, the ratio stdout and the report give. With paths, the line's neighbour can lie
//   many commits back: the parent is built and placed like a step, and a group it already draws
//   as the culprit does is not the culprit's: it is reported unattributed, its move among the
//   commits outside the paths between the two, with the bisection that would name it.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "audit/speed_audit.h"
#include "geometry/primitive.h"

namespace ra::triage {

struct BisectOptions;

struct BisectSpeedOptions {
  bool enabled = false;     // --speed
  int repeats = 10;         // rounds per timing, each a fresh process per side (>= 2)
  uint64_t per_view = 100;  // primitives of each kind and view timed
  double threshold = 0.05;  // a change counts when its whole interval lies beyond this
};

// One kind and view group whose drawing time is judged.
struct SpeedGroup {
  geometry::Kind kind = geometry::Kind::kPoint;
  int view_group = 0;  // 0 = A
  // "triangles, view group D"
  std::string text() const;
  // "drawing time of triangles, view group D": its label in the attribution plan, beside the
  // primitives' labels ("triangle 3 of view 1")
  std::string label() const;
  bool operator<(const SpeedGroup& o) const {
    return kind != o.kind ? kind < o.kind : view_group < o.view_group;
  }
  bool operator==(const SpeedGroup& o) const { return kind == o.kind && view_group == o.view_group; }
};

// A group's time at the ends: the bad ref over the good ref, the good ref again as the control.
struct SpeedAtEnds {
  SpeedGroup group;
  audit::SpeedComparison comparison;
  bool moved() const {
    return comparison.verdict == audit::SpeedVerdict::kFaster ||
           comparison.verdict == audit::SpeedVerdict::kSlower;
  }
};

enum class TimePlace { kAsGood, kAsBad, kUnknown };
const char* time_place_name(TimePlace p);  // "as good", "as bad", "unknown"
TimePlace parse_time_place(const std::string& name);  // throws std::invalid_argument

// Where one step's drawing time of one group lies.
struct StepTime {
  SpeedGroup group;
  TimePlace place = TimePlace::kUnknown;
  // the step over the good ref: ratio and 95% interval over the rounds (NaN: none)
  double ratio = 0, low = 0, high = 0;
  // where the step's time lies between the ends' on a log scale: 0 the good ref's, 1 the bad
  // ref's; its 95% interval
  double share = 0, share_low = 0, share_high = 0;
  int repeats = 0;    // rounds it rests on
  std::string note;   // why unknown when no interval could be formed
};

// The place of a step from the three sides' times of one group (audit/speed_timing.h's
// RoundTimes, the same primitives and rounds on each side). Per round r, a_r is the
// Hodges-Lehmann log ratio of the step over the good ref and b_r that of the bad ref over the good
// ref; the step is "as bad" when the 95% Student's t interval of sign(mean b) (a_r - b_r / 2) lies
// above 0, "as good" when below, else unknown. share = mean a / mean b.
StepTime place_step(const audit::RoundTimes& good, const audit::RoundTimes& step,
                    const audit::RoundTimes& bad);

// A commit that moved the drawing time of one or more groups.
struct SpeedCulprit {
  std::string commit, subject, date;
  std::string previous;  // the commit before it on the line (with paths: the paths' previous)
  // The commit the confirmation drew it beside: its git parent (first parent); `previous` only
  // when the parent differs and failed to build, `beside_note` then saying so.
  std::string beside, beside_note;
  struct Move {
    SpeedGroup group;
    audit::SpeedVerdict direction = audit::SpeedVerdict::kUnknown;  // at the ends: faster, slower
    audit::SpeedComparison confirmation;  // the commit over `beside`, with an A/A control
    std::string error;                    // the confirmation could not be timed: why
    TimePlace at_culprit = TimePlace::kAsBad;  // the culprit's place (as good: a move back)
  };
  std::vector<Move> moves;
  // With paths that left commits out before it: where its git parent's time lies, per move.
  std::vector<StepTime> parent_places;
};

// The builds a culprit's confirmation draws with: the ends', the line's commit before it, its own.
struct CulpritBuilds {
  std::string good, previous, culprit, bad;
};

// A group whose time moved between the ends but whose commit cannot be named.
struct SpeedUnattributed {
  SpeedGroup group;
  std::string from, to;                 // the commits with a decided place on either side
  std::vector<std::string> candidates;  // only failed builds between: the commits that may have
  std::string why;
  std::string next_command;  // the bisection that would name it, where one can ("": none)
};

// The kinds and view groups of the run that a bisection times: those with primitives, less what
// --kind and --view leave out.
std::vector<SpeedGroup> speed_groups(const BisectOptions& o);

// The ends timed (the good ref, the bad ref, the good ref again) over `groups`. Throws
// util::UserError when a side cannot be timed.
std::vector<SpeedAtEnds> time_ends(const BisectOptions& o, const std::vector<SpeedGroup>& groups,
                                   const std::string& good_build, const std::string& bad_build,
                                   const std::function<void(const std::string&)>& say);

// A step's time placed between the ends' for each of `groups`; timed once more where a group is
// unknown. A side that cannot be timed leaves every group unknown, with the reason in `note`.
std::vector<StepTime> time_step(const BisectOptions& o, const std::vector<SpeedGroup>& groups,
                                const std::string& good_build, const std::string& step_build,
                                const std::string& bad_build,
                                const std::function<void(const std::string&)>& say);

// Each move of `c` confirmed: the culprit's build over its git parent's, with a control. The
// parent is `c.previous` unless paths left commits out between them; then the parent is built
// (the source tree left at it) and placed between the ends as a step is: a move it already has
// (placed where the culprit is) leaves `c` for `unattributed`, with the bisection without paths
// that would name it.
void confirm_speed_culprit(const BisectOptions& o, SpeedCulprit& c, const CulpritBuilds& at,
                           std::vector<SpeedUnattributed>& unattributed,
                           const std::function<void(const std::string&)>& say);

// The stdout lines of a culprit: one "first slower commit: HASH SUBJECT (GROUP: RATIO x [LOW,
// HIGH]; ...)" for its slower groups, one "first faster commit: ..." for its faster ones; `lead`
// opens the parenthesis (watch: "PLATFORM: ").
std::vector<std::string> speed_culprit_lines(const SpeedCulprit& c, const std::string& lead = "");

}  // namespace ra::triage
