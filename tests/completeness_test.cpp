// Every lit pixel is accounted for: a pixel that GL lights far from the primitive (outside the
// region the runner reads back first) must still be found, through the occlusion-query proof and
// the full-window fallback, and must change the case's classification.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <tuple>

#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "tests/cli_harness.h"

using namespace ra::testing_cli;

namespace {

using Key = std::tuple<std::string, int, uint64_t>;  // kind, view, index

std::map<Key, ra::metrics::Record> load(const std::string& run_dir) {
  std::map<Key, ra::metrics::Record> out;
  for (const auto& e : std::filesystem::directory_iterator(run_dir + "/records"))
    ra::rundir::read_records(e.path().string(), [&](const ra::metrics::Record& r) {
      out[{r.kind, r.view, r.index}] = r;
    });
  return out;
}

TEST(Completeness, AWildPixelFarFromThePrimitiveIsFoundAndClassified) {
  const std::string dir = fresh_dir("wild");
  const std::string views =
      "seed = 5\n[views]\norientations = 1\nfov_deg = [150]\nwindows = [96]\nnear = 0.01\n"
      "far = 10.0\n[primitives]\npoints = 60\nlines = 60\ntriangles = 60\n";
  write_text(dir + "/clean.toml", "platforms = [\"osmesa-llvmpipe\"]\n" + views);
  write_text(dir + "/wild.toml", "platforms = [\"faulty\"]\n" + views +
                                     "[faults]\nbase = \"osmesa-llvmpipe\"\n"
                                     "wild_pixel = [3, 7, 11, 19, 23, 42]\n");
  ASSERT_EQ(run_renderaudit("run " + dir + "/clean.toml --out " + dir + "/clean").exit_code, 0);
  const Outcome o = run_renderaudit("run " + dir + "/wild.toml --out " + dir + "/wild");
  ASSERT_EQ(o.exit_code, 0) << o.output;

  const auto clean = load(dir + "/clean"), wild = load(dir + "/wild");
  ASSERT_EQ(clean.size(), 180u);
  ASSERT_EQ(wild.size(), 180u);
  const std::set<uint64_t> planted = {3, 7, 11, 19, 23, 42};
  int checked_points = 0;
  for (const auto& [key, c] : clean) {
    const ra::metrics::Record& w = wild.at(key);
    const bool is_wild = planted.count(std::get<2>(key));
    if (!is_wild) {
      EXPECT_EQ(w.pixels, c.pixels);
      EXPECT_EQ(w.pixel_hash, c.pixel_hash);
      continue;
    }
    if (c.pixels == int64_t(c.width) * c.height) continue;  // a full-window triangle: no room
    // One more lit pixel, found although it lies outside the region read back first.
    EXPECT_EQ(w.pixels, c.pixels + 1) << std::get<0>(key) << " " << std::get<2>(key);
    EXPECT_NE(w.pixel_hash, c.pixel_hash);
    EXPECT_GE(w.ref_diff, c.ref_diff + 1);
    if (std::get<0>(key) == "point") {
      ++checked_points;
      // A visible point now lights two pixels; an invisible one lights a pixel it should not.
      if (c.visibility == ra::metrics::Visibility::kTrueVisible) {
        EXPECT_EQ(w.visibility, ra::metrics::Visibility::kMultipleVisible);
      }
      if (c.visibility == ra::metrics::Visibility::kTrueInvisible) {
        EXPECT_EQ(w.visibility, ra::metrics::Visibility::kFalseVisible);
      }
    }
    if (std::get<0>(key) != "point" && c.visibility == ra::metrics::Visibility::kTrueInvisible) {
      EXPECT_EQ(w.visibility, ra::metrics::Visibility::kFalseVisible);
    }
  }
  EXPECT_EQ(checked_points, 6);
}

}  // namespace
