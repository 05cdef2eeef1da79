// End-to-end tests of `renderaudit audit` (the acceptance tests): small experiments run
// through the program, audited through the program, checked against what the records say.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <tuple>

#include "audit/history_db.h"
#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

// kind, view, index
using Key = std::tuple<std::string, int, uint64_t>;

std::string experiment(const std::string& platforms, const std::string& views,
                       const std::string& primitives, const std::string& extra = "",
                       int seed = 11) {
  return "seed = " + std::to_string(seed) + "\nplatforms = [" + platforms + "]\n[views]\n" + views +
         "near = 0.01\nfar = 10.0\n[primitives]\n" + primitives + "[run]\nshard_size = 1000\n" +
         extra;
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

nlohmann::json read_json(const std::string& path) { return nlohmann::json::parse(read_text(path)); }

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> f;
  std::stringstream s(line);
  std::string x;
  while (std::getline(s, x, ',')) f.push_back(x);
  if (!line.empty() && line.back() == ',') f.push_back("");
  return f;
}

// A primitive's identity in the records: status, visibility and pixel hash of one platform,
// read independently of the program (plain CSV, columns by header name).
std::map<Key, std::string> records_of(const std::string& run_dir, const std::string& platform) {
  std::map<Key, std::string> out;
  for (const auto& e : fs::directory_iterator(run_dir + "/records")) {
    if (!ra::rundir::is_records_file_name(e.path().filename().string())) continue;
    std::istringstream in(read_records_text(e.path().string()));
    std::string line;
    std::getline(in, line);
    const std::vector<std::string> header = split(line);
    auto col = [&](const char* name) {
      return std::size_t(std::find(header.begin(), header.end(), name) - header.begin());
    };
    const std::size_t p = col("platform"), k = col("kind"), v = col("view"), i = col("index"),
                      st = col("status"), vis = col("visibility"), h = col("pixel_hash");
    while (std::getline(in, line)) {
      const std::vector<std::string> f = split(line);
      if (f.at(p) != platform) continue;
      out[{f.at(k), std::stoi(f.at(v)), std::stoull(f.at(i))}] =
          f.at(st) + "/" + f.at(vis) + "/" + f.at(h);
    }
  }
  return out;
}

// The primitives whose records differ between two platforms (or runs).
std::set<Key> differing(const std::map<Key, std::string>& a, const std::map<Key, std::string>& b) {
  std::set<Key> out;
  for (const auto& [key, value] : a)
    if (b.count(key) && b.at(key) != value) out.insert(key);
  return out;
}

// The primitives audit listed in changed_primitives.csv: all, or those with the given recheck.
std::set<Key> listed(const std::string& audit_dir, const std::string& recheck = "") {
  std::set<Key> out;
  std::ifstream in(audit_dir + "/changed_primitives.csv");
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line);
    if (recheck.empty() || f.at(6) == recheck)
      out.insert({f.at(2), std::stoi(f.at(3)), std::stoull(f.at(5))});
  }
  return out;
}

Outcome run_experiment(const std::string& toml, const std::string& out,
                       const std::string& extra = "") {
  return run_renderaudit("run " + toml + " --out " + out + " --jobs 2 --quiet " + extra);
}

const std::string kOneView = "orientations = 1\nfov_deg = [150]\nwindows = [32]\n";

