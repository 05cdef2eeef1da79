// One night of the branch-following audit (see the header).
#include "triage/watch.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <toml++/toml.h>

#include "audit/history_db.h"
#include "rundir/audit_document.h"
#include "rundir/experiment.h"
#include "rundir/manifest.h"
#include "rundir/platform_spec.h"
#include "rundir/run_folder.h"
#include "builds/git_command.h"
#include "triage/bisect.h"
#include "triage/watch_state.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/dir_lock.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/interrupt.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

using builds::git;

std::string short_hash(const std::string& c) { return c.substr(0, 12); }

// The platforms of the experiment file, each of which must be able to draw a driver build.
std::vector<std::string> watched_platforms(const std::string& file, const toml::table& t) {
  const toml::array* list = t["platforms"].as_array();
  if (!list || list->empty())
    throw util::UserError("watch: " + file + ": platforms: must name the platforms to watch");
  std::vector<std::string> platforms;
  for (const toml::node& n : *list) {
    const std::string p = n.value_or(std::string());
    if (p.find('@') != std::string::npos || !rundir::find_platform(p + "@" + kTonightBuild))
      throw util::UserError("watch: " + file + ": platforms: '" + p +
                            "' cannot draw a driver build (allowed: the osmesa-* and surfaceless "
                            "egl-* platforms, vk-lavapipe, faulty, without @BUILD)");
    platforms.push_back(p);
  }
  return platforms;
}

toml::table parse_toml(const std::string& file) {
  try {
    return toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    throw util::UserError("watch: " + file + ": " + std::string(e.description()));
  }
}

// The experiment with each platform P drawn by last night's and tonight's builds. The file's path
// is written into a comment as a JSON string (escaped): a line break in it would end the comment
// and make the rest of the path TOML of the night's experiment.
std::string night_experiment(const std::string& file, const std::string& last_dir,
                             const std::string& tonight_dir) {
  toml::table t = parse_toml(file);
  toml::array both;
  for (const std::string& p : watched_platforms(file, t)) {
    if (!last_dir.empty()) both.push_back(p + "@" + kLastBuild);
    both.push_back(p + "@" + kTonightBuild);
  }
  t.insert_or_assign("platforms", both);
  if (!t["builds"].as_table()) t.insert_or_assign("builds", toml::table{});
  toml::table& builds = *t["builds"].as_table();
  if (!last_dir.empty()) builds.insert_or_assign(kLastBuild, toml::table{{"dir", last_dir}});
  builds.insert_or_assign(kTonightBuild, toml::table{{"dir", tonight_dir}});
  std::ostringstream out;
  out << "# the experiment file as `renderaudit watch` ran it tonight: "
      << nlohmann::json(file).dump(-1, ' ', true, nlohmann::json::error_handler_t::replace) << "\n"
      << t << "\n";
  return out.str();
}

