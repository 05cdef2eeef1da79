// End-to-end tests of `renderaudit run`: sharding, resume, failures, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <tuple>
#include <nlohmann/json.hpp>

#include "metrics/conformance.h"
#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "tests/cli_harness.h"
#include "util/atomic_file.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string experiment(const std::string& platforms, int points, int shard_size,
                       const std::string& extra = "") {
  return "seed = 42\nplatforms = [" + platforms +
         "]\n[views]\norientations = 2\nfov_deg = [30, 150]\nwindows = [64]\nnear = 0.01\n"
         "far = 10.0\n[primitives]\npoints = " +
         std::to_string(points) + "\n[run]\nshard_size = " + std::to_string(shard_size) + "\n" +
         extra;
}

TEST(RunCommand, OneShardAndManyShardsGiveIdenticalRecords) {
  const std::string dir = fresh_dir("shards");
  write_text(dir + "/one.toml", experiment("\"osmesa-llvmpipe\", \"reference\"", 600, 600));
  write_text(dir + "/many.toml", experiment("\"osmesa-llvmpipe\", \"reference\"", 600, 70));
  const Outcome a = run_renderaudit("run " + dir + "/one.toml --out " + dir + "/one --jobs 1");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const Outcome b = run_renderaudit("run " + dir + "/many.toml --out " + dir + "/many --jobs 2");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto ra = records_without_timing(dir + "/one"), rb = records_without_timing(dir + "/many");
  EXPECT_EQ(ra.size(), 2u * 4 * 600);  // platforms x views x points
  EXPECT_TRUE(ra == rb);
  EXPECT_TRUE(fs::exists(dir + "/many/manifest.json"));
  EXPECT_TRUE(fs::exists(dir + "/many/summary.md"));
}

// Starting the largest expected cost first (the default) and plan order give the same records;
// the manifest says which order ran and how many core-seconds no worker used.
TEST(RunCommand, TheShardOrderChangesNoRecordAndTheManifestSaysHowTheCoresWereUsed) {
  const std::string dir = fresh_dir("order");
  write_text(dir + "/e.toml", experiment("\"osmesa-softpipe\", \"reference\"", 300, 100));
  const Outcome a = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/cost --jobs 2");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const Outcome b =
      run_renderaudit("run " + dir + "/e.toml --out " + dir + "/plan --jobs 2 --shard-order plan");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  EXPECT_TRUE(records_without_timing(dir + "/cost") == records_without_timing(dir + "/plan"));
  for (const char* order : {"cost", "plan"}) {
    const nlohmann::json m =
        nlohmann::json::parse(ra::util::read_file(dir + "/" + order + "/manifest.json"));
    const nlohmann::json& inv = m.at("invocations").back();
    EXPECT_EQ(inv.at("shard_order"),
              std::string(order) == "plan" ? "plan" : "largest-expected-cost-first");
    const double busy = inv.at("worker_busy_s"), idle = inv.at("idle_core_s"),
                 elapsed = inv.at("elapsed_s");
    EXPECT_GT(busy, 0) << order;
    EXPECT_GE(idle, 0) << order;
    EXPECT_NEAR(idle, std::max(0.0, 2 * elapsed - busy), 1e-6) << order;
    // every shard's measured wall time, for cost models and simulations of more machines
    const nlohmann::json& seconds = m.at("shard_seconds");
    EXPECT_EQ(seconds.size(), 2u * 4 * 3);  // platforms x views x shards of 100
    double sum = 0;
    for (const auto& [id, s] : seconds.items()) sum += s.get<double>();
    EXPECT_LE(sum, busy + 1e-6) << order;
    EXPECT_GT(sum, 0.5 * busy) << order;
    // the summary sets the run against the drivers' own drawing
    const std::string summary = ra::util::read_file(dir + "/" + order + "/summary.md");
    EXPECT_NE(summary.find("on 2 jobs, which is "), std::string::npos) << summary;
    EXPECT_NE(summary.find(" times the drivers' own drawing time"), std::string::npos) << summary;
    EXPECT_NE(summary.find("(shard order: " + inv.at("shard_order").get<std::string>() + ")"),
              std::string::npos)
        << summary;
  }
  const Outcome bad = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/x --shard-order fast");
  EXPECT_EQ(bad.exit_code, 2) << bad.output;  // bad input: nothing run
  EXPECT_NE(bad.output.find("--shard-order"), std::string::npos) << bad.output;
}

