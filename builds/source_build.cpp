// Building a Mesa source tree into the build cache (see the header).
#include "builds/source_build.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "rundir/build_record.h"
#include "platforms/platform_probe.h"
#include "rundir/platform_spec.h"
#include "rundir/manifest.h"
#include "builds/git_command.h"
#include "builds/meson_plan.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/duration_text.h"
#include "util/errors.h"
#include "util/fnv1a.h"
#include "util/interrupt.h"

namespace fs = std::filesystem;

namespace ra::builds {
namespace {

// The tools meson's Mesa build runs (python3 with mako among them) are Debian's, in /usr/bin:
// a python3 first on PATH without mako (pyenv's) breaks the configure.
std::string build_path() {
  const char* p = std::getenv("PATH");
  return "PATH=/usr/bin:/bin:" + std::string(p && *p ? p : "/usr/local/bin");
}

util::ProgramResult run_captured(const std::vector<std::string>& argv, const std::string& cwd = "") {
  util::ChildSpec spec;
  spec.argv = argv;
  spec.stdin_null = true;
  spec.capture_output = true;
  spec.working_dir = cwd;
  spec.set_env = {build_path()};
  return util::run_program(spec);
}

// The first line of a program's output, trimmed; "" when it cannot run.
std::string first_line(const std::vector<std::string>& argv) {
  const util::ProgramResult r = run_captured(argv);
  if (!r.exited_ok()) return "";
  std::string line = r.output.substr(0, r.output.find('\n'));
  while (!line.empty() && std::isspace(static_cast<unsigned char>(line.back()))) line.pop_back();
  return line;
}

// The last `lines` lines of a file ("" when unreadable).
std::string tail_of(const std::string& path, std::size_t lines) {
  std::string text;
  try {
    text = util::read_file(path);
  } catch (const std::exception&) {
    return "";
  }
  std::vector<std::string> all;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) all.push_back(l);
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i)
    out += all[i] + "\n";
  return out;
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : " ") + x;
  return s;
}

// ninja's last "[n/N]" in its log, as the progress of a compile ("" when it printed none yet).
std::string ninja_progress(const std::string& log, double elapsed_s) {
  const std::string tail = tail_of(log, 40);
  const std::size_t open = tail.rfind("\n[");
  if (open == std::string::npos) return "";
  unsigned done = 0, total = 0;
  if (std::sscanf(tail.c_str() + open + 2, "%u/%u]", &done, &total) != 2 || total == 0 || done == 0)
    return "";
  std::string text = "[" + std::to_string(done) + "/" + std::to_string(total) + "] " +
                     util::duration_text(elapsed_s) + " so far";
  if (done < total) text += ", about " + util::duration_text(elapsed_s * (total - done) / done) + " left";
  return text;
}

