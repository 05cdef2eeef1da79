// Tests of rundir/manifest.h's write_manifest on a full disk: the manifest on disk must never stay
// "running" when the final write fails.
#include "rundir/manifest.h"

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::rundir {
namespace {

TEST(Manifest, OnAFullDiskTheManifestSaysFailedInPlace) {
  const auto dir = std::filesystem::temp_directory_path() / ("ra_manifest_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=256k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root?): " << std::strerror(errno);
  const std::string path = (dir / "manifest.json").string();
  RunManifest m = read_manifest(
      {{"schema_version", kManifestSchemaVersion},
       {"status", "running"},
       {"experiment", {{"name", "x"}, {"hash", "abc"}}},
       {"invocations", nlohmann::json::array({{{"started", "t"}, {"jobs", 1}, {"shards_to_run", 1}}})}},
      path);
  write_manifest(path, m);
  {  // fill the disk
    std::ofstream fill(dir / "fill", std::ios::binary);
    const std::string block(4096, 'x');
    while (fill.write(block.data(), block.size())) {
    }
  }
  m.status = "complete";
  m.drivers = {{"x", std::string(20000, 'd')}};  // larger than the file that is there
  try {
    write_manifest(path, m);
    ADD_FAILURE() << "writing on a full disk succeeded";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("No space left on device"), std::string::npos) << msg;
    EXPECT_NE(msg.find("bytes free on the file system of " + dir.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("now says \"failed\""), std::string::npos) << msg;
  }
  const nlohmann::json on_disk = nlohmann::json::parse(util::read_file(path));
  EXPECT_EQ(on_disk["status"], "failed");
  // What fits of the reason is kept (here the whole manifest was small: its start).
  EXPECT_EQ(on_disk.value("reason", "").rfind("cannot write the manifest: cannot write", 0), 0u)
      << on_disk.dump();
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  ::umount(dir.c_str());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ra::rundir

namespace ra::rundir {
namespace {

// A manifest as `run` writes it (a resumed run with a crash recorded), in the file's own layout:
// read and written again, it must be the same bytes.
const char* const kRunManifest = R"json({
  "conformance_rules": 2,
  "damaged_shards_redone": [
    {
      "reason": "no trailer (cut short?)",
      "shard": "reference.point.v1.0-10"
    }
  ],
  "drivers": {
    "reference": {
      "renderer": "renderaudit reference rasterizer",
      "subpixel_bits": 8,
      "version": "exact"
    }
  },
  "experiment": {
    "file": "e.toml",
    "hash": "3f2a",
    "name": "e",
    "platforms": [
      "reference"
    ],
    "seed": 18446744073709551615
  },
  "failed_primitives": [
    {
      "index": 7,
      "reason": "crashed (signal 11, Segmentation fault)",
      "shard": "reference.point.v1.0-10",
      "status": "crash"
    }
  ],
  "failures": [],
  "finished": "2026-11-26T05:42:53Z",
  "future_key": {
    "kept": [
      1,
      2.5
    ]
  },
  "host": {
    "cores": 2,
    "cpu": "x",
    "hostname": "h",
    "os": "Linux"
  },
  "invocations": [
    {
      "jobs": 2,
      "shards_to_run": 3,
      "started": "2026-11-26T05:40:00Z"
    },
    {
      "elapsed_s": 0.12345678901234566,
      "idle_core_s": 0.0,
      "jobs": 2,
      "shard_order": "largest-expected-cost-first",
      "shards_to_run": 1,
      "started": "2026-11-26T05:42:52Z",
      "worker_busy_s": 1.5,
      "worker_processes": 1,
      "workers": "serve-shards"
    }
  ],
  "platforms_run": [
    "reference"
  ],
  "schema": "renderaudit-manifest",
  "schema_version": 1,
  "shard_seconds": {
    "reference.point.v1.0-10": 0.01,
    "reference.point.v1.10-20": 3e-05
  },
  "shards": {
    "complete": 2,
    "total": 2
  },
  "slice": {
    "count": 2,
    "index": 1,
    "shards": 2
  },
  "started": "2026-11-26T05:40:00Z",
  "status": "complete-with-failed-primitives",
  "tool": {
    "commit": "0368a8c42415",
    "name": "renderaudit",
    "version": "0.1.0"
  }
}
)json";

TEST(Manifest, ARunManifestReadsBackAndRewritesToTheSameBytes) {
  const RunManifest m = read_manifest(nlohmann::json::parse(kRunManifest), "m.json");
  EXPECT_EQ(manifest_json(m).dump(2) + "\n", kRunManifest);
  ASSERT_TRUE(m.experiment && m.experiment->seed);
  EXPECT_EQ(*m.experiment->seed, 18446744073709551615ull);
  EXPECT_EQ(m.rules_judged_by(), 2);
  ASSERT_NE(m.last_invocation(), nullptr);
  EXPECT_EQ(m.last_invocation()->workers, "serve-shards");
  EXPECT_EQ(*m.last_invocation()->worker_busy_s, 1.5);
  EXPECT_EQ(m.slice->index, 1);
  EXPECT_EQ(m.failed_primitives->at(0).index, 7u);
  EXPECT_EQ(m.unknown.size(), 1u);  // "future_key", kept as read
}

TEST(Manifest, AnEarlierRunWithoutRulesWasJudgedByTheFirst) {
  RunManifest m = read_manifest(
      nlohmann::json::parse(R"({"invocations": [{"jobs": 1, "shards_to_run": 1}]})"), "m.json");
  EXPECT_EQ(m.rules_judged_by(), 1);
  EXPECT_EQ(read_manifest(nlohmann::json(), "m.json").rules_judged_by(), 0);  // a new directory
}

TEST(Manifest, AWrongTypeNamesTheFileTheKeyAndWhatItMustBe) {
  const std::pair<const char*, const char*> cases[] = {
      {R"({"invocations": [{"jobs": -1, "shards_to_run": 1}]})",
       "m.json: 'invocations[].jobs' must be an integer from 0 (found -1)"},
      {R"({"shard_seconds": {"a": "1"}})",
       "m.json: 'shard_seconds.a' must be a number of seconds (found \"1\")"},
      {R"({"experiment": {"seed": 1.5}})",
       "m.json: 'experiment.seed' must be an integer from 0 (found 1.5)"},
      {R"({"failed_primitives": [{"shard": "s", "index": "7"}]})",
       "m.json: 'failed_primitives[].index' must be an integer from 0 (found \"7\")"},
      {R"({"conformance_rules": 0})",
       "m.json: 'conformance_rules' must be an integer from 1 to 1000 (found 0)"},
      {R"({"inputs": [{"dir": "a"}]})",
       "m.json: 'inputs[].shards_taken' must be an integer from 0 (found null)"},
  };
  for (const auto& [text, message] : cases) {
    try {
      read_manifest(nlohmann::json::parse(text), "m.json");
      ADD_FAILURE() << text << " was accepted";
    } catch (const util::UserError& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
}

TEST(Manifest, TheShortestManifestAFullDiskLeavesStillReads) {
  // write_manifest's last resort keeps the experiment's name only
  const RunManifest m = read_manifest(
      nlohmann::json::parse(R"({"experiment": "e", "schema_version": 1, "status": "failed"})"),
      "m.json");
  ASSERT_TRUE(m.experiment);
  EXPECT_EQ(m.experiment->name, "e");
  EXPECT_EQ(m.status, "failed");
}

}  // namespace
}  // namespace ra::rundir