// 1. A run compared with a re-run of itself (same experiment, another directory) is unchanged;
// the history database gets the audit; --expect-renderer checks the current drivers.
TEST(AuditCommand, ARerunOfTheSameExperimentIsUnchanged) {
  const std::string dir = fresh_dir("audit_rerun");
  write_text(dir + "/e.toml", experiment("\"osmesa-llvmpipe\"", kOneView,
                                         "points = 20\nlines = 20\ntriangles = 20\n"));
  ASSERT_EQ(run_experiment(dir + "/e.toml", dir + "/base").exit_code, 0);
  ASSERT_EQ(run_experiment(dir + "/e.toml", dir + "/cur").exit_code, 0);
  const Outcome o =
      run_renderaudit("audit " + dir + "/base " + dir + "/cur --db " + dir + "/h.sqlite");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("audit: unchanged (exit 0)"), std::string::npos) << o.output;
  const nlohmann::json j = read_json(dir + "/cur/audit/audit.json");
  EXPECT_EQ(j["schema_version"], 2);
  EXPECT_EQ(j["verdict"], "unchanged");
  EXPECT_EQ(j["counts"]["compared"], 3 * 20);
  EXPECT_EQ(j["counts"]["changed"], 0);
  EXPECT_EQ(j["distribution_tests"]["significant"], 0);
  EXPECT_EQ(read_text(dir + "/cur/audit/audit.md").rfind("# renderaudit audit: UNCHANGED", 0), 0u);
  EXPECT_NE(read_text(dir + "/cur/audit/junit.xml").find("tests=\"8\" failures=\"0\""),
            std::string::npos);  // drivers, shards, point/line/triangle group A and conformance
  const std::vector<ra::audit::HistoryEntry> history = ra::audit::read_history(dir + "/h.sqlite");
  ASSERT_EQ(history.size(), 1u);
  const ra::audit::AuditSummary& s = history[0].summary;
  EXPECT_EQ(s.verdict, ra::audit::Verdict::kUnchanged);
  EXPECT_EQ(s.experiment_hash, j["experiment"]["hash"]);
  ASSERT_EQ(s.current_drivers.size(), 1u);
  EXPECT_NE(s.current_drivers[0].renderer.find("llvmpipe"), std::string::npos);
  ASSERT_FALSE(s.metrics.empty());
  EXPECT_EQ(s.metrics[0].view_group, 1);  // 1 = group A
  EXPECT_GT(s.metrics[0].n, 0);
  EXPECT_FALSE(s.classes.empty());

  const Outcome match = run_renderaudit("audit " + dir + "/base " + dir +
                                        "/cur --no-history --expect-renderer llvmpipe");
  EXPECT_EQ(match.exit_code, 0) << match.output;
  const Outcome mismatch = run_renderaudit("audit " + dir + "/base " + dir + "/cur --no-history " +
                                           "--expect-renderer '^softpipe' --out " + dir + "/o2");
  EXPECT_EQ(mismatch.exit_code, 2) << mismatch.output;
  EXPECT_NE(mismatch.output.find("does not match --expect-renderer '^softpipe'"), std::string::npos)
      << mismatch.output;
  EXPECT_EQ(read_json(dir + "/o2/audit.json")["verdict"], "failed");
}

