// End to end: experiments/lod_smoke.toml through run_lod_study, analyze_lod_study and
// plot_lod_study into a temporary folder; and the experiment file's located errors.
#include "terrain_lod/lod_document.h"
#include "terrain_lod/lod_figures.h"
#include "terrain_lod/lod_run.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <fstream>
#include <sstream>

#include "plots/figure_testing.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "terrain_lod/height_field.h"
#include "terrain_lod/lod_experiment.h"

namespace ra::lod {
namespace {

std::string error_of(const std::string& text) {
  try {
    parse_lod_experiment(text, "x.toml");
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

TEST(LodExperiment, ErrorsAreLocated) {
  EXPECT_EQ(error_of("[lod]\ntau = [1, -2]\n"), "x.toml:2:11: 'lod.tau' = -2 is out of range (allowed: (0, 1000] pixels)");
  EXPECT_NE(error_of("[lod]\ntile_size = 256\n").find("x.toml:2:13: 'lod.tile_size' = 256 is out of range"), std::string::npos);
  EXPECT_NE(error_of("[lod]\nlambda = \"cubic\"\n").find("x.toml:2:10: 'lod.lambda' = \"cubic\" is out of range (allowed: window, planar, spherical)"),
            std::string::npos);
  EXPECT_NE(error_of("[lod]\nframez = 3\n").find("x.toml:2:1"), std::string::npos);
  EXPECT_NE(error_of("[lod]\nfov_deg = \"wide\"\n").find("x.toml:2:11: 'lod.fov_deg' must be a number"), std::string::npos);
  EXPECT_NE(error_of("[lod]\nnear = 10\nfar = 5\n").find("x.toml:3:7: 'lod.far' = 5 is out of range"), std::string::npos);
  // the terrain size cap: 2^24 vertices, located at `tiles` (or `tile_size` when tiles is default)
  const std::string big = error_of("[lod]\ntile_size = 4097\ntiles = [64, 64]\n");
  EXPECT_NE(big.find("x.toml:3:9: 'lod.tiles' = [64, 64] x 'lod.tile_size' = 4097"), std::string::npos) << big;
  EXPECT_NE(big.find("at most 16777216"), std::string::npos) << big;
  EXPECT_NE(error_of("[lod]\ntile_size = 4097\n").find("x.toml:2:13: 'lod.tiles' = [2, 2] x 'lod.tile_size'"),
            std::string::npos);
  EXPECT_NO_THROW(parse_lod_experiment("[lod]\ntile_size = 1025\ntiles = [3, 3]\n", "x.toml"));  // 3073^2
  EXPECT_NO_THROW(parse_lod_experiment("[lod]\ntile_size = 257\ntiles = [16, 15]\n", "x.toml"));   // 4097 x 3841
  EXPECT_THROW(parse_lod_experiment("[lod]\ntile_size = 257\ntiles = [16, 16]\n", "x.toml"),
               util::UserError);  // 4097^2
  const LodSettings s = parse_lod_experiment("[lod]\ntau = [2]\nlambda = \"planar\"\ntiles = [3, 1]\n", "dir/e.toml");
  EXPECT_EQ(s.name, "e");
  EXPECT_EQ(s.lambda, LambdaKind::kPlanar);
  EXPECT_EQ(s.tiles_x, 3);
  ASSERT_EQ(s.check_lambdas.size(), 2u);  // default: the two others
  EXPECT_EQ(s.camera.width, 1024);
}

TEST(HeightFile, NonFiniteHeightsAndSmallFilesAreRejected) {
  const std::string dir = ::testing::TempDir() + "lod_height_file";
  std::filesystem::create_directories(dir);
  HeightField f;
  f.nx = f.ny = 5;
  f.spacing = 1;
  f.z.assign(25, 1.0);
  f.source = "small.tif";
  EXPECT_THROW(crop_to_tiles(f, 9, 0, 0), util::UserError);
  const HeightField c = crop_to_tiles(f, 3, 1, 0);
  EXPECT_EQ(c.nx, 3);
  EXPECT_EQ(c.ny, 5);
  EXPECT_NE(c.source.find("cropped from 5 x 5 to 3 x 5"), std::string::npos);
  EXPECT_THROW(read_height_file(dir + "/missing.tif", 1, 1), util::UserError);
}

TEST(LodStudy, SmokeExperimentRunsAnalysesAndPlots) {
  const std::string dir = ::testing::TempDir() + "lod_smoke_study";
  std::filesystem::remove_all(dir);
  rundir::StudyRunOptions o;
  o.experiment = std::string(RA_SOURCE_DIR) + "/experiments/lod_smoke.toml";
  o.out_dir = dir;
  o.progress = false;
  const rundir::StudyRunResult r = run_lod_study(o);
  EXPECT_FALSE(r.findings) << r.summary;
  EXPECT_NE(r.summary.find("every check passed"), std::string::npos) << r.summary;
  EXPECT_THROW(plot_lod_study(dir), util::UserError);  // not analysed yet
  analyze_lod_study(dir);
  const std::optional<rundir::StudyInfo> info = rundir::read_study_info(dir);
  ASSERT_TRUE(info);
  EXPECT_EQ(info->kind, rundir::StudyKind::kLod);
  EXPECT_TRUE(info->analysed);
  EXPECT_EQ(info->document, "lod.md");
  // the table: window lambda at tau 4 is below full resolution, every check passed
  const std::string table_text = util::read_file(dir + "/lod_table.csv");
  std::istringstream table(table_text);
  std::string line;
  std::getline(table, line);
  int window_rows = 0;
  while (std::getline(table, line)) {
    std::vector<std::string> c;
    std::istringstream cells(line);
    for (std::string x; std::getline(cells, x, ',');) c.push_back(x);
    ASSERT_GE(c.size(), 17u);
    if (c[0] != "window") continue;
    ++window_rows;
    EXPECT_EQ(c[2], "6");                          // frames
    EXPECT_EQ(c[14], "6");                         // frames conforming
    EXPECT_EQ(c[15], "6");                         // seams ok
    EXPECT_EQ(c[16], "0");                         // frames over tau
    EXPECT_LE(std::stod(c[12]), std::stod(c[1]));  // max screen error <= tau
    EXPECT_GT(std::stod(c[7]), 0);                 // timed
    if (c[1] == "4") {
      EXPECT_LT(std::stod(c[3]), 0.5 * std::stod(c[9]));  // triangles < half of full
    }
  }
  EXPECT_EQ(window_rows, 2);
  const std::string md = util::read_file(dir + "/lod.md");
  EXPECT_NE(md.find("# Terrain level of detail"), std::string::npos);
  EXPECT_NE(md.find("### At tau = 1 pixel"), std::string::npos);
  plot_lod_study(dir);
  EXPECT_TRUE(std::filesystem::exists(dir + "/figures/index.json"));
  plots::testing::expect_drawn_png(dir + "/figures/lod_speed_vs_error.png");
  plots::testing::expect_whole_pdf(dir + "/figures/lod_screen_error_vs_tau.pdf");
  {  // the figure draws numbers: at least one row per tau of the window lambda after its header
    std::ifstream csv(dir + "/figures/lod_triangles_vs_tau.csv");
    std::string row;
    int data_rows = -1;  // the header
    while (std::getline(csv, row))
      if (!row.empty() && row[0] != '#') ++data_rows;
    EXPECT_GE(data_rows, window_rows) << "lod_triangles_vs_tau.csv";
  }
  // a re-run removes what analyze and plot derived, and plot refuses until analyze runs again
  {
    const rundir::StudyRunResult again = run_lod_study(o);
    EXPECT_FALSE(again.findings) << again.summary;
    for (const char* f : {"lod_table.csv", "lod.md", "figures"})
      EXPECT_FALSE(std::filesystem::exists(dir + "/" + f)) << f;
    const std::optional<rundir::StudyInfo> rerun = rundir::read_study_info(dir);
    ASSERT_TRUE(rerun);
    EXPECT_FALSE(rerun->analysed);
    // even with a (stale) table present, plot checks study.json's flag
    util::write_file_atomic(dir + "/lod_table.csv", table_text);
    try {
      plot_lod_study(dir);
      ADD_FAILURE() << "plot_lod_study accepted a folder that was not analysed";
    } catch (const util::UserError& e) {
      EXPECT_NE(std::string(e.what()).find("has not been analysed"), std::string::npos) << e.what();
    }
  }
  // an incomplete folder is refused
  std::filesystem::remove(dir + "/frames.csv");
  EXPECT_THROW(analyze_lod_study(dir), util::UserError);
  EXPECT_THROW(analyze_lod_study(dir + "/nonexistent"), util::UserError);
}

TEST(LodStudy, BrokenErrorPropagationIsAFinding) {
  const std::string dir = ::testing::TempDir() + "lod_broken_study";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  std::string text = util::read_file(std::string(RA_SOURCE_DIR) + "/experiments/lod_smoke.toml");
  // the same experiment with the broken LOD
  text.replace(text.find("[lod]"), 5, "[lod]\nerror_propagation = \"unnested\"");
  util::write_file_atomic(dir + "/broken.toml", text);
  rundir::StudyRunOptions o;
  o.experiment = dir + "/broken.toml";
  o.out_dir = dir + "/out";
  o.progress = false;
  const rundir::StudyRunResult r = run_lod_study(o);
  EXPECT_TRUE(r.findings) << r.summary;
  EXPECT_NE(r.summary.find("failed a check"), std::string::npos) << r.summary;
}

}  // namespace
}  // namespace ra::lod

namespace ra::lod {
namespace {

// The default study, for measuring by hand (minutes): run with
//   RA_LOD_OUT=DIR terrain_lod_tests --gtest_also_run_disabled_tests --gtest_filter=*DISABLED_Default*
TEST(LodStudy, DISABLED_DefaultExperiment) {
  const char* out = std::getenv("RA_LOD_OUT");
  rundir::StudyRunOptions o;
  o.experiment = std::string(RA_SOURCE_DIR) + "/experiments/lod.toml";
  o.out_dir = out ? out : ::testing::TempDir() + "lod_default";
  const rundir::StudyRunResult r = run_lod_study(o);
  std::cerr << r.summary << "\n";
  EXPECT_FALSE(r.findings);
  analyze_lod_study(o.out_dir);
  plot_lod_study(o.out_dir);
}

}  // namespace
}  // namespace ra::lod