// This program, run as a child with its output in `log`; returns the exit code. The child has a
// process group of its own that a signal to this process stops (util/interrupt.h), so a night
// interrupted during its run or audit stops them with it rather than waiting for their end.
int run_self(const std::vector<std::string>& args, const std::string& log) {
  util::throw_if_interrupted();
  util::ChildSpec spec;
  spec.argv = {fs::read_symlink("/proc/self/exe").string()};
  spec.argv.insert(spec.argv.end(), args.begin(), args.end());
  spec.stdin_null = true;
  spec.own_process_group = true;
  spec.log_to(log);
  const util::Child c = util::start_child(spec);
  util::set_interruptible_group(c.pid);
  const int status = util::wait_child(c.pid);
  util::set_interruptible_group(0);
  util::throw_if_interrupted();
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

std::vector<std::string> night_lines(const WatchNight& n) {
  std::vector<std::string> lines;
  lines.push_back("night: " + n.verdict + ": " + n.note +
                  (n.commit.empty() ? std::string() : " (" + n.commit.substr(0, 12) + ")"));
  if (!n.dir.empty()) lines.push_back("details: " + n.dir + "/night.md");
  for (const std::string& c : n.culprits) lines.push_back("first bad commit: " + c);
  for (const std::string& c : n.speed_culprits) lines.push_back(c);
  for (const std::string& u : n.unattributed) lines.push_back("unattributed: " + u);
  for (const std::string& p : n.not_bisected) lines.push_back("not bisected: " + p);
  return lines;
}

namespace {

class Night {
 public:
  Night(const WatchOptions& o, const std::function<void(const std::string&)>& progress)
      : o_(o), progress_(progress) {}

  WatchNight run() {
    std::error_code ec;
    fs::create_directories(o_.state, ec);
    if (ec || !fs::is_directory(o_.state, ec))
      throw util::UserError(util::io_error_message("watch: cannot create", o_.state));
    const util::DirLock lock(o_.state, "watch", "one night at a time; wait for it to finish");
    // A signal stops the build's, the run's or the audit's process group and ends the night
    // unrecorded (util::Interrupted).
    util::InterruptScope interrupts;
    if (o_.db.empty()) o_.db = o_.state + "/history.sqlite";
    if (!fs::is_regular_file(o_.experiment, ec))
      throw util::UserError("watch: --experiment " + o_.experiment + " is not a file");
    if (!fs::is_directory(o_.source, ec) || !git(o_.source, {"rev-parse", "--git-dir"}).ok)
      throw util::UserError("watch: " + o_.source + " is not a git checkout");
    o_.source = fs::canonical(o_.source).string();
    // Bad input is refused here, before anything is fetched or built, and is no night.
    LastNight last = read_last(o_.state + "/watch.json");
    check_same_tree(last);
    check_experiment(last.build_dir);

    n_.date_utc = rundir::utc_now_iso8601();
    n_.previous_commit = last.commit;
    const Unseen unseen = branch_head(last.branch);
    if (!unseen.verdict.empty()) {
      say(unseen.why);
      return finish(unseen_night(unseen.verdict, unseen.why));
    }
    say("tonight: " + short_hash(n_.commit) + " " + subject(n_.commit) +
        (last.commit.empty() ? " (no baseline yet)" : "; last night: " + short_hash(last.commit)));
    const bool descends =
        !last.commit.empty() &&
        git(o_.source, {"merge-base", "--is-ancestor", "--end-of-options", last.commit, n_.commit})
            .ok;
    const NightKind kind = night_kind(last.commit, n_.commit, descends);
    if (kind == NightKind::nothing_new) return finish(nothing_new_night());
    n_.dir = o_.state + "/nights/" + night_folder_name(n_.date_utc);
    fs::create_directories(n_.dir, ec);

    // Tonight's build.
    builds::SourceBuildOptions b = o_.build;
    b.source = o_.source;
    b.ref = n_.commit;
    b.probe = false;  // the run is the probe
    // Last night's build, held against `builds remove` all night; built again if it is gone.
    builds::SourceBuildResult last_build;
    if (kind == NightKind::compare) {
      last_build = builds::use_source_build(last.build_dir, last.commit, b, [&](const std::string& s) { say("  " + s); });
      last.build_dir = last_build.build.dir;
    }
    builds::SourceBuildResult built;
    try {
      built = builds::build_from_source(b, [&](const std::string& s) { say("  " + s); });
    } catch (const util::UserError& e) {
      util::throw_if_interrupted();  // stopped, not failed: nothing recorded
      const std::string error_file = n_.dir + "/build-error.txt";
      util::write_file_atomic(error_file, std::string(e.what()) + "\n");
      return finish(build_failed_night(n_.commit, e.what(), error_file, !last.commit.empty()));
    }
    say(built.reused ? "build: reused " + built.build.name
                     : "build: " + built.build.name + " in " + util::duration_text(built.seconds));

    // Both builds drawn tonight, in one run.
    const std::string last_dir = kind == NightKind::compare ? last.build_dir : "";
    const std::string exp = rundir::run_folder::experiment(n_.dir);
    util::write_file_atomic(exp, night_experiment(o_.experiment, last_dir, built.build.dir));
    const std::string run = n_.dir + "/run";
    n_.run_dir = run;
    say("run: " + exp);
    const int run_rc = run_self(run_arguments(exp, run, o_.jobs), n_.dir + "/run.log");
    if (!run_finished(run_rc)) return finish(run_failed_night(run_rc, n_.dir + "/run.log"));
    if (kind != NightKind::compare)
      return finish(uncompared_night(kind, last.commit), built.build.dir);
    // Audit each platform; attribute what changed. The audits keep their history in the night's
    // folder until the night is recorded (see the header).
    ComparedNight found;
    for (const std::string& p : platforms_) {
      const std::string out = rundir::run_folder::named_audit(n_.dir, p);
      const int rc =
          run_self(audit_arguments(p, run, out, night_db(), o_.jobs, o_.speed), out + ".log");
      say("audit " + p + ": exit " + std::to_string(rc) + " (" + rundir::run_folder::audit_md(out) + ")");
      if (audit_failed(rc)) found.audit_failed = true;
      const std::size_t moved = audit_judged(rc) ? time_moved(out) : 0;
      if (moved > 0) say("audit " + p + ": drawing time of " + std::to_string(moved) + " group(s) moved");
      n_.counts.time_moved += moved;
      if (platform_needs_bisection(rc, moved)) {
        found.changed = true;
        attribute(p, last.commit);
      }
    }
    found.counts = n_.counts;
    found.not_bisected = n_.not_bisected;
    found.speed = o_.speed.enabled;
    found.last_commit = last.commit;
    found.night_dir = n_.dir;
    return finish(compared_night(found), built.build.dir);
  }

 private:
  void say(const std::string& s) const {
    if (progress_) progress_(s);
  }
  std::string subject(const std::string& commit) const {
    return git(o_.source, {"log", "-1", "--format=%s", "--end-of-options", commit}).out;
  }
  std::string night_db() const { return n_.dir + "/audits.sqlite"; }

  // A state folder follows one tree: another tree's commits would read as a branch that moved
  // backwards, and the state would silently switch trees. A watch.json without `source` (written
  // before it was recorded) is checked against the history's last night.
  void check_same_tree(const LastNight& last) const {
    std::string follows = last.source, where = o_.state + "/watch.json: source";
    std::error_code ec;
    if (follows.empty() && !last.commit.empty() && fs::exists(o_.db, ec)) {
      try {
        const std::vector<audit::NightEntry> nights = audit::read_nights(o_.db, 1);
        if (!nights.empty()) follows = nights.back().source;
        where = o_.db + ": the last night's source";
      } catch (const util::UserError&) {
        // A history that cannot be read is said when the night is appended.
      }
    }
    if (follows.empty() || follows == o_.source) return;
    throw util::UserError("watch: " + where + ": the state folder " + o_.state +
                          " follows the tree " + follows + ", not " + o_.source + "; give " +
                          o_.source + " a state folder of its own (--state), or remove " +
                          o_.state + "/watch.json to follow it from a new baseline");
  }

  // The experiment as tonight's run will read it, checked before anything is built: a platform
  // that cannot draw a build, or a count the run would refuse, is bad input and not a night.
  void check_experiment(const std::string& last_build_dir) {
    (void)rundir::load_experiment(o_.experiment);
    platforms_ = watched_platforms(o_.experiment, parse_toml(o_.experiment));
    const std::string text = night_experiment(o_.experiment, last_build_dir,
                                              last_build_dir.empty() ? o_.state : last_build_dir);
    (void)rundir::parse_experiment(text, o_.experiment);
  }

  // Why upstream cannot be seen tonight: a verdict ("fetch failed", "upstream gone") and a note.
  struct Unseen {
    std::string verdict, why;
  };

  // Brings the commit to build tonight into n_.commit: the upstream of the tree's branch after a
  // fetch, else HEAD. Returns an empty Unseen, or why upstream cannot be seen (a fetch that fails,
  // an upstream branch deleted or renamed): such a night is an error, never "nothing new".
  // A tree left detached (a night's bisection killed mid-step) first returns to the branch
  // earlier nights followed, so that tonight is the branch's head and not a bisection step.
  Unseen branch_head(const std::string& last_branch) {
    const auto tree_lock = builds::lock_source_tree(o_.source, "watch");
    builds::GitResult on = git(o_.source, {"symbolic-ref", "-q", "--short", "HEAD"});
    if (!on.ok && !last_branch.empty()) {
      const std::string at = git(o_.source, {"rev-parse", "--short=12", "HEAD"}).out;
      say("returning " + o_.source + " to its branch " + last_branch +
          ": an interrupted night left it detached at " + at);
      const builds::GitResult co =
          git(o_.source, {"switch", "-q", "--end-of-options", last_branch});
      if (!co.ok)
        throw util::UserError("watch: " + o_.source + " is detached at " + at +
                              " and cannot return to its branch " + last_branch + " (" + co.out +
                              "); check the branch out by hand");
      on = git(o_.source, {"symbolic-ref", "-q", "--short", "HEAD"});
    }
    branch_ = on.ok ? on.out : "";
    if (o_.fetch && !git(o_.source, {"remote"}).out.empty()) {
      // --prune: an upstream branch deleted or renamed upstream loses its remote-tracking ref, so
      // it is seen as gone rather than followed at its last known commit forever.
      const builds::GitResult f = git(o_.source, {"fetch", "-q", "--prune"});
      if (!f.ok)
        return {"fetch failed", "git fetch in " + o_.source + " failed (" +
                                    f.out.substr(0, f.out.find('\n')).substr(0, 300) +
                                    "): upstream cannot be seen, nothing was built; check the "
                                    "remote's address and the network (git -C " +
                                    o_.source + " fetch)"};
    }
    // The branch's configured upstream, also when its remote-tracking ref is gone.
    const std::string upstream =
        branch_.empty()
            ? ""
            : git(o_.source, {"for-each-ref", "--format=%(upstream)", "refs/heads/" + branch_}).out;
    builds::GitResult up = git(o_.source, {"rev-parse", "--verify", "-q", "@{upstream}^{commit}"});
    if (!upstream.empty() && !(up.ok && !up.out.empty()))
      return {"upstream gone", "the upstream of the branch " + branch_ + ", " + upstream +
                                   ", is gone (deleted or renamed upstream): nothing was built; "
                                   "point the branch at the branch to follow (git -C " +
                                   o_.source + " branch --set-upstream-to=REMOTE/BRANCH)"};
    if (up.ok && !up.out.empty()) {
      // The branch brought to its head, so that the tree stays where it is built and an
      // incremental build recompiles only what the night changed; a branch that cannot move
      // forward (rewritten upstream) is built at the upstream's commit and left as it is.
      if (!git(o_.source, {"merge", "-q", "--ff-only", "@{upstream}"}).ok)
        say("the branch cannot be fast-forwarded to its upstream: building the upstream's head");
      n_.commit = up.out;
      return {};
    }
    up = git(o_.source, {"rev-parse", "--verify", "-q", "HEAD^{commit}"});
    if (!up.ok) throw util::UserError("watch: " + o_.source + " has no commit");
    n_.commit = up.out;
    return {};
  }

  // --speed: the groups an audit found faster or slower (its audit.json's `speed` array).
  std::size_t time_moved(const std::string& audit_dir) const {
    if (!o_.speed.enabled) return 0;
    try {
      return rundir::read_audit_document(audit_dir).time_moved();
    } catch (const std::exception& e) {
      throw util::UserError("watch: cannot read the night's drawing times: " +
                            std::string(e.what()));
    }
  }

  void attribute(const std::string& platform, const std::string& last_commit) {
    const NightBisection between = night_bisection(platform, last_commit, n_.commit);
    BisectOptions bo;
    bo.run_dir = n_.run_dir;
    bo.good_platform = between.good_platform;
    bo.bad_platform = between.bad_platform;
    bo.platform = platform;
    bo.source = o_.source;
    bo.good_ref = between.good_ref;
    bo.bad_ref = between.bad_ref;
    bo.out_dir = rundir::run_folder::named_bisect(n_.dir, platform);
    bo.build = o_.build;
    bo.jobs = o_.jobs;
    bo.pictures = o_.pictures;
    bo.max_primitives = o_.max_primitives;
    bo.speed = o_.speed;
    bo.command_line = bisect_command_line(bo);
    say("bisect " + platform + ": " + short_hash(last_commit) + ".." + short_hash(n_.commit));
    try {
      const BisectResult r = run_bisect(bo, [&](const std::string& s) { say("  " + s); });
      for (const Culprit& c : r.culprits) {
        n_.culprits.push_back(c.commit + " " + c.subject + " (" +
                              std::to_string(c.primitives.size()) + " primitives of " + platform + ")");
        n_.counts.attributed += c.primitives.size();
        ++n_.counts.culprit_commits;
      }
      for (const SpeedCulprit& c : r.speed_culprits) {
        for (const std::string& line : speed_culprit_lines(c, platform + ": "))
          n_.speed_culprits.push_back(line);
        ++n_.counts.speed_culprit_commits;
      }
      for (const SpeedUnattributed& u : r.speed_unattributed)
        n_.unattributed.push_back(u.group.label() + " of " + platform + ": " + u.why + " (" +
                                  r.report_path + ")");
      n_.counts.changed += r.changed_in_run;
      n_.counts.bisected += r.selection.size();
      n_.counts.unattributed += r.unattributed.size();
      if (!r.unattributed.empty())
        n_.unattributed.push_back(std::to_string(r.unattributed.size()) + " changes of " +
                                  platform +
                                  ": only commits that failed to build lie between the commits " +
                                  "drawn on either side (" + r.report_path + ")");
    } catch (const util::UserError& e) {
      util::throw_if_interrupted();  // stopped, not refused: the night ends unrecorded
      n_.not_bisected.push_back(platform + ": " + e.what());
    }
  }

  void save_last(const std::string& build_dir) const {
    write_last(o_.state + "/watch.json", {n_.commit, build_dir, branch_, o_.source});
  }

  // Records the night (night.json and night.md, then the history: the night's row, then its
  // audits), then moves watch.json to tonight's build (`tonight_build`) when the night moves the
  // baseline. A history that cannot be written leaves watch.json as it was, so the next night
  // finds the same again.
  WatchNight finish(const NightEnd& end, const std::string& tonight_build = "") {
    const std::string& verdict = end.verdict;
    const std::string& note = end.note;
    n_.verdict = verdict;
    n_.note = note;
    n_.exit_code = end.exit_code;
    n_.baseline_kept = end.baseline_kept;
    if (!n_.dir.empty()) write_night_files();
    audit::NightEntry e;
    e.date_utc = n_.date_utc;
    e.source = o_.source;
    e.commit = n_.commit;
    e.previous_commit = n_.previous_commit;
    e.verdict = verdict;
    for (const std::string& c : n_.culprits) e.culprits += (e.culprits.empty() ? "" : "\n") + c;
    for (const std::string& c : n_.speed_culprits)
      e.culprits += (e.culprits.empty() ? "" : "\n") + c;
    e.run_dir = n_.run_dir;
    e.note = note;
    for (const std::string& u : n_.unattributed) e.note += "; unattributed: " + u;
    for (const std::string& p : n_.not_bisected) e.note += "; not bisected: " + p;
    try {
      audit::append_night(o_.db, e);
      std::error_code ec;
      if (!n_.dir.empty() && fs::exists(night_db(), ec))
        for (const audit::HistoryEntry& h : audit::read_history(night_db()))
          audit::append_history(o_.db, h.summary);
    } catch (const std::exception& x) {
      util::throw_if_interrupted();
      throw util::UserError(
          std::string("watch: ") + x.what() + "; tonight (" + verdict +
          ") is not recorded in the history" +
          (n_.dir.empty() ? std::string() : " (it is in " + n_.dir + "/night.md)") + ", and " +
          o_.state +
          "/watch.json stays at last night's commit so the next night finds it again; make the "
          "history writable");
    }
    if (end.moves_baseline) save_last(tonight_build);
    prune_nights();
    return n_;
  }

  // --keep-nights: the oldest nights' folders removed once tonight is recorded.
  void prune_nights() const {
    if (o_.keep_nights == 0) return;
    std::error_code ec;
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(o_.state + "/nights", ec))
      if (e.is_directory(ec)) names.push_back(e.path().filename().string());
    const std::string tonight = n_.dir.empty() ? "" : fs::path(n_.dir).filename().string();
    const std::vector<std::string> old = nights_to_prune(names, o_.keep_nights, tonight);
    for (const std::string& n : old) fs::remove_all(o_.state + "/nights/" + n, ec);
    if (!old.empty())
      say("removed the folders of " + std::to_string(old.size()) + " old night(s) (--keep-nights " +
          std::to_string(o_.keep_nights) + "; the history keeps their rows)");
  }

  void write_night_files() const {
    nlohmann::json j = {{"date_utc", n_.date_utc},
                        {"commit", n_.commit},
                        {"previous_commit", n_.previous_commit},
                        {"verdict", n_.verdict},
                        {"note", n_.note},
                        {"culprits", n_.culprits},
                        {"speed_culprits", n_.speed_culprits},
                        {"time_moved", n_.counts.time_moved},
                        {"unattributed", n_.unattributed},
                        {"not_bisected", n_.not_bisected},
                        {"baseline_kept", n_.baseline_kept},
                        {"changed", n_.counts.changed},
                        {"exit_code", n_.exit_code}};
    j.update(rundir::document_header("watch-night", 1));
    util::write_file_atomic(n_.dir + "/night.json", j.dump(2) + "\n");
    std::string sentence = n_.note;  // the note as a sentence of its own
    while (!sentence.empty() && sentence.back() == '.') sentence.pop_back();
    if (!sentence.empty())
      sentence[0] = char(std::toupper(static_cast<unsigned char>(sentence[0])));
    std::string md = "# Night of " + n_.date_utc + ": " + n_.verdict + "\n\n" + sentence + ".\n\n" +
                     "- tonight: `" + n_.commit + "` " + subject(n_.commit) + "\n" +
                     (n_.previous_commit.empty() ? std::string()
                                                 : "- last night: `" + n_.previous_commit + "` " +
                                                       subject(n_.previous_commit) + "\n");
    if (!n_.culprits.empty()) {
      md += "\n## Culprits\n\n";
      for (const std::string& c : n_.culprits) md += "- " + c + "\n";
    }
    if (!n_.speed_culprits.empty()) {
      md += "\n## Drawing time\n\n";
      for (const std::string& c : n_.speed_culprits) md += "- " + c + "\n";
    }
    if (!n_.unattributed.empty()) {
      md += "\n## Not attributed\n\n";
      for (const std::string& u : n_.unattributed) md += "- " + u + "\n";
    }
    if (!n_.not_bisected.empty()) {
      md += "\n## Not bisected (kept for the next night)\n\n";
      for (const std::string& p : n_.not_bisected) md += "- " + p + "\n";
    }
    util::write_file_atomic(n_.dir + "/night.md", md);
  }

  WatchOptions o_;
  std::function<void(const std::string&)> progress_;
  WatchNight n_;
  std::vector<std::string> platforms_;  // the experiment's, checked before the night
  std::string branch_;                  // the branch the tree is on tonight ("" when detached)
};

}  // namespace

WatchNight watch_night(const WatchOptions& options,
                       const std::function<void(const std::string&)>& progress) {
  return Night(options, progress).run();
}

}  // namespace ra::triage
