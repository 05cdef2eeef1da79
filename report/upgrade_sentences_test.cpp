// The driver upgrade's first sentence says what changed in words, from the counts alone: a
// report whose page 1 was a table titled "Table" with "new violations 799" hid that llvmpipe no
// longer drew some lines. Each test feeds a hand-built summary and asserts the whole sentence.
#include "report/upgrade_sentences.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "util/errors.h"

namespace ra::report {
namespace {

namespace fs = std::filesystem;

// The four view groups of the NIST audit: FOV 30 and 150 degrees, 128 and 907 pixels.
std::vector<UpgradeViewGroup> nist_groups() {
  return {{"A", 30, 128}, {"B", 150, 128}, {"C", 30, 907}, {"D", 150, 907}};
}

// 10,000 primitives of each kind per group, nothing changed.
UpgradePair unchanged_pair(const std::string& platform) {
  UpgradePair p;
  p.platform = platform;
  p.build_platform = platform + "@backports";
  p.installed_version = "4.5 (Compatibility Profile) Mesa 22.3.6";
  p.build_version = "4.5 (Compatibility Profile) Mesa 25.0.7 (git-1234)";
  p.fingerprint = "none";
  for (const char* kind : {"point", "line", "triangle"})
    for (const char* g : {"A", "B", "C", "D"}) {
      UpgradeStratum s;
      s.kind = kind, s.group = g, s.compared = 10000, s.not_drawn_violations = 0;
      p.strata.push_back(s);
    }
  return p;
}

UpgradeStratum& stratum(UpgradePair& p, const std::string& kind, const std::string& group) {
  for (UpgradeStratum& s : p.strata)
    if (s.kind == kind && s.group == group) return s;
  throw std::runtime_error("no stratum " + kind + " " + group);
}

// llvmpipe's upgrade: lines of group C not drawn and breaking the rules, triangles snapped
// otherwise in groups A and C.
UpgradePair llvmpipe_pair(const std::string& platform) {
  UpgradePair p = unchanged_pair(platform);
  p.fingerprint = "9f1c";
  UpgradeStratum& lines = stratum(p, "line", "C");
  lines.changed = 900, lines.not_drawn = 595, lines.new_violations = 799, lines.allowed = 101;
  lines.not_drawn_violations = 595;
  stratum(p, "triangle", "A").changed = stratum(p, "triangle", "A").allowed = 300;
  stratum(p, "triangle", "C").changed = stratum(p, "triangle", "C").allowed = 910;
  return p;
}

UpgradeSummary summary(std::vector<UpgradePair> pairs) {
  UpgradeSummary s;
  s.run_dir = "/nonexistent/run";
  s.build = "backports";
  s.groups = nist_groups();
  s.pairs = std::move(pairs);
  return s;
}

// Why: the same finding through two back ends is one finding; saying it twice doubled the
// report's pictures and hid that the back end does not matter.
TEST(UpgradeSentences, OneFindingIdenticalThroughOSMesaAndEGL) {
  const UpgradeSummary s =
      summary({llvmpipe_pair("osmesa-llvmpipe"), unchanged_pair("osmesa-softpipe"),
               llvmpipe_pair("egl-llvmpipe"), unchanged_pair("egl-softpipe")});
  EXPECT_EQ(upgrade_sentences(s),
            "llvmpipe 25.0.7 stops drawing 595 of 10,000 lines of the FOV-30 907 x 907 views; "
            "799 lines break GL's line rules, 595 of them not drawn at all; 101 other lines light "
            "other pixels, as GL allows; "
            "1,210 of 40,000 triangles light other pixels, as GL allows (identical through "
            "OSMesa and EGL); softpipe unchanged.");
}

// Why: a driver with no change is said in one word, not left out (absent reads as not audited).
TEST(UpgradeSentences, ADriverWithNoChangeIsUnchanged) {
  EXPECT_EQ(upgrade_sentences(summary({unchanged_pair("osmesa-softpipe"),
                                      unchanged_pair("egl-softpipe")})),
            "softpipe unchanged.");
  EXPECT_EQ(upgrade_sentences(summary({})), "no platform was audited.");
}

// Lines not drawn in both 907 x 907 groups are "of the 907 x 907 views"; a rule broken by one
// line is singular; with no line not drawn the driver's part starts with a colon.
TEST(UpgradeSentences, ViewsAreNamedByWhatTheyShare) {
  UpgradePair p = llvmpipe_pair("osmesa-llvmpipe");
  stratum(p, "line", "D").changed = stratum(p, "line", "D").not_drawn = 5;
  stratum(p, "line", "D").new_violations = stratum(p, "line", "D").not_drawn_violations = 5;
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "llvmpipe 25.0.7 stops drawing 600 of 20,000 lines of the 907 x 907 views; 804 lines "
            "break GL's line rules, 600 of them not drawn at all; 101 other lines light other "
            "pixels, as GL allows; 1,210 of 40,000 triangles light other pixels, as GL allows.");
  UpgradePair one = unchanged_pair("egl-llvmpipe");
  one.fingerprint = "1";
  stratum(one, "point", "B").changed = stratum(one, "point", "B").new_violations = 1;
  EXPECT_EQ(upgrade_sentences(summary({one})), "llvmpipe 25.0.7: 1 point breaks GL's point rules.");
}

// Back ends that differ are said one by one.
TEST(UpgradeSentences, BackEndsThatDifferAreSaidApart) {
  UpgradePair egl = unchanged_pair("egl-llvmpipe");
  egl.fingerprint = "2";
  stratum(egl, "triangle", "D").changed = stratum(egl, "triangle", "D").allowed = 7;
  EXPECT_EQ(upgrade_sentences(summary({llvmpipe_pair("osmesa-llvmpipe"), egl})),
            "llvmpipe 25.0.7 through OSMesa stops drawing 595 of 10,000 lines of the FOV-30 907 x "
            "907 views; 799 lines break GL's line rules, 595 of them not drawn at all; 101 other "
            "lines light other pixels, as GL allows; 1,210 of 40,000 triangles light other "
            "pixels, as GL allows; llvmpipe 25.0.7 through EGL: 7 of 40,000 triangles light other "
            "pixels, as GL allows.");
}

// Why: page 1 said "stops drawing 53 of 2,000 lines ...; 75 lines break GL's line rules; ...; 1
// more line change where GL's rules were not judged or already broken", and only a table pages
// later showed that 52 of the 53 are among the 75. The sentence says how the counts nest: the
// lines breaking the rules, how many of them not drawn; the one not drawn that breaks no new rule
// among the "more".
TEST(UpgradeSentences, TheCountsSayHowTheyNest) {
  UpgradePair p = unchanged_pair("osmesa-llvmpipe");
  p.fingerprint = "3";
  UpgradeStratum& c = stratum(p, "line", "C");
  c.compared = 2000, c.changed = 333, c.not_drawn = 53, c.new_violations = 75;
  c.not_drawn_violations = 52, c.allowed = 257;
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "llvmpipe 25.0.7 stops drawing 53 of 2,000 lines of the FOV-30 907 x 907 views; 75 "
            "lines break GL's line rules, 52 of them not drawn at all; 257 other lines light "
            "other pixels, as GL allows; 1 more line changes where GL's rules were not judged or "
            "already broken (not drawn).");
  // every line breaking the rules not drawn; the more of several kinds
  c.changed = 340, c.not_drawn = 75, c.not_drawn_violations = 75;
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "llvmpipe 25.0.7 stops drawing 75 of 2,000 lines of the FOV-30 907 x 907 views; 75 "
            "lines break GL's line rules, all 75 not drawn at all; 257 other lines light other "
            "pixels, as GL allows; 8 more lines change where GL's rules were not judged or "
            "already broken.");
  c.not_drawn = 78;  // 3 of the 8 more not drawn
  const std::string more = upgrade_sentences(summary({p}));
  EXPECT_EQ(more.substr(more.find("8 more")),
            "8 more lines change where GL's rules were not judged or already broken (3 of them "
            "not drawn).");
  // none of those breaking the rules among the not drawn; one line of each
  c.changed = 13, c.not_drawn = 12, c.new_violations = 1, c.not_drawn_violations = 0;
  c.allowed = 0;
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "llvmpipe 25.0.7 stops drawing 12 of 2,000 lines of the FOV-30 907 x 907 views; 1 "
            "line breaks GL's line rules, none of them among the 12 not drawn; 12 more lines "
            "change where GL's rules were not judged or already broken (all not drawn).");
  c.changed = 1, c.not_drawn = 1, c.not_drawn_violations = 1;
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "llvmpipe 25.0.7 stops drawing 1 of 2,000 lines of the FOV-30 907 x 907 views; 1 line "
            "breaks GL's line rules, not drawn at all.");
  // a summary written before the overlap was kept: the counts without it
  for (UpgradeStratum& s : p.strata) s.not_drawn_violations = -1;
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "llvmpipe 25.0.7 stops drawing 1 of 2,000 lines of the FOV-30 907 x 907 views; 1 line "
            "breaks GL's line rules.");
}

