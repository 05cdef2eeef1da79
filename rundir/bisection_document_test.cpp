// bisect.json's reader for the readers outside triage/: the inputs, completeness and culprits of
// a sealed file or one from before the seal; another document passed by or refused; a changed copy
// and a damaged field named with the file and the key.
#include "rundir/bisection_document.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <tuple>
#include <vector>

#include "rundir/manifest.h"
#include "util/errors.h"
#include "util/json_seal.h"

namespace ra::rundir {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kCommit = "a07fa6516b0123456789012345678901234567ab";

// A bisection of version 3 as `bisect` writes it (the keys these readers need, and one step), not
// yet sealed.
json a_bisection() {
  json j = {{"inputs", {{"run", "/runs/night"}, {"platform", "egl-llvmpipe"}}},
            {"original_head", "main"},
            {"selection", json::array({json::object(), json::object(), json::object()})},
            {"steps", json::array()},
            {"complete", true},
            {"culprits",
             {{{"commit", kCommit},
               {"subject", "llvmpipe/linear: add support for rgba color buffers"},
               {"date", "2025-03-04T10:00:00+01:00"},
               {"previous", std::string(40, 'b')},
               {"merge", false},
               {"primitives",
                {{{"primitive", "line 1 of view 5"}, {"pixels_before", 9}, {"pixels_after", 0}},
                 {{"primitive", "line 2 of view 5"},
                  {"pixels_before", 7},
                  {"pixels_after", -1}}}}}}},
            {"speed_culprits", json::array()}};
  j.update(document_header(kBisectionDocument, kBisectionDocumentVersion, false));
  return j;
}

struct BisectionFile {
  std::string path;
  explicit BisectionFile(const std::string& text) {
    path = (fs::temp_directory_path() /
            ("ra-bisection-document-" + std::to_string(::getpid()) + "-" +
             ::testing::UnitTest::GetInstance()->current_test_info()->name() + ".json"))
               .string();
    std::ofstream(path) << text;
  }
  ~BisectionFile() { fs::remove(path); }
};

// The message read_bisection_document stops with on `text`, or "(no error)".
std::string refusal(const std::string& text, std::string* path = nullptr) {
  const BisectionFile f(text);
  if (path) *path = f.path;
  try {
    read_bisection_document(f.path);
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(BisectionDocument, ReadsTheInputsAndTheCulpritsWithTheirPrimitives) {
  const BisectionFile f(util::sealed(a_bisection()).dump(2));
  const BisectionDocument d = read_bisection_document(f.path);
  EXPECT_EQ(d.path, f.path);
  EXPECT_EQ(d.version, 3);
  EXPECT_EQ(d.run, "/runs/night");
  EXPECT_EQ(d.platform, "egl-llvmpipe");
  EXPECT_EQ(d.selected, 3u);
  EXPECT_TRUE(d.complete);
  ASSERT_EQ(d.culprits.size(), 1u);
  EXPECT_EQ(d.culprits[0].commit, kCommit);
  EXPECT_EQ(d.culprits[0].subject, "llvmpipe/linear: add support for rgba color buffers");
  EXPECT_EQ(d.culprits[0].date, "2025-03-04T10:00:00+01:00");
  ASSERT_EQ(d.culprits[0].primitives.size(), 2u);
  EXPECT_EQ(d.culprits[0].primitives[1].label, "line 2 of view 5");
  EXPECT_EQ(d.culprits[0].primitives[0].pixels_before, 9);
  EXPECT_EQ(d.culprits[0].primitives[1].pixels_after, -1);
}

// Inputs that name no run or platform (a bisection of explicit primitives) read as "".
TEST(BisectionDocument, InputsMayLeaveTheRunAndPlatformOut) {
  json j = a_bisection();
  j["inputs"] = json::object();
  const BisectionFile f(util::sealed(j).dump());
  const BisectionDocument d = read_bisection_document(f.path);
  EXPECT_EQ(d.run, "");
  EXPECT_EQ(d.platform, "");
}

// Why: a file of version 2 was written before the seal and is still read; one of another schema
// or version is no bisection of this renderaudit: refused when named, passed by when looked for.
TEST(BisectionDocument, AnUnsealedVersion2ReadsAndAForeignDocumentIsRefused) {
  json v2 = a_bisection();
  v2["schema_version"] = 2;
  const BisectionFile old(v2.dump());
  EXPECT_EQ(read_bisection_document(old.path).version, 2);
  EXPECT_EQ(read_bisection_document(old.path).culprits.size(), 1u);
  ASSERT_TRUE(read_bisection_document_if_any(old.path));

  for (const auto& [key, value] : std::vector<std::pair<std::string, json>>{
           {"schema_version", 1}, {"schema_version", 4}, {"schema", "renderaudit-audit"}}) {
    json j = a_bisection();
    j[key] = value;
    const std::string text = util::sealed(j).dump();
    std::string path;
    const std::string e = refusal(text, &path);
    EXPECT_NE(e.find(path + ": expected schema renderaudit-bisection version 3 or 2"),
              std::string::npos)
        << e;
    const BisectionFile f(text);
    EXPECT_FALSE(read_bisection_document_if_any(f.path)) << key << " " << value;
  }
  const BisectionFile cut(util::sealed(a_bisection()).dump().substr(0, 40));
  EXPECT_FALSE(read_bisection_document_if_any(cut.path));
  std::string path;
  const std::string e = refusal(util::sealed(a_bisection()).dump().substr(0, 40), &path);
  EXPECT_NE(e.find(path + ": cannot read the bisection"), std::string::npos) << e;
  EXPECT_FALSE(read_bisection_document_if_any("/nonexistent/bisect.json"));
}

// Why: one flipped digit in a copy named another commit; the seal finds it before any value is
// used, and so does a looking reader (a damaged bisection is not passed by).
TEST(BisectionDocument, ACopyChangedAfterItWasWrittenIsRefusedByItsSeal) {
  json j = util::sealed(a_bisection());
  j["culprits"][0]["primitives"][0]["pixels_before"] = 8;
  std::string path;
  const std::string e = refusal(j.dump(), &path);
  EXPECT_NE(e.find(path + ": 'seal'"), std::string::npos) << e;
  EXPECT_NE(e.find("run the bisection again"), std::string::npos) << e;
  const BisectionFile f(j.dump());
  EXPECT_THROW(read_bisection_document_if_any(f.path), util::UserError);
}

// Why: a number where a commit belongs ended in a bare "[json.exception.type_error.302]"; a value
// that git would read as an option must never pass for a commit.
TEST(BisectionDocument, ADamagedFieldIsNamedWithItsFileAndKey) {
  const std::vector<std::tuple<std::string, std::function<void(json&)>, std::string>> damage = {
      {"culprits[0].commit", [](json& j) { j["culprits"][0]["commit"] = 7; }, "must be a string"},
      {"culprits[0].commit", [](json& j) { j["culprits"][0]["commit"] = "--output=x"; },
       "must be a full commit hash"},
      {"culprits[0].date", [](json& j) { j["culprits"][0].erase("date"); }, "is missing"},
      {"culprits[0].primitives[1].pixels_before",
       [](json& j) { j["culprits"][0]["primitives"][1]["pixels_before"] = "many"; },
       "must be a whole number"},
      {"culprits[0].primitives",
       [](json& j) { j["selection"] = json::array({json::object()}); },
       "lists 2 primitives, more than the 1 selected"},
      {"complete", [](json& j) { j["complete"] = "yes"; }, "must be true or false"},
      {"inputs.platform", [](json& j) { j["inputs"]["platform"] = 3; }, "must be a string"},
      {"selection", [](json& j) { j["selection"] = json::object(); }, "must be a list"},
      {"culprits", [](json& j) { j.erase("culprits"); }, "is missing"},
  };
  for (const auto& [key, edit, what] : damage) {
    json j = a_bisection();
    edit(j);
    std::string path;
    // Sealed again: the field's own check is what is tested here, not the seal.
    const std::string e = refusal(util::sealed(j).dump(), &path);
    EXPECT_NE(e.find(path + ": '" + key + "' " + what), std::string::npos) << key << ": " << e;
    EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
  }
}

}  // namespace
}  // namespace ra::rundir