TEST(RunCommand, AResumedRunEqualsAnUninterruptedOne) {
  const std::string dir = fresh_dir("resume");
  write_text(dir + "/e.toml", experiment("\"osmesa-llvmpipe\"", 300, 50));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/full").exit_code, 0);
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/resumed").exit_code, 0);
  // Simulate a run killed mid-way: some shards missing, one half-written temporary file.
  int removed = 0;
  for (const auto& e : fs::directory_iterator(dir + "/resumed/records"))
    if (removed < 5 && ra::rundir::is_records_file_name(e.path().filename().string()))
      fs::remove(e.path()), ++removed;
  write_text(dir + "/resumed/records/osmesa-llvmpipe.point.v1.0-50.csv.zst.tmp", "platform,vi");
  const Outcome again = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/resumed");
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("(19 finished earlier, 5 run now, 0 incomplete)"), std::string::npos)
      << again.output;
  EXPECT_TRUE(records_without_timing(dir + "/full") == records_without_timing(dir + "/resumed"));
  for (const auto& e : fs::directory_iterator(dir + "/resumed/records"))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

// A directory's verdicts come from one version of the conformance rules: the manifest says which,
// and resuming a directory judged by other rules is refused before any shard runs.
TEST(RunCommand, AResumeUnderOtherConformanceRulesIsRefused) {
  const std::string dir = fresh_dir("rules");
  write_text(dir + "/e.toml", experiment("\"reference\"", 40, 20));
  ASSERT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/r").exit_code, 0);
  nlohmann::json m = nlohmann::json::parse(ra::util::read_file(dir + "/r/manifest.json"));
  EXPECT_EQ(m.at("conformance_rules"), ra::metrics::kConformanceRulesVersion);
  m.erase("conformance_rules");  // as an earlier renderaudit wrote it
  write_text(dir + "/r/manifest.json", m.dump(2));
  for (const auto& e : fs::directory_iterator(dir + "/r/records")) {
    fs::remove(e.path());  // one shard left to run
    break;
  }
  const Outcome again = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/r");
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find("judged by conformance rules 1, this renderaudit judges by " +
                              std::to_string(ra::metrics::kConformanceRulesVersion)),
            std::string::npos)
      << again.output;
}

// A worker that crashes or hangs is re-run once, then its shard is bisected down to the primitive
// responsible, which gets a crash / timeout record; every other record is what the same platform
// draws without faults (faulty's base is the reference rasterizer).
TEST(RunCommand, CrashingAndHangingPrimitivesAreBisectedAndRecorded) {
  const std::string dir = fresh_dir("crash");
  const std::string views =
      "seed = 3\n[views]\norientations = 1\nfov_deg = [150]\nwindows = [64]\nnear = 0.01\n"
      "far = 10.0\n[primitives]\npoints = 20\n[run]\nshard_size = 10\n";
  write_text(dir + "/clean.toml", "platforms = [\"reference\"]\n" + views);
  write_text(dir + "/e.toml",
             "platforms = [\"faulty\"]\n" + views + "[faults]\ncrash = [5]\nhang = [13]\n");
  ASSERT_EQ(run_renderaudit("run " + dir + "/clean.toml --out " + dir + "/clean").exit_code, 0);
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --timeout 2");
  EXPECT_EQ(o.exit_code, 1) << o.output;
  EXPECT_NE(o.output.find("2 shards (0 finished earlier, 2 run now, 0 incomplete)"),
            std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("faulty.point.v1.0-10: crashed (signal 11, Segmentation fault); log: " +
                          dir + "/run/logs/faulty.point.v1.0-10.log; re-running it"),
            std::string::npos)
      << o.output;
  EXPECT_NE(o.output.find("primitive 5 of faulty.point.v1.0-10 recorded as crash"),
            std::string::npos);
  EXPECT_NE(o.output.find("primitive 13 of faulty.point.v1.10-20 recorded as timeout: timed out"),
            std::string::npos);

  std::map<uint64_t, ra::metrics::Record> clean, faulty;
  for (const std::string sub : {"clean", "run"})
    for (const auto& e : fs::directory_iterator(dir + "/" + sub + "/records"))
      ra::rundir::read_records(e.path().string(), [&](const ra::metrics::Record& r) {
        (sub == "clean" ? clean : faulty)[r.index] = r;
      });
  ASSERT_EQ(faulty.size(), 20u);
  for (const auto& [i, r] : faulty) {
    if (i == 5 || i == 13) {
      EXPECT_EQ(r.status,
                i == 5 ? ra::metrics::CaseStatus::kCrash : ra::metrics::CaseStatus::kTimeout);
      EXPECT_EQ(r.platform, "faulty");
      EXPECT_EQ(r.view, 1);
      continue;
    }
    EXPECT_EQ(r.status, ra::metrics::CaseStatus::kOk) << i;
    EXPECT_EQ(r.pixel_hash, clean.at(i).pixel_hash) << i;
    EXPECT_EQ(r.visibility, clean.at(i).visibility) << i;
  }
  std::ifstream in(dir + "/run/manifest.json");
  const auto manifest = nlohmann::json::parse(in);
  EXPECT_EQ(manifest["status"], "complete-with-failed-primitives");
  ASSERT_EQ(manifest["failed_primitives"].size(), 2u);
  EXPECT_FALSE(fs::exists(dir + "/run/parts"));
}