// 2. llvmpipe and softpipe differ (8 vs 4 subpixel bits): exactly the primitives whose records
// differ are listed, and every one stays different when both are rendered again.
TEST(AuditCommand, BetweenLlvmpipeAndSoftpipeListsExactlyTheDifferingPrimitives) {
  const std::string dir = fresh_dir("audit_between");
  write_text(dir + "/e.toml", experiment("\"osmesa-llvmpipe\", \"osmesa-softpipe\"", kOneView,
                                         "points = 0\nlines = 40\ntriangles = 40\n"));
  ASSERT_EQ(run_experiment(dir + "/e.toml", dir + "/run").exit_code, 0);
  // a history kept where --db names it; its row says which two platforms were compared
  const Outcome o = run_renderaudit("audit " + dir + "/run --between osmesa-llvmpipe " +
                                    "osmesa-softpipe --db " + dir + "/history.sqlite");
  ASSERT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("history: appended to " + dir + "/history.sqlite"), std::string::npos)
      << o.output;
  const Outcome h = run_renderaudit("history --db " + dir + "/history.sqlite --out " + dir + "/h");
  EXPECT_EQ(h.exit_code, 0) << h.output;
  EXPECT_NE(h.output.find(" osmesa-llvmpipe vs osmesa-softpipe "), std::string::npos)
      << h.output;
  EXPECT_EQ(run_renderaudit("history").exit_code, 2) << "the database is named explicitly";
  const std::string out = dir + "/run/audit-osmesa-llvmpipe-vs-osmesa-softpipe";
  const std::set<Key> expected = differing(records_of(dir + "/run", "osmesa-llvmpipe"),
                                           records_of(dir + "/run", "osmesa-softpipe"));
  ASSERT_GT(expected.size(), 0u);
  EXPECT_EQ(listed(out), expected);
  EXPECT_EQ(listed(out, "still different"), expected);
  const nlohmann::json j = read_json(out + "/audit.json");
  EXPECT_EQ(j["verdict"], "changed");
  EXPECT_EQ(j["counts"]["changed"], expected.size());
  EXPECT_EQ(j["counts"]["flakes"], 0);
  EXPECT_EQ(j["flake_check"]["both_sides"], true);
  // Each changed primitive's show line pastes as printed: the program as it can be run from any
  // folder (this build's absolute path; "renderaudit" where that is on PATH).
  const std::string md = read_text(out + "/audit.md");
  const std::size_t show = md.find(" show " + dir + "/run --platform osmesa-softpipe --kind ");
  ASSERT_NE(show, std::string::npos) << md;
  const std::size_t open = md.rfind('`', show), close = md.find('`', show);
  const std::string line = md.substr(open + 1, close - open - 1);
  EXPECT_TRUE(line.rfind(std::string(RA_BINARY) + " show ", 0) == 0 ||
              line.rfind("renderaudit show ", 0) == 0) << line;
  const Outcome pasted = run_command(line + " --out " + dir + "/pasted.png");
  EXPECT_EQ(pasted.exit_code, 0) << line << "\n" << pasted.output;
  EXPECT_TRUE(fs::exists(dir + "/pasted.png"));
  std::printf("[ llvmpipe vs softpipe ] %zu of %d primitives changed; %d significant tests\n",
              expected.size(), int(j["counts"]["compared"]),
              int(j["distribution_tests"]["significant"]));
}

// 3. The faulty platform (reference base) shifting 1% of its primitives by one pixel, against the
// reference platform of the same run: the listed primitives are exactly the differing ones, about
// 1% of the primitives, and none is a flake.
TEST(AuditCommand, InjectedShiftsAreFoundExactly) {
  const std::string dir = fresh_dir("audit_shift");
  write_text(dir + "/e.toml", experiment("\"reference\", \"faulty\"", kOneView,
                                         "points = 0\nlines = 600\ntriangles = 600\n",
                                         "[faults]\nshift_fraction = 0.01\n"));
  ASSERT_EQ(run_experiment(dir + "/e.toml", dir + "/run").exit_code, 0);
  // an ad-hoc comparison of two platforms keeps no history unless --db names one, and says so
  const Outcome o = run_renderaudit("audit " + dir + "/run --between reference faulty");
  ASSERT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("history: none kept for --between (--db FILE keeps one)"),
            std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir + "/history.sqlite"));
  const std::string out = dir + "/run/audit-reference-vs-faulty";
  const std::set<Key> expected =
      differing(records_of(dir + "/run", "reference"), records_of(dir + "/run", "faulty"));
  EXPECT_EQ(listed(out), expected);
  EXPECT_EQ(listed(out, "still different"), expected);
  // Shifts are drawn per (kind, index) for all views; with one view each differing primitive is
  // one shifted, visible one. Not every shifted primitive is visible: somewhat fewer than 1%.
  EXPECT_GE(expected.size(), 4u);
  EXPECT_LE(expected.size(), 24u);  // 2%
  std::printf("[ faulty shift 1%% ] %zu of 1200 primitives changed\n", expected.size());
}