// Runs one step with its output in `log`, saying a compile's progress every 30 s; UserError naming
// the step, the log's last lines and, for a configure, the package meson says is missing.
void run_step(const std::string& step, const std::vector<std::string>& argv, const std::string& cwd,
              const std::vector<std::string>& env, const std::string& log,
              const std::string& kept_log,
              const std::function<void(const std::string&)>& say = {}) {
  util::ChildSpec spec;
  spec.argv = argv;
  spec.stdin_null = true;
  spec.working_dir = cwd;
  spec.set_env = env;
  spec.log_to(log);
  spec.own_process_group = true;
  const util::Child child = util::start_child(spec);
  util::set_interruptible_group(child.pid);  // an interrupt stops the step's whole group
  const auto t0 = std::chrono::steady_clock::now();
  auto said = t0;
  util::ProgramResult r;
  for (;;) {
    const pid_t done = ::waitpid(child.pid, &r.status, WNOHANG);
    if (done == child.pid || (done < 0 && errno != EINTR)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    const auto now = std::chrono::steady_clock::now();
    if (say && now - said >= std::chrono::seconds(30)) {
      said = now;
      const std::string p = ninja_progress(log, std::chrono::duration<double>(now - t0).count());
      if (!p.empty()) say(step + ": " + p);
    }
  }
  util::set_interruptible_group(0);
  if (r.exited_ok()) return;
  std::error_code ec;
  fs::copy_file(log, kept_log, fs::copy_options::overwrite_existing, ec);
  std::string message = "builds build: the " + step + " step failed (" +
                        (r.exit_code() == 127 ? "cannot run " + argv[0]
                                              : util::describe_exit_status(r.status)) +
                        "); the build cache is unchanged.";
  std::string log_text;
  try {
    log_text = util::read_file(log);
  } catch (const std::exception&) {
  }
  if (const std::string pkg = missing_package_hint(log_text); !pkg.empty())
    message += "\nmissing: " + pkg + " (scripts/install-mesa-build-deps.sh installs what Mesa needs)";
  message += "\nlast lines of the log:\n" + tail_of(log, 12);
  if (!ec) message += "\nfull log: " + kept_log;
  throw util::UserError(message);
}

// Where meson builds and installs: a fresh folder inside the work folder, or the tree's
// incremental folder (SourceBuildOptions::incremental), whose native file must outlive the build
// since meson reads it again when it reconfigures by itself.
struct MesonFolders {
  std::string build, prefix, native_file;
  bool incremental = false;
};

bool log_says(const std::string& path, const std::string& needle) {
  try {
    return util::read_file(path).find(needle) != std::string::npos;
  } catch (const std::exception&) {
    return false;
  }
}

// meson setup (unless the folder is configured with the same options), ninja, ninja install of
// `source` into folders.prefix; logs in `work`; returns the -D options used.
std::vector<std::string> run_meson(const SourceBuildOptions& options, const std::string& source,
                                 const MesonFolders& folders, const std::string& work,
                                 unsigned jobs, const std::string& kept_log,
                                 const std::function<void(const std::string&)>& say,
                                 std::vector<std::string>& notes) {
  std::error_code ec;
  MesonPlanInputs in;
  std::string opts_file = source + "/meson.options";
  if (!fs::exists(opts_file, ec)) opts_file = source + "/meson_options.txt";
  in.options = parse_meson_options(read_tree_file(opts_file));
  in.source_dir = source;
  in.build_dir = folders.build;
  in.prefix = folders.prefix;
  in.native_file = folders.native_file;
  in.glslang_version = [] {
    const std::string v = first_line({"glslangValidator", "--version"});  // "Glslang Version: 11:12.0.0"
    const auto colon = v.rfind(':');
    return colon == std::string::npos ? v : v.substr(colon + 1);
  }();
  in.extra = options.meson_options;
  util::write_file_atomic(in.native_file, native_file_text(options.llvm_config));
  MesonPlan plan = plan_meson_build(in);
  plan.setup[0] = options.meson;
  plan.compile.insert(plan.compile.end(), {"-j", std::to_string(jobs)});
  for (const std::string& n : plan.notes) say(n);
  notes = plan.notes;
  std::vector<std::string> chosen = plan.chosen;
  chosen.insert(chosen.end(), options.meson_options.begin(), options.meson_options.end());
  const std::vector<std::string> env = {build_path()};
  // An incremental folder configured with the same command is reused as it is (ninja runs meson
  // again when a meson.build changed); other options (Mesa's change over its history) start it
  // afresh.
  const std::string setup_text = joined(plan.setup);
  const std::string setup_record = folders.build + "/renderaudit-setup.txt";
  const bool configured = folders.incremental && fs::exists(folders.build + "/build.ninja", ec) &&
                          read_tree_file(setup_record) == setup_text;
  const auto configure = [&] {
    if (folders.incremental) fs::remove_all(folders.build, ec);
    say("configure: " + setup_text);
    run_step("configure (meson setup)", plan.setup, source, env, work + "/configure.log", kept_log);
    if (folders.incremental) util::write_file_atomic(setup_record, setup_text + "\n");
  };
  if (configured)
    say("configure: reusing the incremental build folder " + folders.build);
  else
    configure();
  say("compile: " + joined(plan.compile));
  try {
    run_step("compile (ninja)", plan.compile, source, env, work + "/compile.log", kept_log, say);
  } catch (const util::UserError&) {
    // meson's own reconfigure failed in a folder configured at a distant commit: once afresh.
    if (!configured || !log_says(work + "/compile.log", "rebuilding 'build.ninja'")) throw;
    say("the incremental folder cannot reconfigure itself for this commit: configuring afresh");
    configure();
    run_step("compile (ninja)", plan.compile, source, env, work + "/compile.log", kept_log, say);
  }
  say("install into the build folder");
  fs::remove_all(folders.prefix, ec);
  run_step("install (ninja install)", plan.install, source, env, work + "/install.log", kept_log);
  return chosen;
}

// The incremental folder of a tree and the options that shape its configure.
std::string incremental_folder(const std::string& cache, const std::string& source,
                               const SourceBuildOptions& o) {
  util::Fnv1a64 h;
  for (const std::string& part : {source, o.llvm_config, o.meson})
    h.add(part.data(), part.size()), h.add("\n", 1);
  for (const std::string& m : o.meson_options) h.add(m.data(), m.size()), h.add("\n", 1);
  return cache + "/.incremental/" + util::hex64(h.value);
}

// build.json of a source build: where it came from and how it was built.
nlohmann::json provenance(const SourceBuildOptions& options, const SourceIdentity& id,
                          const rundir::BuildRecord& s, const nlohmann::json& gl,
                          const std::vector<std::string>& chosen, const std::string& key,
                          unsigned jobs, const SourceBuildResult& result) {
  const bool meson = options.build_command.empty();
  const std::string& name = s.name;
  const std::string llvm = meson ? first_line({options.llvm_config, "--version"}) : "";
  nlohmann::json j = {
      {"name", name},
      {"origin", "source"},
      {"suite", ""},
      {"built_utc", s.fetched_utc},
      {"fetched_utc", s.fetched_utc},
      {"source_build",
       {{"source", id.source},
        {"git", id.git},
        {"commit", id.commit},
        {"subject", id.subject},
        {"commit_date", id.date},
        {"dirty", id.dirty},
        {"untracked", id.untracked},
        {"clean", id.clean()},
        {"version", id.version},
        {"debian_version", id.debian_version},
        {"patches", id.patches},
        {"meson_options", chosen},
        {"build_command", options.build_command},
        {"meson", meson ? first_line({options.meson, "--version"}) : ""},
        {"llvm_config", meson ? options.llvm_config : ""},
        {"llvm", llvm},
        {"compiler", first_line({"cc", "--version"})},
        {"ccache", first_line({"ccache", "--version"})},
        {"jobs", jobs},
        {"build_seconds", result.seconds},
        {"notes", result.notes},
        {"key", key}}},
      {"gl", gl},
      {"files", s.files}};
  j.update(rundir::document_header(rundir::kBuildDocument, rundir::kBuildDocumentVersion, false));
  return j;
}

// True when the cached build in `dir` was made from `commit` with the reuse key `key`. The key
// covers the commit; the commit is compared too, so that a build recorded under another commit (a
// tree moved during its build) is never taken for this one; and a git build must record that its
// tree was clean (no untracked or changed file), else it may not be the commit's.
bool same_build(const std::string& dir, const std::string& key, const std::string& commit) {
  if (!rundir::is_build_folder(dir)) return false;
  try {
    const rundir::BuildRecord b = rundir::read_build_record(dir);
    return b.key == key && b.commit == commit && (!b.from_git || b.clean);
  } catch (const std::exception&) {
    return false;
  }
}

}  // namespace