// Workers that serve many shards (the default) give the records of one process per shard, over
// window sizes that change between shards; a crash stays with its shard: the shards before and
// after it are served, it alone is re-run and bisected in processes of its own.
TEST(RunCommand, ServedShardsEqualOneProcessPerShardAndACrashStaysWithItsShard) {
  const std::string dir = fresh_dir("served");
  write_text(dir + "/e.toml",
             "seed = 11\nplatforms = [\"osmesa-llvmpipe\"]\n[views]\norientations = 1\n"
             "fov_deg = [30, 150]\nwindows = [64, 128]\nnear = 0.01\nfar = 10.0\n"
             "[primitives]\npoints = 200\nlines = 100\ntriangles = 100\n[run]\nshard_size = 50\n");
  const Outcome a = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/served --jobs 1");
  ASSERT_EQ(a.exit_code, 0) << a.output;
  const Outcome b = run_renderaudit("run " + dir + "/e.toml --out " + dir +
                                    "/per-shard --jobs 2 --worker-per-shard");
  ASSERT_EQ(b.exit_code, 0) << b.output;
  const auto served = records_without_timing(dir + "/served");
  EXPECT_EQ(served.size(), 4u * 400);  // views x primitives
  EXPECT_TRUE(served == records_without_timing(dir + "/per-shard"));
  auto invocation = [&](const std::string& run) {
    return nlohmann::json::parse(ra::util::read_file(dir + "/" + run + "/manifest.json"))
        .at("invocations")
        .back();
  };
  EXPECT_EQ(invocation("served").at("worker_processes"), 1);  // one platform, one job
  EXPECT_EQ(invocation("served").at("workers"), "serve-shards");
  EXPECT_EQ(invocation("per-shard").at("worker_processes"), 4 * 8);  // views x shards
  EXPECT_EQ(invocation("per-shard").at("workers"), "per-shard");
  for (const auto& e : fs::directory_iterator(dir + "/served/records"))
    EXPECT_TRUE(fs::exists(dir + "/served/logs/" +
                           ra::rundir::records_file_stem(e.path().filename().string()) + ".log"))
        << e.path();

  const std::string faulty =
      "seed = 3\nplatforms = [\"faulty\"]\n[views]\norientations = 1\nfov_deg = [150]\n"
      "windows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 60\n[run]\n"
      "shard_size = 10\n[faults]\ncrash = [25]\n";
  write_text(dir + "/crash.toml", faulty);
  const Outcome c = run_renderaudit("run " + dir + "/crash.toml --out " + dir + "/crash --jobs 1");
  EXPECT_EQ(c.exit_code, 1) << c.output;
  EXPECT_NE(c.output.find("faulty.point.v1.20-30: crashed (signal 11, Segmentation fault); log: " +
                          dir + "/crash/logs/faulty.point.v1.20-30.log; re-running it"),
            std::string::npos)
      << c.output;
  EXPECT_NE(c.output.find("primitive 25 of faulty.point.v1.20-30 recorded as crash"),
            std::string::npos)
      << c.output;
  const Outcome d = run_renderaudit("run " + dir + "/crash.toml --out " + dir +
                                    "/crash-per-shard --jobs 1 --worker-per-shard");
  EXPECT_EQ(d.exit_code, 1) << d.output;
  const auto crashed = records_without_timing(dir + "/crash");
  EXPECT_EQ(crashed.size(), 60u);
  EXPECT_TRUE(crashed == records_without_timing(dir + "/crash-per-shard"));
  // The six shards in two servers (before and after the crash) instead of six processes; the
  // re-run and the bisection the same in both.
  EXPECT_EQ(invocation("crash-per-shard").at("worker_processes").get<int>() -
                invocation("crash").at("worker_processes").get<int>(),
            4);
}

