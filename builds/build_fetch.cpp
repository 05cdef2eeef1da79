// Fetching a Debian suite's Mesa into the build cache (see the header).
#include "builds/build_fetch.h"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "rundir/build_record.h"
#include "platforms/platform_probe.h"
#include "rundir/manifest.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::builds {
namespace {

// Runs a program to its end; UserError with its last lines when it fails.
std::string run_tool(const std::vector<std::string>& argv, const std::string& what,
                     const std::string& working_dir = "") {
  util::ChildSpec spec;
  spec.argv = argv;
  spec.stdin_null = true;
  spec.capture_output = true;
  spec.working_dir = working_dir;
  const util::ProgramResult r = util::run_program(spec);
  if (r.exit_code() == 127)
    throw util::UserError(what + ": cannot run " + argv[0] + " (apt-get install apt dpkg)");
  if (!r.exited_ok()) {
    std::string tail = r.output;
    if (tail.size() > 1500) tail = "..." + tail.substr(tail.size() - 1500);
    throw util::UserError(what + " failed (" + util::describe_exit_status(r.status) + "):\n" +
                          tail);
  }
  return r.output;
}

// "25.0.7-2~bpo12+1" -> "25.0.7" (no epoch, no Debian revision).
std::string upstream_version(std::string v) {
  if (const auto colon = v.find(':'); colon != std::string::npos) v.erase(0, colon + 1);
  if (const auto dash = v.rfind('-'); dash != std::string::npos) v.resize(dash);
  if (const auto tilde = v.find('~'); tilde != std::string::npos) v.resize(tilde);
  return v;
}

}  // namespace

namespace {

// The private apt configuration: every state and cache folder under `apt`.
std::vector<std::string> apt_options(const std::string& apt) {
  std::vector<std::string> o = {
      "-o", "Dir::Etc::sourcelist=" + apt + "/sources.list",
      "-o", "Dir::Etc::sourceparts=/nonexistent",
      "-o", "Dir::State::Lists=" + apt + "/lists",
      "-o", "Dir::Cache=" + apt + "/cache",
      "-o", "Debug::NoLocking=true",
      "-o", "APT::Get::List-Cleanup=false"};
  // apt downloads as user _apt when root, who cannot enter our private folder
  if (::geteuid() == 0) o.insert(o.end(), {"-o", "APT::Sandbox::User=root"});
  return o;
}

// Package -> version the suite offers (apt-cache madison over the private configuration).
std::map<std::string, std::string> offered_versions(const std::vector<std::string>& apt,
                                                    const std::vector<std::string>& packages) {
  std::vector<std::string> argv = {"apt-cache"};
  argv.insert(argv.end(), apt.begin(), apt.end());
  argv.push_back("madison");
  argv.insert(argv.end(), packages.begin(), packages.end());
  util::ChildSpec spec;
  spec.argv = argv;
  spec.stdin_null = true;
  spec.capture_output = true;
  const util::ProgramResult r =
      util::run_program(spec);  // exits non-zero when one package is unknown
  std::map<std::string, std::string> out;
  std::istringstream in(r.output);
  for (std::string line; std::getline(in, line);) {
    // "  libosmesa6 | 25.0.7-2~bpo12+1 | http://deb.debian.org/debian bookworm-backports/main ..."
    std::vector<std::string> f;
    std::istringstream cells(line);
    for (std::string c; std::getline(cells, c, '|');) {
      c.erase(0, c.find_first_not_of(' '));
      c.erase(c.find_last_not_of(' ') + 1);
      f.push_back(c);
    }
    if (f.size() >= 3 && f[2].find("Packages") != std::string::npos && !out.count(f[0]))
      out[f[0]] = f[1];  // the first listed is the newest
  }
  return out;
}

// Downloads and unpacks the suite's packages into `root`; returns package -> version.
std::map<std::string, std::string> download_and_unpack(const FetchOptions& o, const std::string& work,
                                                       const std::string& root) {
  const std::string apt = work + "/apt";
  for (const char* d : {"/lists/partial", "/cache/archives/partial", "/debs"})
    fs::create_directories((d[1] == 'd' ? work : apt) + d);
  const std::string keyring = "/usr/share/keyrings/debian-archive-keyring.gpg";
  util::write_file_atomic(
      apt + "/sources.list",
      "deb " + (fs::exists(keyring) ? "[signed-by=" + keyring + "] " : std::string()) + o.mirror +
          " " + o.suite + " main\n");
  const std::vector<std::string> opts = apt_options(apt);
  std::vector<std::string> update = {"apt-get"};
  update.insert(update.end(), opts.begin(), opts.end());
  update.insert(update.end(), {"--error-on=any", "-q", "update"});
  try {
    run_tool(update, "apt-get update of " + o.suite);
  } catch (const util::UserError& e) {
    throw util::UserError(
        "suite '" + o.suite + "' of " + o.mirror +
        " is unreachable or does not exist (nothing was written to the cache): " + e.what());
  }
  std::vector<std::string> all = required_build_packages();
  all.insert(all.end(), optional_build_packages().begin(), optional_build_packages().end());
  const std::map<std::string, std::string> versions = offered_versions(opts, all);
  for (const std::string& p : required_build_packages())
    if (!versions.count(p))
      throw util::UserError("suite '" + o.suite + "' of " + o.mirror + " has no package '" + p +
                            "' (a Mesa build needs " +
                            [] {
                              std::string s;
                              for (const auto& r : required_build_packages())
                                s += (s.empty() ? "" : " ") + r;
                              return s;
                            }() +
                            "); nothing was written to the cache");
  std::vector<std::string> download = {"apt-get"};
  download.insert(download.end(), opts.begin(), opts.end());
  download.insert(download.end(), {"-q", "download"});
  for (const auto& [p, v] : versions) download.push_back(p + "=" + v);
  run_tool(download, "apt-get download from " + o.suite, work + "/debs");
  fs::create_directories(root);
  for (const auto& e : fs::directory_iterator(work + "/debs"))
    if (e.path().extension() == ".deb")
      run_tool({"dpkg-deb", "-x", e.path().string(), root}, "dpkg-deb -x " + e.path().string());
  return versions;
}

}  // namespace

