// The upgrade summary is written and read by one module: what is written reads back as it was,
// optional keys included, so the sentences said from the file are those said from memory.
#include "report/upgrade_summary.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "report/upgrade_sentences.h"

namespace ra::report {
namespace {

namespace fs = std::filesystem;

// Why: a timed pair with an unknown group (NaN ratios, null in the file) and an untimed pair
// without `speed` must both survive the file.
TEST(UpgradeSummary, WhatIsWrittenReadsBackAsItWas) {
  UpgradeSummary s;
  s.run_dir = "/runs/upgrade";
  s.build = "backports";
  s.groups = {{"A", 30, 128}, {"B", 150, 907}};
  UpgradePair timed{"osmesa-llvmpipe", "osmesa-llvmpipe@backports", "Mesa 22.3.6", "Mesa 25.0.7",
                    "00c0ffee00c0ffee", {}, true, {}};
  timed.strata.push_back({"line", "A", 100, 9, 3, 1, 4, 1, 2, 2});
  timed.strata.push_back({"triangle", "B", 50, 0, 0, 0, 0, 0, 0, 0});
  timed.speed.push_back({"line", "A", 1.3, 1.2, 1.4, "slower"});
  timed.speed.push_back({"triangle", "B", NAN, NAN, NAN, "unknown"});
  UpgradePair plain{"egl-softpipe", "egl-softpipe@backports", "Mesa 22.3.6", "Mesa 25.0.7",
                    "0000000000000000", {}, false, {}};
  plain.strata.push_back({"point", "A", 10, 0, 0, 0, 0, 0, 0, 0});
  s.pairs = {timed, plain};

  const fs::path path = fs::temp_directory_path() / "renderaudit_upgrade_summary.json";
  write_upgrade_summary(s, path.string());
  const UpgradeSummary r = read_upgrade_summary(path.string());
  fs::remove(path);
  EXPECT_EQ(upgrade_summary_json(r), upgrade_summary_json(s));
  ASSERT_EQ(r.pairs.size(), 2u);
  EXPECT_TRUE(r.pairs[0].timed);
  EXPECT_TRUE(std::isnan(r.pairs[0].speed[1].ratio));
  EXPECT_EQ(r.pairs[0].strata[0].not_drawn_violations, 2);
  EXPECT_FALSE(r.pairs[1].timed);
  EXPECT_EQ(upgrade_sentences(r), upgrade_sentences(s));
}

}  // namespace
}  // namespace ra::report
