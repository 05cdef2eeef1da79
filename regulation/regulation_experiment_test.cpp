// Tests of the regulation experiment file (regulation_experiment.h): defaults, and errors located
// at FILE:LINE:COLUMN.
#include "regulation/regulation_experiment.h"

#include <gtest/gtest.h>

#include "util/errors.h"

namespace ra::regulation {
namespace {

const char* kScene = "\n[[scene]]\nkind = \"forest\"\ntrees = 3\n";

std::string error_of(const std::string& text) {
  try {
    parse_regulation_experiment(text, "reg.toml");
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "no error";
}

TEST(RegulationExperiment, DefaultsAndValues) {
  const RegulationSettings s = parse_regulation_experiment(
      std::string("[regulation]\nbudgets_ms = [1, 2.5]\n[regulation.attention]\nalpha = 0.5\n"
                  "tags = { \"tree 2\" = \"background\" }\n") + kScene,
      "dir/reg.toml");
  EXPECT_EQ(s.name, "reg");
  EXPECT_EQ(s.platform, "osmesa-llvmpipe");
  EXPECT_EQ(s.budgets_ms, (std::vector<double>{1, 2.5}));
  EXPECT_EQ(s.lod_ratios.front(), 1.0);
  EXPECT_DOUBLE_EQ(s.attention.alpha, 0.5);
  EXPECT_EQ(s.attention.tags.at("tree 2"), Category::kBackground);
  EXPECT_EQ(s.scene.kind, "forest");
  EXPECT_EQ(s.scene.forest.trees, 3);
  EXPECT_TRUE(s.cost.measured_pixels);  // #pix measured by default
  const RegulationSettings e = parse_regulation_experiment(
      std::string("[regulation]\n[regulation.cost_model]\npixels = \"estimated\"\n") + kScene, "reg.toml");
  EXPECT_FALSE(e.cost.measured_pixels);
}

TEST(RegulationExperiment, ErrorsAreLocated) {
  EXPECT_EQ(error_of(std::string("[regulation]\nrepetitions = 0\n") + kScene),
            "reg.toml:2:15: 'regulation.repetitions' = 0 is out of range (allowed: 1 to 1000)");
  EXPECT_EQ(error_of(std::string("[regulation]\nbudgets_ms = [4, 2]\n") + kScene),
            "reg.toml:2:18: 'regulation.budgets_ms' = 2 is out of range (allowed: increasing, each in (0, 10000])");
  EXPECT_EQ(error_of(std::string("[regulation]\n[regulation.attention]\nalpha = 1.5\n") + kScene),
            "reg.toml:3:9: 'regulation.attention.alpha' = 1.5 is out of range (allowed: 0 to 1)");
  EXPECT_EQ(error_of(std::string("[regulation]\nlod_ratios = [1, 0.5, 0.7]\n") + kScene),
            "reg.toml:2:23: 'regulation.lod_ratios' = 0.7 is out of range (allowed: below the previous ratio, above 0)");
  // an unknown key and a wrong type
  EXPECT_NE(error_of(std::string("[regulation]\nbudget = 3\n") + kScene).find("reg.toml:2:"), std::string::npos);
  EXPECT_NE(error_of(std::string("[regulation]\nrender = 1\n") + kScene)
                .find("reg.toml:2:10: 'regulation.render' must be true or false"),
            std::string::npos);
  EXPECT_NE(error_of("[regulation]\n[regulation.attention]\nshare = { background = 0.35 }\n" + std::string(kScene))
                .find("reg.toml:3:9: 'regulation.attention.share' sums to 0.85"),
            std::string::npos);
  EXPECT_EQ(error_of(std::string("[regulation]\n[regulation.cost_model]\npixels = \"exact\"\n") + kScene),
            "reg.toml:3:10: 'regulation.cost_model.pixels' must be a string (allowed: \"measured\", \"estimated\")");
  EXPECT_NE(error_of("[regulation]\n").find("exactly one [[scene]]"), std::string::npos);
  EXPECT_NE(error_of(std::string("[regulation]\nplatform = \"reference\"\n") + kScene).find("reg.toml:2:12:"),
            std::string::npos);
}

// The random instances' exact DP must fit dp_max_cells: rejected when the file is read, at
// random.max_cost (else random.objects, else dp_max_cells), naming the three keys and the largest
// allowed max_cost.
TEST(RegulationExperiment, RandomInstancesMustFitTheDpLimit) {
  const std::string e = error_of(std::string("[regulation]\n[regulation.random]\nobjects = [2, 64]\nmax_cost = 100000\n") + kScene);
  EXPECT_EQ(e.find("reg.toml:4:12: 'regulation.random.max_cost' = 100000"), 0u) << e;
  EXPECT_NE(e.find("'regulation.random.objects' = [2, 64]"), std::string::npos) << e;
  EXPECT_NE(e.find("'regulation.dp_max_cells' = 400000000"), std::string::npos) << e;
  // 64 (64 c + 1) <= 4e8  <=>  c <= 97656
  EXPECT_NE(e.find("allowed: regulation.random.max_cost <= 97656"), std::string::npos) << e;
  // the limit and the bound agree on both sides of it
  EXPECT_NO_THROW(parse_regulation_experiment(
      std::string("[regulation]\n[regulation.random]\nobjects = [2, 64]\nmax_cost = 97656\n") + kScene, "reg.toml"));
  // located at objects when max_cost is the default, at dp_max_cells when neither is given
  EXPECT_EQ(error_of(std::string("[regulation]\ndp_max_cells = 1000\n[regulation.random]\nobjects = [2, 64]\n") + kScene)
                .find("reg.toml:4:11: "), 0u);
  const std::string d = error_of(std::string("[regulation]\ndp_max_cells = 1000\n") + kScene);
  EXPECT_EQ(d.find("reg.toml:2:16: "), 0u) << d;
  EXPECT_NE(d.find("allowed: regulation.random.max_cost <= "), std::string::npos) << d;
  // no random instances: nothing to check
  EXPECT_NO_THROW(parse_regulation_experiment(
      std::string("[regulation]\ndp_max_cells = 1000\n[regulation.random]\ninstances = 0\n") + kScene, "reg.toml"));
  // the settings carry the limit to the instances
  const RegulationSettings s = parse_regulation_experiment(std::string("[regulation]\ndp_max_cells = 5000000\n") + kScene, "reg.toml");
  EXPECT_EQ(s.random.dp_max_cells, 5000000);
}

TEST(RegulationExperiment, ValidatePlatformNamesTheAllowedOnes) {
  EXPECT_NO_THROW(validate_platform("osmesa-llvmpipe"));
  EXPECT_NO_THROW(validate_platform("osmesa-softpipe"));
  EXPECT_NO_THROW(validate_platform("egl-llvmpipe"));
  EXPECT_NO_THROW(validate_platform("egl-device:1"));
  EXPECT_THROW(validate_platform("egl-llvmpipe-msaa4"),
               util::UserError);                                  // the study draws aliased
  EXPECT_THROW(validate_platform("reference"), util::UserError);  // no GL to time
  try {
    validate_platform("a\"b");
    ADD_FAILURE();
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find(
                  "(allowed: osmesa-llvmpipe, osmesa-softpipe, egl-llvmpipe, egl-softpipe, "
                  "egl-zink, egl-device, egl-device:N)"), std::string::npos);
  }
}

}  // namespace
}  // namespace ra::regulation
