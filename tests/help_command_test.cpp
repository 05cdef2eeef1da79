// How `--help` reads (app/help_format.h): lines of at most 100 columns, a short top help, option
// placeholders without CLI11's type and check, `renderaudit help COMMAND`, and a mistyped option
// or experiment key named with the nearest one.
#include <gtest/gtest.h>

#include <sstream>

#include "app/help_format.h"
#include "tests/cli_harness.h"

using namespace ra::testing_cli;

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

// The commands the top help lists.
std::vector<std::string> commands() {
  std::vector<std::string> out;
  bool in_list = false;
  for (const std::string& line : lines_of(run_renderaudit("--help").output)) {
    if (line == "Commands:") in_list = true;
    else if (in_list && line.rfind("  ", 0) == 0) out.push_back(line.substr(2, line.find(' ', 2) - 2));
    else if (in_list) in_list = false;
  }
  return out;
}

TEST(Help, TheTopHelpIsOneShortLinePerCommand) {
  const Outcome o = run_renderaudit("--help");
  ASSERT_EQ(o.exit_code, 0);
  const std::vector<std::string> lines = lines_of(o.output);
  EXPECT_LT(lines.size(), 40u) << o.output;
  for (const std::string& line : lines) EXPECT_LE(line.size(), 100u) << line;
  const std::vector<std::string> names = commands();
  EXPECT_GE(names.size(), 18u) << o.output;
  for (const char* name : {"run", "audit", "bisect", "watch", "records", "conformance"})
    EXPECT_NE(std::find(names.begin(), names.end(), name), names.end()) << name;
  EXPECT_NE(o.output.find("renderaudit COMMAND --help"), std::string::npos) << o.output;
}

TEST(Help, EveryCommandsHelpFitsOneHundredColumnsWithoutTypeNoise) {
  for (const std::string& c : commands()) {
    const Outcome o = run_renderaudit(c + " --help");
    EXPECT_EQ(o.exit_code, 0) << c;
    EXPECT_EQ(o.output.rfind("Usage: renderaudit " + c, 0), 0u) << o.output;
    for (const std::string& line : lines_of(o.output)) EXPECT_LE(line.size(), 100u) << c << ": " << line;
    for (const char* noise : {"INT:", "UINT", "FLOAT", " in [", "(1x)", "=2000", "default: "})
      EXPECT_EQ(o.output.find(noise), std::string::npos) << c << " says '" << noise << "':\n" << o.output;
  }
  // One placeholder for a count wherever it is: `--jobs N` (an int in run, unsigned in bisect).
  EXPECT_NE(run_renderaudit("run --help").output.find("--jobs N "), std::string::npos);
  EXPECT_NE(run_renderaudit("bisect --help").output.find("--jobs N "), std::string::npos);
  EXPECT_NE(run_renderaudit("bisect --help").output.find("(default 2000)"), std::string::npos);
}

TEST(Help, HelpCommandIsTheCommandsHelp) {
  const Outcome help = run_renderaudit("help records");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_EQ(help.output, run_renderaudit("records --help").output);
  EXPECT_EQ(run_renderaudit("help").output, run_renderaudit("--help").output);
  const Outcome typo = run_renderaudit("help recrods");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_NE(typo.output.find("did you mean 'records'?"), std::string::npos) << typo.output;
}

TEST(Help, AMistypedOptionIsNamedWithTheNearestOne) {
  // Why: `--ouT` got no suggestion, and `--speed-repeat 3` was read as a run folder named 3.
  const Outcome out = run_renderaudit("run experiments/quick.toml --ouT x");
  EXPECT_EQ(out.exit_code, 2);
  EXPECT_NE(out.output.find("renderaudit run: unknown option '--ouT'; did you mean '--out'?"),
            std::string::npos)
      << out.output;
  const Outcome rep = run_renderaudit("audit --speed-repeat 3 a b");
  EXPECT_EQ(rep.exit_code, 2);
  EXPECT_NE(rep.output.find("did you mean '--speed-repeats'?"), std::string::npos) << rep.output;
  // An option of a command under the command (`builds build --ref`) is known.
  EXPECT_EQ(run_renderaudit("builds build --ref").output.find("unknown option"), std::string::npos);
}

TEST(Help, AMistypedExperimentKeyIsNamedWithTheNearestOne) {
  const std::string dir = fresh_dir("help_typo_key");
  write_text(dir + "/typo.toml",
             "name = \"typo\"\nseed = 1\nplatforms = [\"reference\"]\n[views]\norientatons = 2\n"
             "fov_deg = [30]\nwindows = [128]\nnear = 0.01\nfar = 10.0\n[primitives]\npoints = 5\n"
             "lines = 3\ntriangles = 2\n");
  const Outcome o = run_renderaudit("run " + dir + "/typo.toml --out " + dir + "/run");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.output.find(dir + "/typo.toml:5:1: unknown key 'views.orientatons'; did you mean "
                                "'orientations'?"),
            std::string::npos)
      << o.output;
}

TEST(HelpFormat, WrapsLongLinesAtSpacesAndKeepsItsOwnBreaks) {
  EXPECT_EQ(ra::app::wrap_text("aaa bbb ccc", 7), "aaa bbb\nccc");
  EXPECT_EQ(ra::app::wrap_text("aaa bbb ccc", 7, 2), "aaa bbb\n  ccc");
  EXPECT_EQ(ra::app::wrap_text("ab\ncd ef gh", 5), "ab\ncd ef\ngh");
  EXPECT_EQ(ra::app::wrap_text("averyveryverylongword x", 5), "averyveryverylongword\nx");
  EXPECT_EQ(ra::app::wrap_text("", 5), "");
}

TEST(HelpFormat, ACommandsSummaryIsItsFirstSentenceCutToFit) {
  EXPECT_EQ(ra::app::command_summary("Render it. Then more.", 80), "Render it");
  EXPECT_EQ(ra::app::command_summary("Name one, e.g. this. More", 80), "Name one, e.g. this");
  EXPECT_EQ(ra::app::command_summary("Stats of columns: t, F and Levene tests. More", 20),
            "Stats of columns");
  EXPECT_EQ(ra::app::command_summary("Compare a run (the current one) with its baseline, or two", 45),
            "Compare a run with its baseline, or two");
  EXPECT_EQ(ra::app::command_summary("Compare a run with its baseline, or two", 33),
            "Compare a run with its baseline");
}

}  // namespace