std::string missing_package_hint(const std::string& log) {
  static const std::vector<std::pair<std::string, std::string>> known = {
      {"\"libdrm\"", "libdrm-dev"},        {"\"libelf\"", "libelf-dev"},
      {"\"zlib\"", "zlib1g-dev"},          {"\"expat\"", "libexpat1-dev"},
      {"\"libzstd\"", "libzstd-dev"},      {"\"libudev\"", "libudev-dev"},
      {"Program 'bison", "bison"},         {"Program 'flex", "flex"},
      {"Program 'glslangValidator", "glslang-tools"},
      {"mako", "python3-mako"},            {"yaml", "python3-yaml"},
      {"packaging", "python3-packaging"},  {"\"LLVM\"", "llvm-15-dev"},
      {"llvm-config", "llvm-15-dev"},      {"Meson version is", "meson (bookworm-backports)"},
  };
  for (const auto& [needle, package] : known) {
    const std::size_t at = log.find(needle);
    if (at == std::string::npos) continue;
    // Only where meson reports it as missing or too old.
    const std::size_t line_end = log.find('\n', at);
    const std::size_t line_start = log.rfind('\n', at);
    const std::string line = log.substr(line_start == std::string::npos ? 0 : line_start + 1,
                                        line_end == std::string::npos ? std::string::npos
                                                                      : line_end - line_start);
    for (const char* word : {"not found", "NO", "ERROR", "required", "No module", "Meson version"})
      if (line.find(word) != std::string::npos) return package;
  }
  return "";
}