// 4. Flaky primitives (wrong on the first attempt only) are reported as flakes, not changes. The
// run is copied as the current run; the baseline's shards are then rendered again as second
// attempts (`worker` with RA_RENDER_ATTEMPT=2), which have no flaky pixels.
TEST(AuditCommand, FlakesAreReportedApartAndLeaveTheVerdictUnchanged) {
  const std::string dir = fresh_dir("audit_flakes");
  write_text(dir + "/e.toml", experiment("\"faulty\"", kOneView, "lines = 100\ntriangles = 100\n",
                                         "[faults]\nflaky_fraction = 0.05\n"));
  ASSERT_EQ(run_experiment(dir + "/e.toml", dir + "/base").exit_code, 0);
  fs::copy(dir + "/base", dir + "/cur", fs::copy_options::recursive);
  ::setenv("RA_RENDER_ATTEMPT", "2", 1);
  const Outcome lines = run_renderaudit("worker " + dir + "/base faulty line 1 0 100");
  const Outcome triangles = run_renderaudit("worker " + dir + "/base faulty triangle 1 0 100");
  ::unsetenv("RA_RENDER_ATTEMPT");
  ASSERT_EQ(lines.exit_code, 0) << lines.output;
  ASSERT_EQ(triangles.exit_code, 0) << triangles.output;
  const std::set<Key> flaky =
      differing(records_of(dir + "/base", "faulty"), records_of(dir + "/cur", "faulty"));
  ASSERT_GT(flaky.size(), 0u);
  const Outcome o = run_renderaudit("audit " + dir + "/base " + dir + "/cur --no-history");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(listed(dir + "/cur/audit", "flake"), flaky);
  const nlohmann::json j = read_json(dir + "/cur/audit/audit.json");
  EXPECT_EQ(j["verdict"], "unchanged");
  EXPECT_EQ(j["flakes"]["total"], flaky.size());
  EXPECT_EQ(j["changed_primitives"]["total"], 0);
  EXPECT_EQ(j["flake_check"]["both_sides"], false);
  const std::string md = read_text(dir + "/cur/audit/audit.md");
  EXPECT_NE(md.find(std::to_string(flaky.size()) + " difference(s) disappeared on re-render"),
            std::string::npos)
      << md;
  std::printf("[ flakes ] %zu flaky primitives of 200\n", flaky.size());
}

// Why: runs written as plain CSV (run.records_format = "csv", or before records were compressed)
// stay auditable against compressed ones, both ways round, and analysable.
TEST(AuditCommand, APlainCsvRunAndACompressedRunAuditAsUnchanged) {
  const std::string dir = fresh_dir("audit_formats");
  write_text(dir + "/plain.toml", experiment("\"reference\"", kOneView, "points = 30\nlines = 30\n",
                                             "records_format = \"csv\"\n"));
  write_text(dir + "/zst.toml", experiment("\"reference\"", kOneView, "points = 30\nlines = 30\n"));
  ASSERT_EQ(run_experiment(dir + "/plain.toml", dir + "/plain").exit_code, 0);
  ASSERT_EQ(run_experiment(dir + "/zst.toml", dir + "/zst").exit_code, 0);
  EXPECT_TRUE(fs::exists(dir + "/plain/records/reference.point.v1.0-30.csv"));
  EXPECT_TRUE(fs::exists(dir + "/zst/records/reference.point.v1.0-30.csv.zst"));
  EXPECT_EQ(records_of(dir + "/plain", "reference"), records_of(dir + "/zst", "reference"));
  for (const auto& [base, cur] : {std::pair{"plain", "zst"}, std::pair{"zst", "plain"}}) {
    const Outcome o = run_renderaudit("audit " + dir + "/" + base + " " + dir + "/" + cur +
                                      " --no-history");
    EXPECT_EQ(o.exit_code, 0) << o.output;
    EXPECT_EQ(read_json(dir + "/" + cur + "/audit/audit.json")["counts"]["compared"], 60);
  }
  EXPECT_EQ(run_renderaudit("analyze " + dir + "/plain").exit_code, 0);
}

