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
#include "rundir/manifest.h"
#include "rundir/platform_spec.h"
#include "rundir/run_folder.h"
#include "runner/git_command.h"
#include "triage/bisect.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/dir_lock.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/interrupt.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

using runner::git;

constexpr const char* kLastBuild = "watch-last";
constexpr const char* kTonightBuild = "watch-tonight";

std::string short_hash(const std::string& c) { return c.substr(0, 12); }

// The last good night: its commit and build, and the branch the tree follows (STATE/watch.json).
struct LastNight {
  std::string commit, build_dir, branch;
};

LastNight read_last(const std::string& path) {
  LastNight l;
  std::error_code ec;
  if (!fs::exists(path, ec)) return l;
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(util::read_file(path));
  } catch (const std::exception& e) {
    throw util::UserError("watch: " + path + " is not readable JSON (" + e.what() +
                          "); remove it to start again from a new baseline");
  }
  for (const char* key : {"commit", "build_dir"})
    if (!j.is_object() || !j.contains(key) || !j[key].is_string())
      throw util::UserError("watch: " + path + ": '" + key +
                            "' must be a string; remove the file to start again from a new baseline");
  l.commit = j["commit"];
  l.build_dir = j["build_dir"];
  if (j.contains("branch") && j["branch"].is_string()) l.branch = j["branch"];
  return l;
}

// The experiment with each platform P drawn by last night's and tonight's builds.
std::string night_experiment(const std::string& file, const std::string& last_dir,
                             const std::string& tonight_dir, std::vector<std::string>& platforms) {
  toml::table t;
  try {
    t = toml::parse_file(file);
  } catch (const toml::parse_error& e) {
    throw util::UserError("watch: " + file + ": " + std::string(e.description()));
  }
  const toml::array* list = t["platforms"].as_array();
  if (!list || list->empty())
    throw util::UserError("watch: " + file + ": 'platforms' must name the platforms to watch");
  toml::array both;
  for (const toml::node& n : *list) {
    const std::string p = n.value_or(std::string());
    if (p.find('@') != std::string::npos || !rundir::find_platform(p + "@" + kTonightBuild))
      throw util::UserError("watch: " + file + ": platforms: '" + p +
                            "' cannot draw a driver build (allowed: the osmesa-* and surfaceless "
                            "egl-* platforms, vk-lavapipe, faulty, without @BUILD)");
    platforms.push_back(p);
    if (!last_dir.empty()) both.push_back(p + "@" + kLastBuild);
    both.push_back(p + "@" + kTonightBuild);
  }
  t.insert_or_assign("platforms", both);
  if (!t["builds"].as_table()) t.insert_or_assign("builds", toml::table{});
  toml::table& builds = *t["builds"].as_table();
  if (!last_dir.empty()) builds.insert_or_assign(kLastBuild, toml::table{{"dir", last_dir}});
  builds.insert_or_assign(kTonightBuild, toml::table{{"dir", tonight_dir}});
  std::ostringstream out;
  out << "# " << file << " as `renderaudit watch` ran it tonight\n" << t << "\n";
  return out.str();
}

// This program, run as a child with its output in `log`; returns the exit code.
int run_self(const std::vector<std::string>& args, const std::string& log) {
  util::ChildSpec spec;
  spec.argv = {fs::read_symlink("/proc/self/exe").string()};
  spec.argv.insert(spec.argv.end(), args.begin(), args.end());
  spec.stdin_null = true;
  spec.log_to(log);
  const util::Child c = util::start_child(spec);
  const int status = util::wait_child(c.pid);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

}  // namespace

