// A manifest that is not what this program writes: every reader names the file and the key
// (analyze too), one nested too deep to parse safely is refused, not a crash, and one that is not
// JSON at all is named by every reader and kept, not overwritten, by `run`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli_harness.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace fs = std::filesystem;
using namespace ra::testing_cli;

namespace {

std::string small_run(const std::string& name) {
  const std::string dir = fresh_dir(name);
  write_text(dir + "/e.toml",
             "seed = 3\nplatforms = [\"reference\"]\n[views]\norientations = 1\nfov_deg = [30]\n"
             "windows = [128]\nnear = 0.01\nfar = 10.0\n[primitives]\nlines = 5\n");
  EXPECT_EQ(run_renderaudit("run " + dir + "/e.toml --out " + dir + "/run --quiet").exit_code, 0);
  return dir + "/run";
}

TEST(ManifestInput, AWrongFieldIsNamedByAnalyzeAsByStatus) {
  const std::string run = small_run("manifest_field");
  std::ifstream in(run + "/manifest.json");
  nlohmann::json m = nlohmann::json::parse(in);
  m["status"] = 5;
  std::ofstream(run + "/manifest.json", std::ios::trunc) << m.dump(2);
  const std::string message = run + "/manifest.json: 'status' must be";
  const Outcome status = run_renderaudit("status " + run);
  EXPECT_EQ(status.exit_code, 2) << status.output;
  EXPECT_NE(status.output.find(message), std::string::npos) << status.output;
  const Outcome analyze = run_renderaudit("analyze " + run + " --quiet");
  EXPECT_EQ(analyze.exit_code, 3) << analyze.output;
  EXPECT_NE(analyze.output.find(message), std::string::npos) << analyze.output;
  EXPECT_EQ(analyze.output.find("missing or unreadable"), std::string::npos) << analyze.output;
}

TEST(ManifestInput, ADeeplyNestedManifestIsRefusedNotACrash) {
  const std::string run = small_run("manifest_deep");
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += '[';
  for (int i = 0; i < 100000; ++i) deep += ']';
  write_text(run + "/manifest.json", "{\"status\": \"complete\", \"x\": " + deep + "}");
  // audit and analyze read it strictly: refused with the reason.
  for (const std::string& args : {"audit " + run + " " + run, "analyze " + run}) {
    const Outcome o = run_renderaudit(args);
    EXPECT_TRUE(o.exit_code == 2 || o.exit_code == 3) << args << ": " << o.exit_code << " " << o.output;
    EXPECT_NE(o.output.find("nested deeper than 256 levels"), std::string::npos)
        << args << ": " << o.output;
  }
  for (const std::string& args : {"status " + run, "merge " + run + " --out " + run + "-m"}) {
    const Outcome o = run_renderaudit(args);
    EXPECT_EQ(o.exit_code, 2) << args << ": " << o.output;  // 139 before the depth was bounded
    EXPECT_NE(o.output.find("nested deeper than 256 levels"), std::string::npos) << o.output;
  }
}

// A manifest that is not JSON is damaged (manifests are replaced by an atomic rename): status and
// merge name it; run keeps it as manifest.json.damaged (then .damaged.2, ...: no copy kept
// earlier is overwritten) before writing a new one.
TEST(ManifestInput, AnUnparseableManifestIsNamedAndKeptNotOverwritten) {
  const std::string run = small_run("manifest_unparseable");
  const std::string experiment = fs::path(run).parent_path().string() + "/e.toml";
  std::ifstream in(run + "/manifest.json");
  const std::string good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const struct {
    const char* what;
    std::string bytes;
  } cases[] = {{"empty", ""},
               {"cut", good.substr(0, good.size() / 2)},
               {"NaN", "{\"status\": NaN}"},
               {"bad UTF-8", "{\"status\": \"complete\", \"reason\": \"\xff\xfe\"}"}};
  int damage = 0;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string kept_as =
        run + "/manifest.json.damaged" + (++damage > 1 ? "." + std::to_string(damage) : "");
    write_text(run + "/manifest.json", c.bytes);
    const Outcome status = run_renderaudit("status " + run);
    EXPECT_EQ(status.exit_code, 2) << status.output;
    EXPECT_NE(status.output.find(run + "/manifest.json: not a JSON document"), std::string::npos)
        << status.output;
    fs::remove_all(run + "-m");
    const Outcome merge = run_renderaudit("merge " + run + " --out " + run + "-m");
    EXPECT_EQ(merge.exit_code, 2) << merge.output;
    EXPECT_NE(merge.output.find(run + "/manifest.json: not a JSON document"), std::string::npos)
        << merge.output;
    const Outcome resume = run_renderaudit("run " + experiment + " --out " + run + " --quiet");
    EXPECT_EQ(resume.exit_code, 0) << resume.output;
    EXPECT_NE(resume.output.find("kept it as " + kept_as + ";"), std::string::npos)
        << resume.output;
    std::ifstream kept(kept_as);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(kept)), std::istreambuf_iterator<char>()),
              c.bytes);
    EXPECT_EQ(run_renderaudit("status " + run).exit_code, 0);  // the new manifest reads
  }
}

TEST(ManifestInput, NestingIsCountedOutsideStringsOnly) {
  std::string ok = "{\"a\": \"";
  for (int i = 0; i < 1000; ++i) ok += "[{";
  ok += "\\\"\", \"b\": [[1]]}";
  EXPECT_EQ(ra::util::parse_json_document(ok, "x.json")["b"][0][0], 1);
  std::string deep;
  for (int i = 0; i < 257; ++i) deep += '[';
  for (int i = 0; i < 257; ++i) deep += ']';
  EXPECT_THROW(ra::util::parse_json_document(deep, "x.json"), ra::util::UserError);
  std::string limit;
  for (int i = 0; i < 256; ++i) limit += '[';
  for (int i = 0; i < 256; ++i) limit += ']';
  EXPECT_NO_THROW(ra::util::parse_json_document(limit, "x.json"));
}

}  // namespace