// A driver that hangs in its teardown, after every record is written: the run completes with
// every record, in either worker mode. A server told that no shard is left is killed after
// min(10 s, timeout); a one-shard worker at its timeout, its committed file counting as done.
TEST(RunCommand, AWorkerHangingInTeardownLosesNothing) {
  const std::string dir = fresh_dir("teardown");
  write_text(dir + "/e.toml",
             "seed = 3\nplatforms = [\"faulty\"]\n[views]\norientations = 1\nfov_deg = [150]\n"
             "windows = [64]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 30\n[run]\n"
             "shard_size = 10\n[faults]\nhang_at_exit = true\n");
  std::vector<std::multiset<std::string>> stored;
  for (const std::string mode : {"served", "per-shard"}) {
    const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/" + mode +
                                      " --jobs 1 --timeout 2" +
                                      (mode == "per-shard" ? " --worker-per-shard" : ""));
    EXPECT_EQ(o.exit_code, 0) << mode << ": " << o.output;
    const auto records = records_without_timing(dir + "/" + mode);
    EXPECT_EQ(records.size(), 30u) << mode;
    const auto manifest =
        nlohmann::json::parse(ra::util::read_file(dir + "/" + mode + "/manifest.json"));
    EXPECT_EQ(manifest.at("status"), "complete") << mode;
    if (mode == "served") {
      // One process served all three shards, then hung and was killed.
      EXPECT_EQ(manifest.at("invocations").back().at("worker_processes"), 1);
      EXPECT_NE(o.output.find("a faulty worker did not exit within 2 s of its last shard (killed; "
                              "its shards are complete"),
                std::string::npos)
          << o.output;
    } else {
      for (const char* shard : {"faulty.point.v1.0-10", "faulty.point.v1.10-20",
                                "faulty.point.v1.20-30"})
        EXPECT_NE(o.output.find(std::string("shard ") + shard +
                                ": its worker hung after writing every record (killed after 2 s"),
                  std::string::npos)
            << o.output;
    }
    stored.push_back(records);
  }
  ASSERT_EQ(stored.size(), 2u);
  EXPECT_TRUE(stored[0] == stored[1]);  // both modes stored the same records
}

// --expect-renderer stops a run that loaded another driver, before it renders for hours.
TEST(RunCommand, ExpectRendererStopsTheWrongDriver) {
  const std::string dir = fresh_dir("renderer");
  write_text(dir + "/e.toml", experiment("\"osmesa-llvmpipe\"", 20, 10));
  const Outcome wrong =
      run_renderaudit("run " + dir + "/e.toml --out " + dir + "/a --expect-renderer softpipe");
  EXPECT_EQ(wrong.exit_code, 2) << wrong.output;
  EXPECT_NE(wrong.output.find("stopped: osmesa-llvmpipe: GL_RENDERER 'llvmpipe"), std::string::npos)
      << wrong.output;
  EXPECT_NE(wrong.output.find("does not match --expect-renderer 'softpipe'"), std::string::npos);
  const Outcome right =
      run_renderaudit("run " + dir + "/e.toml --out " + dir + "/b --expect-renderer '^llvmpipe'");
  EXPECT_EQ(right.exit_code, 0) << right.output;
  const Outcome bad =
      run_renderaudit("run " + dir + "/e.toml --out " + dir + "/c --expect-renderer '('");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.output.find("not a valid regular expression"), std::string::npos) << bad.output;
}