std::optional<SourceBuildResult> cached_source_build(const SourceBuildOptions& options) {
  const SourceIdentity id = identify_source(fs::canonical(options.source).string());
  if (!id.clean()) return std::nullopt;
  const std::string cache = options.cache.empty() ? rundir::build_cache_dir() : options.cache;
  const std::string target = cache + "/" + source_build_name(id, options);
  if (!same_build(target, source_build_key(id, options), id.commit)) return std::nullopt;
  try {
    SourceBuildResult r;
    r.in_use = std::make_shared<BuildInUse>(target);
    r.build = rundir::read_build_record(target);
    r.reused = true;
    return r;
  } catch (const util::UserError&) {
    return std::nullopt;  // removed just now
  }
}

SourceBuildResult use_source_build(const std::string& dir, const std::string& commit,
                                   SourceBuildOptions options,
                                   const std::function<void(const std::string&)>& progress) {
  try {
    if (rundir::is_build_folder(dir)) {
      rundir::BuildRecord b = rundir::read_build_record(dir);
      if (b.commit == commit && b.clean) {
        SourceBuildResult r;
        r.in_use = std::make_shared<BuildInUse>(dir);
        r.build = std::move(b);
        r.reused = true;
        return r;
      }
    }
  } catch (const std::exception&) {
    // damaged or removed just now: built again
  }
  if (progress)
    progress(dir + " no longer holds the build of " + commit.substr(0, 12) + ": building it again");
  options.ref = commit;
  return build_from_source(options, progress);
}

std::string source_build_key(const SourceIdentity& id, const SourceBuildOptions& o) {
  util::Fnv1a64 h;
  const auto add = [&](const std::string& s) { h.add(s.data(), s.size()), h.add("\n", 1); };
  add(id.git ? "git " + id.commit
             : "tree " + id.version + " " + id.debian_version + " " + id.content_hash);
  add(id.patches);
  std::vector<std::string> opts = o.meson_options;
  for (const std::string& x : opts) add(x);
  add(o.llvm_config);
  add(o.build_command);
  return util::hex64(h.value);
}

std::string source_build_name(const SourceIdentity& id, const SourceBuildOptions& o) {
  if (!o.name.empty()) return o.name;
  std::string name = id.git ? "mesa-" + id.commit.substr(0, 12)
                            : "mesa-" + (id.version.empty() ? std::string("unknown") : id.version) +
                                  "-src";
  if (id.dirty || !id.untracked.empty()) name += "-dirty";  // not its commit's files alone
  const bool defaults = o.meson_options.empty() && o.build_command.empty() &&
                        o.llvm_config == SourceBuildOptions{}.llvm_config;
  if (!defaults) name += "-" + source_build_key(id, o).substr(0, 6);
  return name;
}