std::string changed_night_note(std::size_t changed, std::size_t attributed, std::size_t culprit_commits) {
  std::string note = std::to_string(changed) + (changed == 1 ? " primitive changed" : " primitives changed");
  if (attributed < changed)
    note += " (" + std::to_string(attributed) + " of them attributed: a sample, see the bisection's report)";
  return note + ", " + std::to_string(culprit_commits) + " culprit commit(s)";
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
    // A signal stops the build's process group and ends the night unrecorded (util::Interrupted).
    util::InterruptScope interrupts;
    if (o_.db.empty()) o_.db = o_.state + "/history.sqlite";
    if (!fs::is_regular_file(o_.experiment, ec))
      throw util::UserError("watch: --experiment " + o_.experiment + " is not a file");
    if (!fs::is_directory(o_.source, ec) || !git(o_.source, {"rev-parse", "--git-dir"}).ok)
      throw util::UserError("watch: " + o_.source + " is not a git checkout");
    o_.source = fs::canonical(o_.source).string();
    LastNight last = read_last(o_.state + "/watch.json");
    n_.date_utc = rundir::utc_now_iso8601();
    n_.previous_commit = last.commit;
    n_.commit = branch_head(last.branch);
    say("tonight: " + short_hash(n_.commit) + " " + subject(n_.commit) +
        (last.commit.empty() ? " (no baseline yet)" : "; last night: " + short_hash(last.commit)));
    if (n_.commit == last.commit) return finish("nothing new", "the branch head is last night's commit", 0);
    const bool backwards = !last.commit.empty() &&
                           !git(o_.source, {"merge-base", "--is-ancestor", last.commit, n_.commit}).ok;
    std::string stamp = n_.date_utc;
    for (char& ch : stamp)
      if (ch == ':') ch = '-';
    n_.dir = o_.state + "/nights/" + stamp;
    fs::create_directories(n_.dir, ec);

    // Tonight's build.
    runner::SourceBuildOptions b = o_.build;
    b.source = o_.source;
    b.ref = n_.commit;
    b.probe = false;  // the run is the probe
    // Last night's build, held against `builds remove` all night; built again if it is gone.
    runner::SourceBuildResult last_build;
    if (!backwards && !last.commit.empty()) {
      last_build = runner::use_source_build(last.build_dir, last.commit, b, [&](const std::string& s) { say("  " + s); });
      last.build_dir = last_build.build.dir;
    }
    runner::SourceBuildResult built;
    try {
      built = runner::build_from_source(b, [&](const std::string& s) { say("  " + s); });
    } catch (const util::UserError& e) {
      util::throw_if_interrupted();  // stopped, not failed: nothing recorded
      util::write_file_atomic(n_.dir + "/build-error.txt", std::string(e.what()) + "\n");
      return finish("build failed", std::string(e.what()).substr(0, 400) +
                                        (last.commit.empty() ? "" : "; last night's build stays the baseline"),
                    2);
    }
    say(built.reused ? "build: reused " + built.build.name
                     : "build: " + built.build.name + " in " + util::duration_text(built.seconds));

    // Both builds drawn tonight, in one run.
    std::vector<std::string> platforms;
    const std::string last_dir = backwards ? "" : last.build_dir;
    const std::string exp = rundir::run_folder::experiment(n_.dir);
    util::write_file_atomic(exp, night_experiment(o_.experiment, last_dir, built.build.dir, platforms));
    const std::string run = n_.dir + "/run";
    n_.run_dir = run;
    say("run: " + exp);
    util::throw_if_interrupted();
    const int run_rc = run_self({"run", exp, "--out", run, "--quiet", "--jobs", std::to_string(o_.jobs ? o_.jobs : 2)},
                                n_.dir + "/run.log");
    if (run_rc != 0 && run_rc != 1)
      return finish("run failed", "the run exited " + std::to_string(run_rc) + " (" + n_.dir +
                                      "/run.log)", 2);
    if (last_dir.empty()) {
      save_last(built.build.dir);
      return finish(backwards ? "moved backwards" : "baseline established",
                    backwards ? "the branch no longer holds last night's commit " +
                                    short_hash(last.commit) + ": tonight is the new baseline"
                              : "tonight's build is the baseline from now on",
                    backwards ? 1 : 0);
    }
    // Audit each platform; attribute what changed.
    bool changed = false, failed = false;
    for (const std::string& p : platforms) {
      const std::string out = n_.dir + "/audit-" + p;
      const int rc = run_self({"audit", run, "--between", p + "@" + kLastBuild, p + "@" + kTonightBuild,
                               "--out", out, "--db", o_.db, "--jobs", std::to_string(o_.jobs ? o_.jobs : 2)},
                              n_.dir + "/audit-" + p + ".log");
      util::throw_if_interrupted();
      say("audit " + p + ": exit " + std::to_string(rc) + " (" + out + "/audit.md)");
      if (rc == 2 || rc > 2) failed = true;
      if (rc == 1) {
        changed = true;
        attribute(p, last.commit);
      }
    }
    if (failed)
      return finish("run failed", "a driver crashed or the audit failed (" + n_.dir + ")", 2);
    save_last(built.build.dir);
    if (!changed) return finish("unchanged", "no primitive changed", 0);
    if (unbisected_) return finish("changed", "primitives changed; a bisection could not run (see the culprits)", 1);
    return finish("changed", changed_night_note(n_.changed, n_.attributed, culprit_commits_), 1);
  }

 private:
  void say(const std::string& s) const {
    if (progress_) progress_(s);
  }
  std::string subject(const std::string& commit) const {
    return git(o_.source, {"log", "-1", "--format=%s", commit}).out;
  }

  // The commit to build tonight: the upstream of the tree's branch after a fetch, else HEAD.
  // A tree left detached (a night's bisection killed mid-step) first returns to the branch
  // earlier nights followed, so that tonight is the branch's head and not a bisection step.
  std::string branch_head(const std::string& last_branch) {
    const auto tree_lock = runner::lock_source_tree(o_.source, "watch");
    runner::GitResult on = git(o_.source, {"symbolic-ref", "-q", "--short", "HEAD"});
    if (!on.ok && !last_branch.empty()) {
      const std::string at = git(o_.source, {"rev-parse", "--short=12", "HEAD"}).out;
      say("returning " + o_.source + " to its branch " + last_branch +
          ": an interrupted night left it detached at " + at);
      const runner::GitResult co = git(o_.source, {"checkout", "-q", last_branch});
      if (!co.ok)
        throw util::UserError("watch: " + o_.source + " is detached at " + at +
                              " and cannot return to its branch " + last_branch + " (" + co.out +
                              "); check the branch out by hand");
      on = git(o_.source, {"symbolic-ref", "-q", "--short", "HEAD"});
    }
    branch_ = on.ok ? on.out : "";
    if (o_.fetch && !git(o_.source, {"remote"}).out.empty()) {
      const runner::GitResult f = git(o_.source, {"fetch", "-q"});
      if (!f.ok) say("git fetch failed (" + f.out + "): watching the tree's own head");
    }
    runner::GitResult up = git(o_.source, {"rev-parse", "--verify", "-q", "@{upstream}^{commit}"});
    if (up.ok && !up.out.empty()) {
      // The branch brought to its head, so that the tree stays where it is built and an
      // incremental build recompiles only what the night changed; a branch that cannot move
      // forward (rewritten upstream) is built at the upstream's commit and left as it is.
      if (!git(o_.source, {"merge", "-q", "--ff-only", "@{upstream}"}).ok)
        say("the branch cannot be fast-forwarded to its upstream: building the upstream's head");
      return up.out;
    }
    up = git(o_.source, {"rev-parse", "--verify", "-q", "HEAD^{commit}"});
    if (!up.ok) throw util::UserError("watch: " + o_.source + " has no commit");
    return up.out;
  }

  void attribute(const std::string& platform, const std::string& last_commit) {
    BisectOptions bo;
    bo.run_dir = n_.run_dir;
    bo.good_platform = platform + "@" + kLastBuild;
    bo.bad_platform = platform + "@" + kTonightBuild;
    bo.platform = platform;
    bo.source = o_.source;
    bo.good_ref = last_commit;
    bo.bad_ref = n_.commit;
    bo.out_dir = n_.dir + "/bisect-" + platform;
    bo.build = o_.build;
    bo.jobs = o_.jobs;
    bo.pictures = o_.pictures;
    bo.max_primitives = o_.max_primitives;
    bo.command_line = bisect_command_line(bo);
    say("bisect " + platform + ": " + short_hash(last_commit) + ".." + short_hash(n_.commit));
    try {
      const BisectResult r = run_bisect(bo, [&](const std::string& s) { say("  " + s); });
      for (const Culprit& c : r.culprits) {
        n_.culprits.push_back(c.commit + " " + c.subject + " (" +
                              std::to_string(c.primitives.size()) + " primitives of " + platform + ")");
        n_.attributed += c.primitives.size();
        ++culprit_commits_;
      }
      n_.changed += r.changed_in_run;
      if (!r.unattributed.empty())
        n_.culprits.push_back("unattributed: " + std::to_string(r.unattributed.size()) +
                              " changes of " + platform + " (failed builds between; " + r.report_path + ")");
    } catch (const util::UserError& e) {
      n_.culprits.push_back("no bisection of " + platform + ": " + e.what());
      unbisected_ = true;
    }
  }

  void save_last(const std::string& build_dir) const {
    util::write_file_atomic(o_.state + "/watch.json",
                            nlohmann::json{{"commit", n_.commit}, {"build_dir", build_dir}, {"branch", branch_}}
                                    .dump(2) +
                                "\n");
  }

  WatchNight finish(const std::string& verdict, const std::string& note, int exit_code) {
    n_.verdict = verdict;
    n_.note = note;
    n_.exit_code = exit_code;
    audit::NightEntry e;
    e.date_utc = n_.date_utc;
    e.source = o_.source;
    e.commit = n_.commit;
    e.previous_commit = n_.previous_commit;
    e.verdict = verdict;
    for (const std::string& c : n_.culprits) e.culprits += (e.culprits.empty() ? "" : "\n") + c;
    e.run_dir = n_.run_dir;
    e.note = note;
    audit::append_night(o_.db, e);
    if (!n_.dir.empty()) {
      nlohmann::json j = {{"date_utc", n_.date_utc}, {"commit", n_.commit},
                          {"previous_commit", n_.previous_commit}, {"verdict", verdict},
                          {"note", note}, {"culprits", n_.culprits}, {"changed", n_.changed},
                          {"exit_code", exit_code}};
      j.update(rundir::document_header("watch-night", 1));
      util::write_file_atomic(n_.dir + "/night.json", j.dump(2) + "\n");
      std::string sentence = note;  // the note as a sentence of its own
      while (!sentence.empty() && sentence.back() == '.') sentence.pop_back();
      if (!sentence.empty()) sentence[0] = char(std::toupper(static_cast<unsigned char>(sentence[0])));
      std::string md = "# Night of " + n_.date_utc + ": " + verdict + "\n\n" + sentence + ".\n\n" +
                       "- tonight: `" + n_.commit + "` " + subject(n_.commit) + "\n" +
                       (n_.previous_commit.empty() ? std::string()
                                                   : "- last night: `" + n_.previous_commit + "` " +
                                                         subject(n_.previous_commit) + "\n");
      if (!n_.culprits.empty()) {
        md += "\n## Culprits\n\n";
        for (const std::string& c : n_.culprits) md += "- " + c + "\n";
      }
      util::write_file_atomic(n_.dir + "/night.md", md);
    }
    return n_;
  }

  WatchOptions o_;
  std::function<void(const std::string&)> progress_;
  WatchNight n_;
  std::string branch_;  // the branch the tree is on tonight ("" when detached)
  std::size_t culprit_commits_ = 0;
  bool unbisected_ = false;  // a platform's bisection refused to start
};

}  // namespace

WatchNight watch_night(const WatchOptions& options,
                       const std::function<void(const std::string&)>& progress) {
  return Night(options, progress).run();
}

}  // namespace ra::triage