TEST(RunCommand, BadExperimentWritesNothing) {
  const std::string dir = fresh_dir("bad");
  write_text(dir + "/e.toml", experiment("\"swrast\"", 10, 10));
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("e.toml:2:14: unknown platform 'swrast' (allowed: "), std::string::npos)
      << o.output;
  EXPECT_FALSE(fs::exists(dir + "/run"));
}

TEST(RunCommand, RefusesARunDirectoryOfAnotherExperiment) {
  const std::string dir = fresh_dir("other");
  write_text(dir + "/a.toml", experiment("\"reference\"", 10, 10));
  write_text(dir + "/b.toml", experiment("\"reference\"", 20, 10));
  ASSERT_EQ(run_renderaudit("run " + dir + "/a.toml --out " + dir + "/run").exit_code, 0);
  const Outcome o = run_renderaudit("run " + dir + "/b.toml --out " + dir + "/run");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find("holds a run of a different experiment"), std::string::npos) << o.output;
}

// [run] shard_size is outside the experiment's hash but names the records files: a run into a
// directory cut with another size is refused before anything is written, never rendered twice.
TEST(RunCommand, AnotherShardSizeIntoTheSameDirectoryIsRefused) {
  const std::string dir = fresh_dir("shard_size");
  write_text(dir + "/a.toml", experiment("\"reference\"", 30, 10));
  write_text(dir + "/b.toml", experiment("\"reference\"", 30, 7));
  ASSERT_EQ(run_renderaudit("run " + dir + "/a.toml --out " + dir + "/run --quiet").exit_code, 0);
  const auto before = records_without_timing(dir + "/run");
  ASSERT_EQ(before.size(), 4u * 30);  // views x points
  const Outcome o = run_renderaudit("run " + dir + "/b.toml --out " + dir + "/run --quiet");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("holds a run cut into shards of 10 primitives ([run] shard_size), " +
                          dir + "/b.toml asks for 7"),
            std::string::npos)
      << o.output;
  EXPECT_TRUE(records_without_timing(dir + "/run") == before);  // nothing rendered twice
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir + "/run/records"))
    files += ra::rundir::is_records_file_name(e.path().filename().string());
  EXPECT_EQ(files, 4u * 3);  // views x shards of 10
  EXPECT_EQ(run_renderaudit("analyze " + dir + "/run").exit_code, 0);
}