nlohmann::json probe_build(rundir::BuildRecord& s, const std::string& dir) {
  nlohmann::json gl = nlohmann::json::object();
  for (const auto& [key, platform] : {std::pair{"osmesa", "osmesa-llvmpipe"},
                                      std::pair{"egl", "egl-llvmpipe"}}) {
    rundir::PlatformSpec spec = *rundir::find_platform(std::string(platform) + "@" + s.name);
    spec.build_dir = dir;
    const platforms::PlatformProbe p = platforms::probe_platform(spec);
    gl[key] = p.available ? nlohmann::json{{"renderer", p.driver.renderer},
                                           {"version", p.driver.version}}
                          : nlohmann::json{{"error", p.reason}};
    (std::string(key) == "osmesa" ? s.osmesa_version : s.egl_version) = p.driver.version;
  }
  return gl;
}

std::vector<std::string> build_libraries(const std::string& dir) {
  std::vector<std::string> files;
  std::error_code ec;
  const std::string lib_dir = rundir::build_library_dir(dir);
  if (fs::is_directory(lib_dir, ec))
    for (const auto& e : fs::recursive_directory_iterator(lib_dir))
      if (e.is_regular_file() && e.path().string().find(".so") != std::string::npos)
        files.push_back(e.path().lexically_relative(dir).string());
  std::sort(files.begin(), files.end());
  return files;
}

const std::vector<std::string>& required_build_packages() {
  static const std::vector<std::string> p = {"libosmesa6", "libegl-mesa0", "libgbm1", "libdrm2"};
  return p;
}