// Every kind in every group judged the same: ratio 1 within +-2%.
void time_all_same(UpgradePair& p) {
  p.timed = true;
  for (const char* kind : {"point", "line", "triangle"})
    for (const char* g : {"A", "B", "C", "D"})
      p.speed.push_back({kind, g, 1.0, 0.98, 1.02, "same"});
}

UpgradeTime& time_of(UpgradePair& p, const std::string& kind, const std::string& group) {
  for (UpgradeTime& t : p.speed)
    if (t.kind == kind && t.group == group) return t;
  throw std::runtime_error("no time " + kind + " " + group);
}

// The sentence on drawing time, after the one on pixels (the sentences of the summary without
// its drawing times, which must open it).
std::string time_sentence(UpgradeSummary s) {
  const std::string all = upgrade_sentences(s);
  for (UpgradePair& p : s.pairs) p.timed = false, p.speed.clear();
  const std::string pixels = upgrade_sentences(s);
  EXPECT_EQ(all.substr(0, pixels.size() + 1), pixels + " ") << all;
  return all.size() > pixels.size() ? all.substr(pixels.size() + 1) : "";
}

// Why: page 1 said what the upgrade did to pixels and nothing of time, though the audits had
// judged it. A faster and a slower group are said in words with their percentages (faster: 1 -
// ratio, its interval from 1 - high to 1 - low; slower: ratio - 1), the rest in one clause; the
// same verdicts through OSMesa and EGL are said once, with both back ends' numbers held.
TEST(UpgradeSentences, FasterAndSlowerGroupsAreSaidInWords) {
  UpgradePair osmesa = llvmpipe_pair("osmesa-llvmpipe"), egl = llvmpipe_pair("egl-llvmpipe");
  UpgradePair softpipe = unchanged_pair("osmesa-softpipe");
  for (UpgradePair* p : {&osmesa, &egl, &softpipe}) time_all_same(*p);
  time_of(osmesa, "line", "C") = {"line", "C", 1.16, 1.09, 1.24, "slower"};
  time_of(osmesa, "triangle", "D") = {"triangle", "D", 0.78, 0.75, 0.80, "faster"};
  time_of(egl, "line", "C") = {"line", "C", 1.16, 1.093, 1.238, "slower"};
  time_of(egl, "triangle", "D") = {"triangle", "D", 0.79, 0.76, 0.81, "faster"};
  EXPECT_EQ(upgrade_sentences(summary({osmesa, softpipe, egl})),
            "llvmpipe 25.0.7 stops drawing 595 of 10,000 lines of the FOV-30 907 x 907 views; "
            "799 lines break GL's line rules, 595 of them not drawn at all; 101 other lines light "
            "other pixels, as GL allows; "
            "1,210 of 40,000 triangles light other pixels, as GL allows (identical through "
            "OSMesa and EGL); softpipe unchanged. llvmpipe 25.0.7 through OSMesa and EGL draws "
            "the lines of the FOV-30 907 x 907 views 16% slower (95%: 9-24%) and the triangles "
            "of the FOV-150 907 x 907 views 21-22% faster (95%: 19-25%); other drawing times "
            "unchanged or not measurably different.");

  // One pair alone: its own numbers, no back end named.
  UpgradePair one = unchanged_pair("egl-llvmpipe");
  time_all_same(one);
  time_of(one, "triangle", "D") = {"triangle", "D", 0.78, 0.75, 0.80, "faster"};
  EXPECT_EQ(upgrade_sentences(summary({one})),
            "llvmpipe unchanged. llvmpipe 25.0.7 draws the triangles of the FOV-150 907 x 907 "
            "views 22% faster (95%: 20-25%); other drawing times unchanged or not measurably "
            "different.");
  // Groups of one kind and verdict are one clause, named by what their views share, with the
  // range of their estimates: lines slower in every group, triangles faster in both 907 x 907.
  time_of(one, "triangle", "C") = {"triangle", "C", 0.80, 0.78, 0.82, "faster"};
  for (const char* g : {"A", "B", "C", "D"})
    time_of(one, "line", g) = {"line", g, 1.10, 1.06, 1.15, "slower"};
  EXPECT_EQ(time_sentence(summary({one})),
            "llvmpipe 25.0.7 draws the lines 10% slower (95%: 6-15%) and the triangles of the 907 "
            "x 907 views 20-22% faster (95%: 18-25%); other drawing times unchanged or not "
            "measurably different.");
  // Every group said: no "other".
  for (const char* kind : {"point", "triangle"})
    for (const char* g : {"A", "B", "C", "D"})
      time_of(one, kind, g) = {kind, g, 1.10, 1.06, 1.15, "slower"};
  EXPECT_EQ(time_sentence(summary({one})),
            "llvmpipe 25.0.7 draws the points 10% slower (95%: 6-15%), the lines 10% slower (95%: "
            "6-15%) and the triangles 10% slower (95%: 6-15%).");

  // Back ends whose verdicts differ are said one by one, each named.
  time_of(egl, "triangle", "D").verdict = "same";
  EXPECT_EQ(time_sentence(summary({osmesa, egl})),
            "llvmpipe 25.0.7 through OSMesa draws the lines of the FOV-30 907 x 907 views 16% "
            "slower (95%: 9-24%) and the triangles of the FOV-150 907 x 907 views 22% faster "
            "(95%: 20-25%); llvmpipe 25.0.7 through EGL draws the lines of the FOV-30 907 x 907 "
            "views 16% slower (95%: 9-24%); other drawing times unchanged or not measurably "
            "different.");
}