// Points are judged inside the depth range in eye space: with far / near of 1e18 and beyond,
// clip-space depth rounds onto w and every point looked outside (the driver, which draws them, was
// blamed: false-visible). Points lie in the unit ball, none nearer than 0.01 for this seed, so
// every near plane below 0.01 must give the records of near = 0.01, on a driver and on the
// reference, but for the near column.
TEST(RunCommand, ExtremeNearFarRatiosJudgePointsAsAModerateOneDoes) {
  const std::string dir = fresh_dir("near_far");
  auto toml = [](const std::string& near) {
    return "seed = 9\nplatforms = [\"osmesa-llvmpipe\", \"reference\"]\n[views]\n"
           "orientations = 1\nfov_deg = [30, 150]\nwindows = [128]\nnear = " + near +
           "\nfar = 10.0\n[primitives]\npoints = 300\n[run]\nshard_size = 300\n";
  };
  // what a point's judgement is made of: everything but near, timing and batching
  using Judgement = std::tuple<int, int64_t, double, int64_t, uint64_t, int>;
  auto judged = [&](const std::string& name) {
    std::map<std::tuple<std::string, int, uint64_t>, Judgement> out;
    for (const auto& e : fs::directory_iterator(dir + "/" + name + "/records"))
      ra::rundir::read_records(e.path().string(), [&](const ra::metrics::Record& r) {
        const double pe = std::isnan(r.pe) ? -1.0 : r.pe;  // empty when not true-visible
        out[{r.platform, r.view, r.index}] = {int(r.visibility), r.pixels, pe, r.ref_diff,
                                              r.pixel_hash, int(r.conformance)};
      });
    return out;
  };
  write_text(dir + "/moderate.toml", toml("0.01"));
  ASSERT_EQ(run_renderaudit("run " + dir + "/moderate.toml --out " + dir + "/moderate --quiet")
                .exit_code, 0);
  const auto expected = judged("moderate");
  ASSERT_EQ(expected.size(), 2u * 2 * 300);
  std::size_t visible = 0;
  for (const auto& [key, j] : expected)
    visible += std::get<0>(j) == int(ra::metrics::Visibility::kTrueVisible);
  EXPECT_GT(visible, 100u);  // the comparison means something
  for (const std::string near : {"1e-15", "1e-17", "1e-30", "1e-300"}) {
    write_text(dir + "/tiny.toml", toml(near));
    fs::remove_all(dir + "/tiny");
    const Outcome o = run_renderaudit("run " + dir + "/tiny.toml --out " + dir + "/tiny --quiet");
    EXPECT_EQ(o.exit_code, 0) << near << "\n" << o.output;
    const auto got = judged("tiny");
    ASSERT_EQ(got.size(), expected.size()) << near;
    std::size_t differ = 0;
    for (const auto& [key, j] : expected) differ += got.at(key) != j;
    EXPECT_EQ(differ, 0u) << "near = " << near;
  }
}

// A plan whose views need a large colour buffer per worker says how much before it starts:
// 16384 x 16384 RGBA8 pixels are 1.00 GiB each.
TEST(RunCommand, ALargeWindowSaysTheMemoryAWorkerNeeds) {
  const std::string dir = fresh_dir("large_window");
  std::string toml = experiment("\"reference\"", 1, 1);
  toml.replace(toml.find("windows = [64]"), 14, "windows = [16384]");
  write_text(dir + "/e.toml", toml);
  const Outcome o = run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet --jobs 3");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("note: views of 16384 x 16384 pixels need about 1.00 GiB of memory in "
                          "each GL worker (its colour buffer); 3 workers at once: about 3.00 GiB"),
            std::string::npos)
      << o.output;
  write_text(dir + "/small.toml", experiment("\"reference\"", 1, 1));
  const Outcome small = run_renderaudit("run " + dir + "/small.toml --out " + dir + "/small --quiet");
  EXPECT_EQ(small.output.find("GiB of memory"), std::string::npos) << small.output;
}

TEST(RunCommand, HelpNamesTheOptions) {
  const Outcome o = run_renderaudit("run --help");
  EXPECT_EQ(o.exit_code, 0);
  for (const char* opt : {"--out", "--jobs", "--timeout", "experiment file"})
    EXPECT_NE(o.output.find(opt), std::string::npos) << opt;
}

}  // namespace

// A run folder whose name starts with '-' is a path for the workers too, never an option.
TEST(RunCommand, AnOutputFolderNamedLikeAnOptionRuns) {
  const std::string dir = fresh_dir("run_dash_out");
  write_text(dir + "/e.toml",
             "seed = 3\nplatforms = [\"reference\"]\n[views]\norientations = 1\nfov_deg = [30]\n"
             "windows = [128]\nnear = 0.01\nfar = 10.0\n[primitives]\nlines = 5\n");
  ra::util::ChildSpec spec;
  spec.argv = {RA_BINARY, "run", dir + "/e.toml", "--out", "-dash", "--quiet", "--jobs", "2"};
  spec.working_dir = dir;
  spec.stdin_null = true;
  spec.capture_output = true;
  const ra::util::ProgramResult r = ra::util::run_program(spec);
  EXPECT_TRUE(r.exited_ok()) << r.output;
  EXPECT_EQ(r.output.find("platform is required"), std::string::npos) << r.output;
  EXPECT_TRUE(std::filesystem::exists(dir + "/-dash/manifest.json"));
  const Outcome s = run_renderaudit("status " + dir + "/-dash");
  EXPECT_EQ(s.exit_code, 0) << s.output;
}