// 5a. Crash / timeout records and missing shards (hand-edited copies of a clean run): failed,
// exit 2, the primitives and shards named.
TEST(AuditCommand, CrashRecordsAndMissingShardsFail) {
  const std::string dir = fresh_dir("audit_failed");
  std::string toml = experiment("\"reference\"", kOneView, "points = 20\n");
  toml.replace(toml.find("shard_size = 1000"), 17, "shard_size = 10");
  write_text(dir + "/e.toml", toml);
  ASSERT_EQ(run_experiment(dir + "/e.toml", dir + "/base").exit_code, 0);
  fs::copy(dir + "/base", dir + "/crash", fs::copy_options::recursive);
  fs::copy(dir + "/base", dir + "/missing", fs::copy_options::recursive);

  // Index 4 becomes a crash record.
  const std::string shard = dir + "/crash/records/reference.point.v1.0-10.csv.zst";
  std::stringstream in(read_records_text(shard));
  std::string line, edited;
  std::getline(in, line);
  edited = line + "\n";
  const std::vector<std::string> header = split(line);
  const std::size_t status =
      std::size_t(std::find(header.begin(), header.end(), "status") - header.begin());
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;  // the seal, made again below
    std::vector<std::string> f = split(line);
    if (f.at(std::size_t(std::find(header.begin(), header.end(), "index") - header.begin())) == "4")
      f.at(status) = "crash";
    for (std::size_t i = 0; i < f.size(); ++i) edited += (i ? "," : "") + f[i];
    edited += "\n";
  }
  write_records_text(shard, edited);
  reseal_records_file(shard);
  const Outcome crash = run_renderaudit("audit " + dir + "/base " + dir + "/crash --no-history");
  EXPECT_EQ(crash.exit_code, 2) << crash.output;
  const nlohmann::json jc = read_json(dir + "/crash/audit/audit.json");
  EXPECT_EQ(jc["verdict"], "failed");
  ASSERT_EQ(jc["failures"]["primitives"].size(), 1u);
  EXPECT_EQ(jc["failures"]["primitives"][0]["index"], 4);
  EXPECT_EQ(jc["failures"]["primitives"][0]["status"], "crash");
  EXPECT_NE(read_text(dir + "/crash/audit/audit.md")
                .find("crash: current reference point, view 1, index 4"),
            std::string::npos);

  // The second shard is gone, and the manifest says why.
  fs::remove(dir + "/missing/records/reference.point.v1.10-20.csv.zst");
  nlohmann::json manifest = read_json(dir + "/missing/manifest.json");
  manifest["failures"] = {
      {{"shard", "reference.point.v1.10-20"}, {"reason", "timed out after 3 s (killed)"}}};
  manifest["status"] = "failed";
  write_text(dir + "/missing/manifest.json", manifest.dump(2));
  const Outcome missing =
      run_renderaudit("audit " + dir + "/base " + dir + "/missing --no-history");
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
  const nlohmann::json jm = read_json(dir + "/missing/audit/audit.json");
  ASSERT_EQ(jm["failures"]["missing_shards"].size(), 1u);
  EXPECT_EQ(jm["failures"]["missing_shards"][0]["shard"], "reference.point.v1.10-20");
  EXPECT_EQ(jm["failures"]["missing_shards"][0]["reason"], "timed out after 3 s (killed)");
  EXPECT_NE(read_text(dir + "/missing/audit/junit.xml").find("<failure type=\"failed\""),
            std::string::npos);

  // A worker failure the manifest lists, whose shard then completed without a crash record (the
  // coordinator's re-run succeeded): reported, not a failure.
  fs::copy(dir + "/base", dir + "/recovered", fs::copy_options::recursive);
  manifest = read_json(dir + "/recovered/manifest.json");
  manifest["failures"] = {{{"shard", "reference.point.v1.0-10"},
                           {"reason", "crashed (signal 11, Segmentation fault); re-running it"}}};
  write_text(dir + "/recovered/manifest.json", manifest.dump(2));
  const Outcome recovered =
      run_renderaudit("audit " + dir + "/base " + dir + "/recovered --no-history");
  EXPECT_EQ(recovered.exit_code, 0) << recovered.output;
  const nlohmann::json jr = read_json(dir + "/recovered/audit/audit.json");
  EXPECT_EQ(jr["failures"]["manifest"][0]["outcome"], "recovered");
  EXPECT_NE(read_text(dir + "/recovered/audit/audit.md").find("did not recur"), std::string::npos);
}