// Why: a group the audit could not judge is neither unchanged nor changed; one short clause
// counts them, and only where there are any.
TEST(UpgradeSentences, UnknownDrawingTimesAreCountedInOneClause) {
  UpgradePair p = unchanged_pair("osmesa-softpipe");
  p.timed = true;
  p.speed = {{"line", "A", NAN, NAN, NAN, "unknown"}, {"line", "B", 1.04, 0.9, 1.2, "unknown"}};
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "softpipe unchanged. The drawing time of 2 groups could not be judged at this noise.");
  p.speed.push_back({"line", "C", 1.0, 0.99, 1.01, "same"});
  EXPECT_EQ(upgrade_sentences(summary({p})),
            "softpipe unchanged. Drawing times unchanged or not measurably different; the drawing "
            "time of 2 groups could not be judged at this noise.");
}

TEST(UpgradeSentences, MesaVersionFromGlVersion) {
  EXPECT_EQ(mesa_version("4.5 (Compatibility Profile) Mesa 25.0.7 (git-abc)"), "25.0.7");
  EXPECT_EQ(mesa_version("4.5 (Compatibility Profile) Mesa 26.0.0-devel"), "26.0.0-devel");
  EXPECT_EQ(mesa_version("4.5 (Compatibility Profile) Mesa 25.0.7-2~bpo12+1"), "25.0.7");
  EXPECT_EQ(mesa_version("4.6.0 NVIDIA 550.54"), "");
}

