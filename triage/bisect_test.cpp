// The bisection's selection syntax and its state file (the loop itself: tests/scripts/bisect-test.sh,
// ctest bisect_faulty, with real drawing; the choice of commits: bisect_plan_test.cpp).
#include "triage/bisect.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <functional>

#include "triage/bisect_selection.h"
#include "triage/bisect_state.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_seal.h"

namespace fs = std::filesystem;

namespace ra::triage {
namespace {

TEST(Bisect, PrimitivesAreNamedAsKindViewIndex) {
  const BisectPrimitive p = parse_primitive("line:5:721");
  EXPECT_EQ(p.kind, geometry::Kind::kLine);
  EXPECT_EQ(p.view, 5);
  EXPECT_EQ(p.index, 721u);
  EXPECT_EQ(p.label(), "line 721 of view 5");
  EXPECT_EQ(parse_primitive("triangles:2:0").kind, geometry::Kind::kTriangle);
  for (const char* bad : {"line:5", "line:0:1", "lines:5:-1", "quad:1:1", "line:5:1x",
                          "line:x:1", "line:5:99999999999999999999", ""})
    EXPECT_THROW(parse_primitive(bad), util::UserError) << bad;
}

BisectState a_state() {
  BisectState st;
  st.inputs = {{"good", std::string(40, 'a')}};
  st.result.original_head = "main";
  BisectStep s;
  s.role = "step";
  s.commit = std::string(40, 'b');
  s.position = 3;
  s.summary = "1 like the good ref, 0 like the bad ref, 0 like neither";
  s.drawing.hashes["line 1 of view 1"] = 18446744073709551615ull;
  s.drawing.pixels["line 1 of view 1"] = 12;
  st.result.steps = {s};
  st.result.good = s;
  st.result.good.role = "good ref";
  st.result.good.position = 0;
  return st;
}

std::string temp_file() {
  return (fs::temp_directory_path() / ("bisect-state-" + std::to_string(::getpid()) + ".json"))
      .string();
}

TEST(BisectState, ReadsBackWhatItWrote) {
  const std::string path = temp_file();
  save_bisect_state(path, a_state());
  const BisectState back = load_bisect_state(path);
  EXPECT_EQ(back.inputs, a_state().inputs);
  EXPECT_EQ(back.result.original_head, "main");
  ASSERT_EQ(back.result.steps.size(), 1u);
  EXPECT_EQ(back.result.steps[0].position, 3u);
  EXPECT_EQ(back.result.steps[0].drawing.hashes.at("line 1 of view 1"), 18446744073709551615ull);
  EXPECT_EQ(back.result.bad.commit, "");  // not drawn yet
  fs::remove(path);
}

TEST(BisectState, ABadFieldIsNamedWithItsFileAndKey) {
  // Why: a hand-edited or damaged bisect.json said "stoull" or a JSON library code, exit 1.
  const std::string path = temp_file();
  const std::vector<std::pair<std::string, std::string>> damage = {
      {"steps.0.drawing.primitives.line 1 of view 1.pixel_hash", "\"x\""},
      {"steps.0.drawing.primitives.line 1 of view 1.pixel_hash", "\"99999999999999999999\""},
      {"steps.0.position", "-1"},
      {"steps.0.commit", "\"HEAD\""},
      {"steps.0.build_s", "\"slow\""},
      {"original_head", "7"},
      {"original_head", "\"--orphan=pwned\""},
      {"original_head", "\"main..x\""},
      {"steps.0.commit", "\"--output=/tmp/x\""},
      {"steps.0.role", "\"good ref\""},
      {"steps", "{}"},
  };
  for (const auto& [key, value] : damage) {
    nlohmann::json j = bisect_state_json(a_state());
    nlohmann::json* at = &j;
    std::string rest = key, last;
    for (std::size_t dot; (dot = rest.find('.')) != std::string::npos; rest = rest.substr(dot + 1)) {
      const std::string part = rest.substr(0, dot);
      at = at->is_array() ? &(*at)[std::stoul(part)] : &(*at)[part];
    }
    (*at)[rest] = nlohmann::json::parse(value);
    // Sealed again: the field's own check is what is tested here, not the seal.
    util::write_file_atomic(path, util::sealed(j).dump());
    try {
      load_bisect_state(path);
      ADD_FAILURE() << key << " = " << value << " was accepted";
    } catch (const util::UserError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(path), std::string::npos) << m;
      const std::string leaf = key.substr(key.rfind('.') + 1);
      EXPECT_NE(m.find(leaf), std::string::npos) << m;
      EXPECT_EQ(m.find("json.exception"), std::string::npos) << m;
    }
  }
  util::write_file_atomic(path, "{\"version\": 2, \"inputs\": ");
  EXPECT_THROW(load_bisect_state(path), util::UserError);
  fs::remove(path);
}

TEST(BisectState, ACopyChangedAfterItWasWrittenIsRefusedByItsSeal) {
  // Why: one flipped digit of a pixel hash named an extra culprit with exit 0; a primitive lost
  // from a drawing ended in "map::at".
  const std::string path = temp_file();
  for (const auto& damage : std::vector<std::function<void(nlohmann::json&)>>{
           [](nlohmann::json& j) {
             j["steps"][0]["drawing"]["primitives"]["line 1 of view 1"]["pixel_hash"] =
                 "18446744073709551614";
           },
           [](nlohmann::json& j) { j["good"]["drawing"]["primitives"].erase("line 1 of view 1"); },
           [](nlohmann::json& j) { j.erase("seal"); }}) {
    nlohmann::json j = bisect_state_json(a_state());
    damage(j);
    util::write_file_atomic(path, j.dump(2));
    try {
      load_bisect_state(path);
      ADD_FAILURE() << "a damaged copy was accepted: " << j.dump();
    } catch (const util::UserError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find(path + ": 'seal'"), std::string::npos) << m;
      EXPECT_NE(m.find("move the file away"), std::string::npos) << m;
    }
  }
  // A file of version 2, written before the seal, is still read (each field checked).
  nlohmann::json v2 = bisect_state_json(a_state());
  v2.erase("seal");
  v2["schema_version"] = 2;
  util::write_file_atomic(path, v2.dump(2));
  EXPECT_EQ(load_bisect_state(path).result.steps.size(), 1u);
  fs::remove(path);
}

}  // namespace
}  // namespace ra::triage
