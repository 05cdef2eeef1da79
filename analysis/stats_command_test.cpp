// Tests of `renderaudit stats`: in process (the subcommand on a fresh CLI11 app, stdout captured)
// and end to end through the built binary (RA_BINARY). The JSON must carry exactly the library's
// numbers, undefined statistics as null with a reason, and bad input must stop with a located
// message.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "analysis/box_cox.h"
#include "analysis/descriptive.h"
#include "analysis/hypothesis_tests.h"
#include "analysis/stats_testing.h"
#include "app/commands.h"
#include "runner/errors.h"

namespace ra::stats {
namespace {

using nlohmann::json;

// Runs `stats ARGS...` in process and returns what it printed.
std::string run_stats(std::vector<std::string> args) {
  CLI::App app;
  app.require_subcommand(1);
  int exit_code = -1;
  ra::app::register_stats_command(app, exit_code);
  args.insert(args.begin(), "stats");
  std::reverse(args.begin(), args.end());  // CLI11 takes the arguments last first
  std::ostringstream captured;
  std::streambuf* previous = std::cout.rdbuf(captured.rdbuf());
  try {
    app.parse(args);
  } catch (...) {
    std::cout.rdbuf(previous);
    throw;
  }
  std::cout.rdbuf(previous);
  EXPECT_EQ(exit_code, ra::app::kExitOk);
  return captured.str();
}

std::string write_csv(const std::filesystem::path& dir, const std::string& name,
                      const std::string& header, const std::vector<std::string>& rows) {
  const auto path = (dir / name).string();
  std::ofstream out(path);
  out << header << "\n";
  for (const auto& r : rows) out << r << "\n";
  return path;
}

std::string column_csv(const std::filesystem::path& dir, const std::string& name,
                       const std::vector<double>& values) {
  std::vector<std::string> rows;
  char buf[64];
  for (double v : values) {
    std::snprintf(buf, sizeof buf, "%.17g", v);
    rows.push_back(std::string("id,") + buf);
  }
  return write_csv(dir, name, "label,error_px", rows);
}

class StatsCommand : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::temp_dir("cmd"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(StatsCommand, DescribeJsonCarriesTheLibraryNumbers) {
  const auto x = testing::lognormal_sample(501, 0, 1, 81);
  const std::string file = column_csv(dir_, "a.csv", x);
  const json j = json::parse(run_stats({"describe", file, "--column", "error_px", "--json"}));
  const Description d = describe(x);
  EXPECT_EQ(j["schema_version"], 1);
  EXPECT_EQ(j["quantile_definition"], "hyndman_fan_6");
  EXPECT_EQ(j["n_missing"], 0);
  const json& jd = j["description"];
  EXPECT_EQ(jd["n"], d.n);
  // exact equality: the JSON numbers read back to the same doubles
  EXPECT_EQ(jd["mean"].get<double>(), d.mean);
  EXPECT_EQ(jd["sd"].get<double>(), d.sd);
  EXPECT_EQ(jd["median"].get<double>(), d.median);
  EXPECT_EQ(jd["q1"].get<double>(), d.q1);
  EXPECT_EQ(jd["q3"].get<double>(), d.q3);
  EXPECT_EQ(jd["iqr"].get<double>(), d.iqr);
  EXPECT_EQ(jd["min"].get<double>(), d.min);
  EXPECT_EQ(jd["max"].get<double>(), d.max);
  const json j7 = json::parse(
      run_stats({"describe", file, "--column", "error_px", "--json", "--quantiles", "hf7"}));
  EXPECT_EQ(j7["description"]["q1"].get<double>(),
            describe(x, QuantileDefinition::kHyndmanFan7).q1);
  const std::string text = run_stats({"describe", file, "--column", "error_px"});
  EXPECT_NE(text.find("median"), std::string::npos) << text;
  EXPECT_NE(text.find("hyndman_fan_6"), std::string::npos) << text;
}

TEST_F(StatsCommand, CompareJson) {
  const auto a = testing::lognormal_sample(300, 0, 0.5, 82);
  const auto b = testing::lognormal_sample(200, 0.05, 0.6, 83);
  const json j = json::parse(run_stats({"compare", column_csv(dir_, "a.csv", a),
                                        column_csv(dir_, "b.csv", b), "-c", "error_px", "--json"}));
  EXPECT_EQ(j["a"]["description"]["mean"].get<double>(), describe(a).mean);
  EXPECT_EQ(j["b"]["description"]["n"], 200);
  const TTestResult tp = t_test_pooled(a, b);
  EXPECT_EQ(j["t_test_pooled"]["statistic"].get<double>(), tp.statistic);
  EXPECT_EQ(j["t_test_pooled"]["pooled_sd"].get<double>(), *tp.pooled_sd);
  EXPECT_EQ(j["t_test_welch"]["df"].get<double>(), t_test_welch(a, b).df);
  EXPECT_FALSE(j["t_test_welch"].contains("pooled_sd"));
  EXPECT_EQ(j["f_test"]["p_value"].get<double>(), f_test_variances(a, b).p_value);
  EXPECT_EQ(j["levene"]["median"]["statistic"].get<double>(),
            levene_test({a, b}, LeveneCenter::kMedian).statistic);
  EXPECT_EQ(j["levene"]["trimmed_mean"]["df2"].get<double>(), 498);
  EXPECT_TRUE(j["levene"]["mean"].contains("p_value"));
  EXPECT_EQ(j["box_cox"]["a"]["mle"]["lambda"].get<double>(),
            box_cox_lambda(a, BoxCoxMethod::kMle).lambda);
  EXPECT_EQ(j["box_cox"]["b"]["ppcc"]["lambda"].get<double>(),
            box_cox_lambda(b, BoxCoxMethod::kPpcc).lambda);
  EXPECT_TRUE(j["box_cox"]["b"]["ppcc"].contains("correlation"));
  const std::string text = run_stats({"compare", dir_ / "a.csv", dir_ / "b.csv", "-c", "error_px"});
  EXPECT_NE(text.find("Welch"), std::string::npos) << text;
  EXPECT_NE(text.find("Levene (trimmed_mean centre)"), std::string::npos) << text;
}

// Two constant samples: every test is undefined; the JSON says null and why, never NaN.
TEST_F(StatsCommand, UndefinedStatisticsAreNullWithAReason) {
  const std::string a = column_csv(dir_, "a.csv", {2, 2, 2});
  const std::string b = column_csv(dir_, "b.csv", {2, 2, 2, 2});
  const std::string out = run_stats({"compare", a, b, "--column", "error_px", "--json"});
  EXPECT_EQ(out.find("NaN"), std::string::npos) << out;
  const json j = json::parse(out);
  EXPECT_TRUE(j["t_test_pooled"]["statistic"].is_null());
  EXPECT_TRUE(j["t_test_pooled"]["p_value"].is_null());
  EXPECT_NE(j["t_test_pooled"]["reason"].get<std::string>().find("constant"), std::string::npos);
  EXPECT_TRUE(j["f_test"]["statistic"].is_null());
  EXPECT_TRUE(j["levene"]["median"]["statistic"].is_null());
  EXPECT_FALSE(j["box_cox"]["a"]["ppcc"]["applicable"].get<bool>());
  EXPECT_TRUE(j["box_cox"]["a"]["ppcc"]["lambda"].is_null());
  EXPECT_FALSE(j["box_cox"]["a"]["mle"]["reason"].get<std::string>().empty());
  EXPECT_EQ(j["a"]["description"]["sd"].get<double>(), 0);
  const std::string text = run_stats({"compare", a, b, "--column", "error_px"});
  EXPECT_NE(text.find("undefined (pooled t test: both samples are constant"), std::string::npos)
      << text;
}

// The ANOVA of StRD SmLs01 written as CSV: the command reproduces the certified F.
TEST_F(StatsCommand, AnovaOfStrdData) {
  const auto c = testing::read_strd_anova("SMLS01.dat");
  std::vector<std::string> rows;
  for (std::size_t g = 0; g < c.groups.size(); ++g) {
    for (double v : c.groups[g])
      rows.push_back("\"treatment " + std::to_string(g + 1) + "\"," + std::to_string(v) + ",");
  }
  rows.push_back(",1.5,");              // no group: skipped
  rows.push_back("\"treatment 1\",,");  // no value: skipped
  const std::string file = write_csv(dir_, "smls01.csv", "treatment,response,note", rows);
  const json j = json::parse(
      run_stats({"anova", file, "--group", "treatment", "--value", "response", "--json"}));
  EXPECT_EQ(j["n_missing"], 2);
  ASSERT_EQ(j["groups"].size(), 9u);
  EXPECT_EQ(j["groups"][0]["name"], "treatment 1");
  EXPECT_EQ(j["anova"]["df_between"].get<double>(), c.df_between);
  EXPECT_EQ(j["anova"]["df_within"].get<double>(), c.df_within);
  EXPECT_GE(testing::lre(j["anova"]["f"].get<double>(), c.f), 9);
  EXPECT_GE(testing::lre(j["anova"]["ss_within"].get<double>(), c.ss_within), 9);
  EXPECT_TRUE(j["levene"].contains("median"));
  const std::string text =
      run_stats({"anova", file, "--group", "treatment", "--value", "response"});
  EXPECT_NE(text.find("between"), std::string::npos) << text;
}

TEST_F(StatsCommand, BadInputIsALocatedUserError) {
  const std::string good = column_csv(dir_, "good.csv", {1, 2, 3});
  const std::string one = column_csv(dir_, "one.csv", {1});
  const std::string bad = write_csv(dir_, "bad.csv", "label,error_px", {"a,1", "b,zz"});
  auto message = [](std::vector<std::string> args) -> std::string {
    try {
      run_stats(std::move(args));
    } catch (const UserError& e) {
      return e.what();
    }
    return "(no UserError)";
  };
  const std::string missing = (dir_ / "missing.csv").string();
  EXPECT_NE(message({"describe", missing, "--column", "x"}).find(missing), std::string::npos);
  const std::string unknown = message({"describe", good, "--column", "err"});
  EXPECT_NE(unknown.find("no column named 'err' (available: label, error_px)"), std::string::npos)
      << unknown;
  const std::string cell = message({"describe", bad, "--column", "error_px"});
  EXPECT_NE(cell.find(bad + ":3: column 'error_px': 'zz'"), std::string::npos) << cell;
  const std::string few = message({"compare", good, one, "--column", "error_px"});
  EXPECT_NE(few.find(one + ": column 'error_px' has 1 value(s)"), std::string::npos) << few;
  const std::string groups = message({"anova", good, "--group", "label", "--value", "error_px"});
  EXPECT_NE(groups.find("1 group(s)"), std::string::npos) << groups;
}

// The built program: `renderaudit stats describe --json` prints the library's numbers and exits 0;
// an unknown column exits 2 with the located message on stderr.
TEST_F(StatsCommand, EndToEndThroughTheBinary) {
  const auto x = testing::exponential_sample(99, 2, 84);
  const std::string file = column_csv(dir_, "a.csv", x);
  const std::string out_path = (dir_ / "out.json").string();
  const std::string err_path = (dir_ / "err.txt").string();
  const std::string binary = RA_BINARY;
  const std::string run = "'" + binary + "' stats describe '" + file +
                          "' --column error_px --json > '" + out_path + "' 2> '" + err_path + "'";
  const int status = std::system(run.c_str());
  std::ifstream err_in(err_path);
  const std::string err((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(WEXITSTATUS(status), 0)
      << "`renderaudit stats` failed (is register_stats_command called in app/main.cpp?): " << err;
  std::ifstream out_in(out_path);
  const json j = json::parse(out_in);
  EXPECT_EQ(j["description"]["sd"].get<double>(), describe(x).sd);

  const std::string bad = "'" + binary + "' stats describe '" + file + "' --column nope > '" +
                          out_path + "' 2> '" + err_path + "'";
  const int bad_status = std::system(bad.c_str());
  EXPECT_EQ(WEXITSTATUS(bad_status), ra::app::kExitUsage);
  std::ifstream err2(err_path);
  const std::string bad_err((std::istreambuf_iterator<char>(err2)),
                            std::istreambuf_iterator<char>());
  EXPECT_NE(bad_err.find("no column named 'nope'"), std::string::npos) << bad_err;
}

}  // namespace
}  // namespace ra::stats