// Why: where a bisection of the run named its culprits, page 1 names them, with the number of
// primitives each changed; the summary is read back from the file the script writes.
TEST(UpgradeSentences, ABisectionBesideTheRunNamesItsCulprits) {
  const fs::path dir = fs::temp_directory_path() / ("ra_upgrade_sentences_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "run");
  fs::create_directories(dir / "bisect");
  const std::string run = (dir / "run").string();
  std::ofstream(dir / "bisect" / "bisect.json")
      << R"({"schema": "renderaudit-bisection", "schema_version": 2, "complete": true,
            "inputs": {"run": ")" << run << R"(", "platform": "egl-llvmpipe"},
            "selection": [{}, {}, {}],
            "culprits": [{"commit": "a07fa6516b0123456789012345678901234567ab",
                          "subject": "llvmpipe/linear: add support for rgba color buffers",
                          "date": "2025-03-04T10:00:00+01:00",
                          "primitives": [{"primitive": "line 1 of view 5", "pixels_before": 9,
                                          "pixels_after": 0},
                                         {"primitive": "line 2 of view 5", "pixels_before": 7,
                                          "pixels_after": 0}]}]})";
  std::ofstream(dir / "upgrade-summary.json")
      << R"({"schema": "renderaudit-upgrade-summary", "schema_version": 1, "run": ")" << run
      << R"(", "build": "backports", "groups": [{"label": "A", "fov_deg": 30, "window": 128}],
            "pairs": [{"platform": "egl-softpipe", "build_platform": "egl-softpipe@backports",
                       "installed_version": "Mesa 22.3.6", "build_version": "Mesa 25.0.7",
                       "fingerprint": "", "strata": [{"kind": "line", "group": "A",
                       "compared": 4, "changed": 0, "not_drawn": 0, "newly_drawn": 0,
                       "new_violations": 0, "fixed_violations": 0, "allowed": 0}]}]})";
  const UpgradeSummary s = read_upgrade_summary((dir / "upgrade-summary.json").string());
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_EQ(s.pairs[0].strata[0].compared, 4);
  EXPECT_EQ(upgrade_sentences_markdown(s),
            "**softpipe unchanged.**\n\nBisection of egl-llvmpipe (`" +
                (dir / "bisect" / "bisect.json").string() +
                "`, 3 primitives): first bad commit `a07fa6516b01` \"llvmpipe/linear: add support "
                "for rgba color buffers\" (2 primitives).\n");
  fs::remove_all(dir);
}