// 5b. End to end: a faulty platform that crashes on primitive 1 and hangs on 3. The run coordinator
// re-runs and bisects failing shards into crash / timeout records; the audit names the primitives.
// (One primitive per shard: no bisection rounds, so the hang costs two timeouts, not more.)
TEST(AuditCommand, CrashingAndHangingDriverFails) {
  const std::string dir = fresh_dir("audit_crash");
  std::string toml = experiment("\"reference\", \"faulty\"", kOneView, "points = 4\n",
                                "[faults]\ncrash = [1]\nhang = [3]\n");
  toml.replace(toml.find("shard_size = 1000"), 17, "shard_size = 1");
  write_text(dir + "/e.toml", toml);
  // The timeout leaves room for a slow start (the program loads VTK) on a busy machine.
  run_experiment(dir + "/e.toml", dir + "/run", "--timeout 4");  // exit 1: failed primitives
  const Outcome o =
      run_renderaudit("audit " + dir + "/run --between reference faulty --no-history");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  const std::string out = dir + "/run/audit-reference-vs-faulty";
  const nlohmann::json j = read_json(out + "/audit.json");
  EXPECT_EQ(j["verdict"], "failed");
  std::map<uint64_t, std::string> named;
  for (const auto& p : j["failures"]["primitives"])
    if (p["platform"] == "faulty") named[p["index"].get<uint64_t>()] = p["status"];
  EXPECT_EQ(named, (std::map<uint64_t, std::string>{{1, "crash"}, {3, "timeout"}}));
  EXPECT_TRUE(j["failures"]["missing_shards"].empty());
  const std::string md = read_text(out + "/audit.md");
  EXPECT_NE(md.find("crash: current faulty point, view 1, index 1"), std::string::npos) << md;
  EXPECT_NE(md.find("timeout: current faulty point, view 1, index 3"), std::string::npos) << md;
}

// 6. Runs of different experiments (here: another seed) are refused before anything is compared.
TEST(AuditCommand, RefusesRunsOfDifferentExperiments) {
  const std::string dir = fresh_dir("audit_refuse");
  write_text(dir + "/a.toml", experiment("\"reference\"", kOneView, "points = 5\n", "", 1));
  write_text(dir + "/b.toml", experiment("\"reference\"", kOneView, "points = 5\n", "", 2));
  ASSERT_EQ(run_experiment(dir + "/a.toml", dir + "/a").exit_code, 0);
  ASSERT_EQ(run_experiment(dir + "/b.toml", dir + "/b").exit_code, 0);
  const std::string ha = read_json(dir + "/a/manifest.json")["experiment"]["hash"];
  const std::string hb = read_json(dir + "/b/manifest.json")["experiment"]["hash"];
  const Outcome o = run_renderaudit("audit " + dir + "/a " + dir + "/b --no-history");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find(ha), std::string::npos) << o.output;
  EXPECT_NE(o.output.find(hb), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("(seed 1)"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("(seed 2)"), std::string::npos) << o.output;
  EXPECT_FALSE(fs::exists(dir + "/b/audit"));

  const Outcome one = run_renderaudit("audit " + dir + "/a --no-history");
  EXPECT_EQ(one.exit_code, 2) << one.output;
  const Outcome unknown =
      run_renderaudit("audit " + dir + "/a --between reference faulty --no-history");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_NE(unknown.output.find("--between faulty: not a platform of the run"), std::string::npos)
      << unknown.output;
}

}  // namespace