SourceBuildResult build_from_source(const SourceBuildOptions& options,
                                    const std::function<void(const std::string&)>& progress) {
  const auto say = [&](const std::string& s) {
    if (progress) progress(s);
  };
  std::error_code ec;
  if (options.source.empty() || !fs::is_directory(options.source, ec))
    throw util::UserError("builds build: '" + options.source + "' is not a folder");
  const std::string source = fs::canonical(options.source).string();
  if (options.build_command.empty() && !fs::exists(source + "/meson.build", ec))
    throw util::UserError("builds build: " + source +
                          " holds no meson.build: not a Mesa source tree");
  // Held from the checkout to the install; the caller (a bisection) may hold it already.
  const std::unique_ptr<util::DirLock> tree_lock =
      options.source_locked ? nullptr : lock_source_tree(source, "builds build");
  SourceIdentity id = identify_source(source);
  const std::string restore_ref =
      options.ref.empty() ? "" : check_out_for_build(source, options.ref, id);
  struct Restore {
    std::string dir, ref;
    ~Restore() {
      if (!ref.empty()) git(dir, {"checkout", "-q", ref, "--"});
    }
  } restore{source, options.restore_ref && restore_ref != id.commit ? restore_ref : ""};

  const std::string cache = options.cache.empty() ? rundir::build_cache_dir() : options.cache;
  const std::string name = source_build_name(id, options);
  if (!rundir::is_build_name(name))
    throw util::UserError("builds build: '" + name +
                          "' is not a build name (1 to 64 letters, digits, '.', '_', '-')");
  const std::string key = source_build_key(id, options);
  SourceBuildResult result;
  const std::string target = cache + "/" + name;
  if (options.reuse && (id.clean() || !id.git) && same_build(target, key, id.commit)) {
    try {
      result.in_use = std::make_shared<BuildInUse>(target);
      result.reused = true;
      result.build = rundir::read_build_record(target);
      say("reused " + name + " (same source and options)");
      return result;
    } catch (const util::UserError&) {
      result = SourceBuildResult{};  // removed just now: built again below
    }
  }
  const bool meson = options.build_command.empty();
  if (meson) {
    for (const std::string& tool : {options.meson, std::string("ninja")})
      if (run_captured({tool, "--version"}).exit_code() == 127)
        throw util::UserError("builds build: " + tool +
                              " is not installed: scripts/install-mesa-build-deps.sh installs "
                              "what a Mesa build needs (meson >= 1.4 from bookworm-backports)");
    check_llvm_config(options.llvm_config);
  }
  require_cache_folder(cache);
  std::string work = cache + "/.source-" + name + "-XXXXXX";
  if (!::mkdtemp(work.data()))
    throw util::UserError(util::io_error_message("cannot create a folder in", cache));
  const std::string prefix = work + "/install";
  const std::string kept_log = (fs::temp_directory_path() / ("renderaudit-build-" + name + ".log")).string();
  try {
    const auto t0 = std::chrono::steady_clock::now();
    const unsigned jobs = options.jobs ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
    std::vector<std::string> chosen;
    if (meson) {
      MesonFolders folders{work + "/build", prefix, work + "/native.ini", false};
      std::unique_ptr<util::DirLock> folder_lock;  // one build at a time in the folder
      if (options.incremental) {
        const std::string inc = incremental_folder(cache, source, options);
        fs::create_directories(inc);
        folder_lock = std::make_unique<util::DirLock>(inc, "builds build",
                                                      "wait for that build to finish");
        folders = {inc + "/build", inc + "/install", inc + "/native.ini", true};
      }
      chosen = run_meson(options, source, folders, work, jobs, kept_log, say, result.notes);
      if (folders.prefix != prefix) fs::rename(folders.prefix, prefix);
    } else {
      fs::create_directories(prefix);
      say("build command: " + options.build_command);
      run_step("build command", {"/bin/sh", "-c", options.build_command}, source,
               {build_path(), "RENDERAUDIT_BUILD_PREFIX=" + prefix,
                "RENDERAUDIT_SOURCE_COMMIT=" + id.commit},
               work + "/configure.log", kept_log);
    }
    result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    // The tree must still be the commit (or content) this build is named after.
    const SourceIdentity after = identify_source(source);
    if (after.commit != id.commit || after.dirty != id.dirty ||
        after.content_hash != id.content_hash)
      throw util::UserError(
          "builds build: " + source + " changed while it was built (" +
          (id.git ? "HEAD was " + id.commit.substr(0, 12) + ", is now " +
                        (after.commit.empty() ? std::string("none") : after.commit.substr(0, 12))
                  : std::string("its files changed")) +
          "): another process used the tree; the build is not kept and the cache is unchanged");
    std::string log;
    for (const char* part : {"/configure.log", "/compile.log", "/install.log"})
      if (fs::exists(work + part, ec)) log += util::read_file(work + part);
    util::write_file_atomic(prefix + "/build.log", log);

    rundir::BuildRecord s;
    s.name = name;
    s.origin = "source";
    s.commit = id.commit;
    s.version = id.version;
    s.fetched_utc = rundir::utc_now_iso8601();
    nlohmann::json gl = nlohmann::json::object();
    if (options.probe) {
      say("probe: osmesa-llvmpipe and egl-llvmpipe with the build");
      gl = probe_build(s, prefix);
      if (s.osmesa_version.empty() && s.egl_version.empty())
        throw util::UserError("builds build: the build of " + source +
                              " cannot draw (probe step): " + gl.dump() +
                              "; the build cache is unchanged");
    }
    s.files = build_libraries(prefix);
    const nlohmann::json j = provenance(options, id, s, gl, chosen, key, jobs, result);
    util::write_file_atomic(rundir::build_record_path(prefix), j.dump(2) + "\n");
    s.dir = target;
    // Held before it is in the cache (the lock moves with the folder): no removal between.
    result.in_use = std::make_shared<BuildInUse>(prefix);
    const std::string old = work + "/replaced";
    // A build of the same name that a process draws with (a night, a bisection) stays.
    if (build_drawn_with_now(target))
      throw util::UserError("builds build: " + name + " in " + cache +
                            " is in use: a process draws with it now; wait for it to finish, or "
                            "build under another --name; the build cache is unchanged");
    if (fs::exists(target, ec)) fs::rename(target, old);
    fs::rename(prefix, target);
    fs::remove_all(work, ec);
    result.build = s;
    result.log = target + "/build.log";
    return result;
  } catch (...) {
    fs::remove_all(work, ec);
    throw;
  }
}

}  // namespace ra::builds