// The message `read_upgrade_summary` (or the bisection it reads) stops with; "" when it reads.
std::string summary_error(const fs::path& dir, const std::string& strata,
                          const std::string& culprit_commit = "\"" + std::string(40, 'a') + "\"") {
  fs::remove_all(dir);
  fs::create_directories(dir / "run" / "bisect");
  const std::string run = (dir / "run").string();
  std::ofstream(dir / "run" / "bisect" / "bisect.json")
      << R"({"schema": "renderaudit-bisection", "schema_version": 2, "complete": true,
            "inputs": {"run": ")" << run << R"(", "platform": "egl-llvmpipe"}, "selection": [{}],
            "culprits": [{"commit": )" << culprit_commit << R"(, "subject": "s", "date": "d",
                          "primitives": [{"primitive": "line 1 of view 1", "pixels_before": 3,
                                          "pixels_after": 0}]}]})";
  std::ofstream(dir / "upgrade-summary.json")
      << R"({"schema": "renderaudit-upgrade-summary", "schema_version": 1, "run": ")" << run
      << R"(", "build": "backports", "groups": [{"label": "A", "fov_deg": 30, "window": 128}],
            "pairs": [{"platform": "egl-llvmpipe", "build_platform": "egl-llvmpipe@backports",
                       "installed_version": "Mesa 22.3.6", "build_version": "Mesa 25.0.7",
                       "fingerprint": "f", "strata": )" << strata << "}]}";
  try {
    upgrade_sentences_markdown(read_upgrade_summary((dir / "upgrade-summary.json").string()));
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

std::string a_stratum(const std::string& compared, const std::string& changed,
                      const std::string& not_drawn) {
  return R"([{"kind": "line", "group": "A", "compared": )" + compared + R"(, "changed": )" +
         changed + R"(, "not_drawn": )" + not_drawn +
         R"(, "newly_drawn": 0, "new_violations": 0, "fixed_violations": 0, "allowed": 0}])";
}

// Why: a number where a commit belongs ended in a bare "[json.exception.type_error.302]"; "stops
// drawing 1,000 of 100 lines" passed with exit 0; counts near 2^63 overflowed and the clause
// vanished.
TEST(UpgradeSentences, ADamagedSummaryOrBisectionIsNamedWithItsFileAndKey) {
  const fs::path dir =
      fs::temp_directory_path() / ("ra_upgrade_sentences_bad_" + std::to_string(getpid()));
  const std::string bisect_json = (dir / "run" / "bisect" / "bisect.json").string();
  const std::string summary_json = (dir / "upgrade-summary.json").string();
  EXPECT_EQ(summary_error(dir, a_stratum("100", "10", "5")), "");

  std::string e = summary_error(dir, a_stratum("100", "10", "5"), "7");
  EXPECT_NE(e.find(bisect_json + ": 'culprits[0].commit' must be a string"), std::string::npos) << e;
  EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
  e = summary_error(dir, a_stratum("100", "10", "5"), "\"--output=x\"");
  EXPECT_NE(e.find(bisect_json + ": 'culprits[0].commit' must be a full commit hash"),
            std::string::npos)
      << e;

  e = summary_error(dir, a_stratum("100", "100", "1000"));
  EXPECT_NE(e.find(summary_json + ": 'pairs[0].strata[0].not_drawn' (1000)"), std::string::npos) << e;
  EXPECT_NE(e.find("the counts do not add up"), std::string::npos) << e;
  e = summary_error(dir, a_stratum("100", "1000", "0"));
  EXPECT_NE(e.find("'pairs[0].strata[0].changed' (1000) is more than 'compared' (100)"),
            std::string::npos)
      << e;

  const std::string near = std::to_string(INT64_MAX - 1);
  // two strata of 2^63 - 2 lines each: their sum would wrap
  const std::string one = a_stratum(near, near, near);
  e = summary_error(dir, one.substr(0, one.size() - 1) + ", " + one.substr(1));
  EXPECT_NE(e.find("'pairs[0].strata[0].compared' (" + near + ") takes the summary past 2^62"),
            std::string::npos)
      << e;
  fs::remove_all(dir);
}

// A stratum's not_drawn_violations is read where the summary has it, and must be of both its not
// drawn and its new violations.
TEST(UpgradeSentences, TheOverlapOfNotDrawnAndRulesBrokenIsReadAndChecked) {
  const fs::path dir =
      fs::temp_directory_path() / ("ra_upgrade_sentences_overlap_" + std::to_string(getpid()));
  const auto with = [](const std::string& overlap) {
    return R"([{"kind": "line", "group": "A", "compared": 100, "changed": 10, "not_drawn": 6,
                "newly_drawn": 0, "new_violations": 8, "fixed_violations": 0, "allowed": 0,
                "not_drawn_violations": )" + overlap + "}]";
  };
  EXPECT_EQ(summary_error(dir, with("5")), "");
  UpgradeSummary s = read_upgrade_summary((dir / "upgrade-summary.json").string());
  EXPECT_EQ(s.pairs[0].strata[0].not_drawn_violations, 5);
  EXPECT_EQ(upgrade_sentences(s),
            "llvmpipe 25.0.7 stops drawing 6 of 100 lines; 8 lines break GL's line rules, 5 of "
            "them not drawn at all; 2 more lines change where GL's rules were not judged or "
            "already broken (1 of them not drawn).");
  // without the key: not said
  EXPECT_EQ(summary_error(dir, a_stratum("100", "10", "5")), "");
  s = read_upgrade_summary((dir / "upgrade-summary.json").string());
  EXPECT_EQ(s.pairs[0].strata[0].not_drawn_violations, -1);
  // more than its not drawn; leaving more not drawn than the changes not otherwise counted
  for (const std::string bad : {"7", "3"}) {
    const std::string e = summary_error(dir, with(bad));
    EXPECT_NE(e.find("'pairs[0].strata[0].not_drawn_violations' (" + bad + ")"),
              std::string::npos)
        << e;
    EXPECT_NE(e.find("the counts do not add up"), std::string::npos) << e;
  }
  fs::remove_all(dir);
}