const std::vector<std::string>& optional_build_packages() {
  static const std::vector<std::string> p = {"mesa-libgallium", "libglapi-mesa", "libgl1-mesa-dri",
                                             "mesa-vulkan-drivers"};  // lavapipe: vk-lavapipe@BUILD
  return p;
}

bool is_mirror_url(const std::string& url) {
  for (const unsigned char c : url)
    if (c <= 0x20 || c >= 0x7f || c == '"' || c == '\'' || c == '[' || c == ']' || c == '\\')
      return false;
  for (const char* scheme : {"http://", "https://"}) {
    const std::size_t n = std::strlen(scheme);
    if (url.compare(0, n, scheme) == 0) {
      const std::string host = url.substr(n, url.find('/', n) - n);
      return !host.empty() && host.find('@') == std::string::npos;
    }
  }
  return url.compare(0, 6, "file:/") == 0 && url.size() > 6;
}

rundir::BuildRecord fetch_build(const FetchOptions& options) {
  if (!is_mirror_url(options.mirror))
    throw util::UserError("builds fetch: --mirror '" + options.mirror +
                          "' is not one Debian archive address (allowed: http://HOST/PATH, "
                          "https://HOST/PATH or file:/PATH; no spaces, quotes, brackets or control "
                          "characters)");
  if (!rundir::is_build_name(options.suite))
    throw util::UserError("'" + options.suite +
                          "' is not a Debian suite name (letters, digits, ._-)");
  const std::string cache = options.cache.empty() ? rundir::build_cache_dir() : options.cache;
  require_cache_folder(cache);
  std::string work = cache + "/.fetch-" + options.suite + "-XXXXXX";
  if (!::mkdtemp(work.data()))
    throw util::UserError(util::io_error_message("cannot create a folder in", cache));
  const std::string root = work + "/build";
  try {
    const std::map<std::string, std::string> versions = download_and_unpack(options, work, root);
    rundir::BuildRecord s;
    s.debian_version = versions.at("libosmesa6");
    s.name = "mesa-" + upstream_version(s.debian_version);
    s.suite = options.suite;
    s.fetched_utc = rundir::utc_now_iso8601();
    // Probe both back ends in children of their own, from the temporary folder.
    const nlohmann::json gl = probe_build(s, root);
    if (s.osmesa_version.empty() && s.egl_version.empty())
      throw util::UserError("the Mesa of suite '" + options.suite +
                            "' cannot draw here: " + gl.dump());
    s.files = build_libraries(root);
    nlohmann::json packages = nlohmann::json::object();
    for (const auto& [p, v] : versions) packages[p] = v;
    nlohmann::json j = {{"name", s.name},          {"suite", s.suite},
                        {"origin", "Debian"},      {"mirror", options.mirror},
                        {"debian_version", s.debian_version},
                        {"fetched_utc", s.fetched_utc}, {"packages", packages},
                        {"gl", gl},                {"files", s.files}};
    j.update(rundir::document_header(rundir::kBuildDocument, rundir::kBuildDocumentVersion, false));
    util::write_file_atomic(rundir::build_record_path(root), j.dump(2) + "\n");
    // Into place: a build of the same name is moved aside first, then removed.
    s.dir = cache + "/" + s.name;
    const std::string old = work + "/replaced";
    if (fs::exists(s.dir)) fs::rename(s.dir, old);
    fs::rename(root, s.dir);
    fs::remove_all(work);
    return s;
  } catch (...) {
    std::error_code ec;
    fs::remove_all(work, ec);
    throw;
  }
}

void require_cache_folder(const std::string& cache) {
  std::error_code ec;
  if (fs::exists(cache, ec) && !fs::is_directory(cache, ec))
    throw util::UserError("the build cache " + cache +
                          " is not a folder (RENDERAUDIT_BUILD_CACHE, --cache): name a folder");
  fs::create_directories(cache, ec);
  if (ec) throw util::UserError(util::io_error_message("cannot create the build cache", cache));
}

}  // namespace ra::builds