// Why: summaries written before drawing times were kept (no `speed`) still read, and say
// nothing of time; a summary with `speed` reads each field, null where no interval was formed.
TEST(UpgradeSentences, DrawingTimesAreReadFromTheSummaryAndOptional) {
  const fs::path dir =
      fs::temp_directory_path() / ("ra_upgrade_sentences_speed_" + std::to_string(getpid()));
  const std::string stratum = a_stratum("100", "0", "0");
  EXPECT_EQ(summary_error(dir, stratum), "");
  UpgradeSummary s = read_upgrade_summary((dir / "upgrade-summary.json").string());
  ASSERT_EQ(s.pairs.size(), 1u);
  EXPECT_FALSE(s.pairs[0].timed);
  EXPECT_EQ(upgrade_sentences(s), "llvmpipe unchanged.");

  EXPECT_EQ(summary_error(dir, stratum + R"(, "speed": [
      {"kind": "line", "group": "A", "ratio": 1.3, "low": 1.2, "high": 1.4, "verdict": "slower"},
      {"kind": "point", "group": "A", "ratio": null, "low": null, "high": null,
       "verdict": "unknown"}])"),
            "");
  s = read_upgrade_summary((dir / "upgrade-summary.json").string());
  ASSERT_TRUE(s.pairs[0].timed);
  ASSERT_EQ(s.pairs[0].speed.size(), 2u);
  EXPECT_DOUBLE_EQ(s.pairs[0].speed[0].low, 1.2);
  EXPECT_TRUE(std::isnan(s.pairs[0].speed[1].ratio));
  EXPECT_EQ(upgrade_sentences(s),
            "llvmpipe unchanged. llvmpipe 25.0.7 draws the lines 30% slower (95%: 20-40%); the "
            "drawing time of 1 group could not be judged at this noise.");
  fs::remove_all(dir);
}

// Why: a mistyped drawing time must stop with the file and the key, as every other field does,
// not end in a JSON library message or a sentence that says "-3% faster".
TEST(UpgradeSentences, AMistypedDrawingTimeIsNamedWithItsFileAndKey) {
  const fs::path dir =
      fs::temp_directory_path() / ("ra_upgrade_sentences_speed_bad_" + std::to_string(getpid()));
  const std::string summary_json = (dir / "upgrade-summary.json").string();
  const std::string stratum = a_stratum("100", "0", "0");
  const auto error_of = [&](const std::string& speed) {
    return summary_error(dir, stratum + R"(, "speed": )" + speed);
  };
  const auto group = [](const std::string& ratio, const std::string& low, const std::string& high,
                        const std::string& verdict) {
    return R"([{"kind": "line", "group": "A", "ratio": )" + ratio + R"(, "low": )" + low +
           R"(, "high": )" + high + R"(, "verdict": ")" + verdict + R"("}])";
  };
  EXPECT_EQ(error_of(group("0.8", "0.7", "0.9", "faster")), "");

  std::string e = error_of(R"("fast")");
  EXPECT_EQ(e, summary_json + ": 'pairs[0].speed' must be a list");
  e = error_of(group(R"("0.8")", "0.7", "0.9", "faster"));
  EXPECT_NE(e.find(summary_json + ": 'pairs[0].speed[0].ratio' must be a number above 0"),
            std::string::npos)
      << e;
  EXPECT_EQ(e.find("json.exception"), std::string::npos) << e;
  e = error_of(group("0.8", "-0.7", "0.9", "faster"));
  EXPECT_NE(e.find(summary_json + ": 'pairs[0].speed[0].low' must be a number above 0"),
            std::string::npos)
      << e;
  e = error_of(group("0.8", "0.7", "0.9", "quicker"));
  EXPECT_NE(e.find(summary_json + ": 'pairs[0].speed[0].verdict' is 'quicker' (allowed: faster, "
                                  "slower, same, unknown)"),
            std::string::npos)
      << e;
  e = error_of(R"([{"kind": "line", "group": "A", "ratio": 1, "low": 1, "high": 1}])");
  EXPECT_NE(e.find(summary_json + ": 'pairs[0].speed[0].verdict' is missing"), std::string::npos)
      << e;
  // a faster group whose interval reaches 1, a slower one without numbers: no words for them
  e = error_of(group("0.97", "0.9", "1.03", "faster"));
  EXPECT_NE(e.find(summary_json + ": 'pairs[0].speed[0].high' (1.030000) must be below 1 for a "
                                  "'faster' verdict"),
            std::string::npos)
      << e;
  e = error_of(group("null", "null", "null", "slower"));
  EXPECT_NE(e.find(summary_json + ": 'pairs[0].speed[0].ratio', 'low' and 'high' must be numbers "
                                  "for a 'slower' verdict"),
            std::string::npos)
      << e;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace ra::report
