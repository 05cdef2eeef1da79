// Tests of `renderaudit stats`: in process (the subcommand on a fresh CLI11 app, stdout captured)
// and end to end through the built binary (RA_BINARY). The JSON must carry exactly the library's
// numbers, undefined statistics as null with a reason, and bad input must stop with a located
// message.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "stats/box_cox.h"
#include "stats/descriptive.h"
#include "stats/hypothesis_tests.h"
#include "stats/linear_regression.h"
#include "stats/stats_testing.h"
#include "app/commands.h"
#include "util/child_process.h"
#include "util/errors.h"
#include "util/zstd_stream.h"

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

// Data near the ends of the double range: every command answers with finite numbers or says that a
// value (an sd or a sum of squares above 1.8e308) is out of range; never NaN, inf or an internal
// error (values 1e200 once gave sd 0 and "every group is constant").
TEST_F(StatsCommand, ExtremeMagnitudesNeverPrintNaNOrInf) {
  const std::string groups = write_csv(
      dir_, "g.csv", "group,y,x",
      {"a,1e200,1", "a,2e200,2", "a,1.5e200,3", "b,3e200,4", "b,3.5e200,5", "b,2.75e200,6",
       "c,1e-170,7", "c,2e-170,8", "c,3e-170,9"});
  const std::string huge = column_csv(dir_, "h.csv", {1.7e308, -1.7e308, 1.6e308, 1.0e308});
  const std::vector<std::vector<std::string>> commands = {
      {"describe", huge, "--column", "error_px"},
      {"describe", huge, "--column", "error_px", "--json"},
      {"describe", groups, "--column", "y"},
      {"anova", groups, "--value", "y", "--group", "group"},
      {"anova", groups, "--value", "y", "--group", "group", "--json"},
      {"regress", groups, "--y", "y", "--x", "x"},
      {"regress", groups, "--y", "y", "--x", "x", "--json"}};
  for (const auto& c : commands) {
    const std::string out = run_stats(c);
    std::string lower = out;
    for (char& ch : lower) ch = char(std::tolower(static_cast<unsigned char>(ch)));
    EXPECT_EQ(lower.find("nan"), std::string::npos) << c[0] << ":\n" << out;
    EXPECT_EQ(lower.find(" inf"), std::string::npos) << c[0] << ":\n" << out;
    EXPECT_EQ(lower.find("internal error"), std::string::npos) << c[0] << ":\n" << out;
    EXPECT_EQ(lower.find("constant"), std::string::npos) << c[0] << ":\n" << out;
  }
  const json d = json::parse(run_stats({"describe", huge, "--column", "error_px", "--json"}));
  // deviations from the mean 0.65e308: 1.05, -2.35, 0.95, 0.35 (e308); ss = 7.65, var = 2.55
  EXPECT_NEAR(d["description"]["sd"].get<double>() / 1e308, std::sqrt(2.55), 1e-15);
  // q3 - q1 = 1.675e308 - (-1.025e308) = 2.7e308: beyond the largest double
  EXPECT_EQ(d["description"]["iqr"], "out of double range (|x| > 1.8e308)");
  EXPECT_DOUBLE_EQ(d["description"]["median"].get<double>(), 1.3e308);
}

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
    } catch (const util::UserError& e) {
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

std::string format17(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// StRD Norris written as CSV (columns in another order than the file's, plus a text column):
// `regress --json` carries exactly the library's fit, which reproduces the certified values.
TEST_F(StatsCommand, RegressNorrisJson) {
  const auto rows = testing::strd_data_rows(testing::read_lines(testing::strd_path("Norris.dat")));
  ASSERT_EQ(rows.size(), 36u);
  std::vector<double> x, y;
  std::vector<std::string> lines;
  for (const auto& r : rows) {
    y.push_back(r.at(0));
    x.push_back(r.at(1));
    lines.push_back("ozone," + format17(r.at(1)) + "," + format17(r.at(0)));
  }
  const std::string file = write_csv(dir_, "norris.csv", "label,x,y", lines);
  const json j = json::parse(run_stats({"regress", file, "--y", "y", "--x", "x", "--json"}));
  EXPECT_EQ(j["schema_version"], 1);
  EXPECT_EQ(j["command"], "stats regress");
  EXPECT_EQ(j["file"], file);
  EXPECT_EQ(j["y_column"], "y");
  EXPECT_EQ(j["x_columns"], json::array({"x"}));
  EXPECT_EQ(j["intercept"], true);
  EXPECT_EQ(j["method"], "householder_qr_double");
  EXPECT_NEAR(j["condition_number"].get<double>(), 2.8, 0.05);  // NumPy: 2.8
  EXPECT_EQ(j["n"], 36);
  EXPECT_EQ(j["n_missing"], 0);
  EXPECT_EQ(j["df"], 34);
  EXPECT_EQ(j["rank"], 2);
  EXPECT_EQ(j["r_squared_definition"], "centred");
  const LinearFit fit = fit_least_squares({x}, y, true, {"x"});
  const json& c = j["coefficients"];
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0]["name"], "(intercept)");
  EXPECT_EQ(c[1]["name"], "x");
  for (std::size_t k = 0; k < 2; ++k) {
    // exact equality: the JSON numbers read back to the same doubles
    EXPECT_EQ(c[k]["estimate"].get<double>(), fit.coefficients[k]);
    EXPECT_EQ(c[k]["sd"].get<double>(), fit.standard_deviations[k]);
    EXPECT_EQ(c[k]["t_value"].get<double>(), coefficient_t_test(fit, k).t);
    EXPECT_EQ(c[k]["p_value"].get<double>(), coefficient_t_test(fit, k).p_value);
  }
  EXPECT_EQ(j["residual_sd"].get<double>(), fit.residual_sd);
  EXPECT_EQ(j["rss"].get<double>(), fit.rss);
  EXPECT_EQ(j["r_squared"].get<double>(), *fit.r_squared);
  // certified values, Norris.dat lines 31-37 (all of them: linear_regression_test.cpp)
  EXPECT_GE(testing::lre(c[0]["estimate"].get<double>(), -0.262323073774029), 9);
  EXPECT_GE(testing::lre(c[1]["estimate"].get<double>(), 1.00211681802045), 9);
  EXPECT_GE(testing::lre(c[1]["sd"].get<double>(), 0.429796848199937E-03), 9);
  EXPECT_GE(testing::lre(j["residual_sd"].get<double>(), 0.884796396144373), 9);
  EXPECT_GE(testing::lre(j["r_squared"].get<double>(), 0.999993745883712), 9);

  const std::string text = run_stats({"regress", file, "--y", "y", "--x", "x"});
  EXPECT_NE(text.find("(intercept)"), std::string::npos) << text;
  EXPECT_NE(text.find("residual SD = 0.8847963961 on 34 degrees of freedom"), std::string::npos)
      << text;
  EXPECT_NE(text.find("R-squared = 0.9999937459 (centred)"), std::string::npos) << text;
}

// `regress --poly x:2` with x near 1e300 (the x^2 coefficient near 1e-601) or near 1e-300 (near
// 1e+600): refused with the reason, never printed as 0 with "the fit is exact", never a raw
// message from the t distribution.
TEST_F(StatsCommand, RegressPolynomialAtTheEndsOfTheDoubleRangeIsRefused) {
  const double noise[] = {0.31, -0.42, 0.05, 0.38, -0.27, -0.11, 0.46, -0.35, 0.02, -0.07};
  for (const char* magnitude : {"e300", "e-300"}) {
    std::vector<std::string> rows;
    for (int i = 0; i < 10; ++i)
      rows.push_back("1." + std::to_string(i) + magnitude + "," + format17(1 + i + noise[i]));
    const std::string file = write_csv(dir_, std::string("x") + magnitude + ".csv", "x,y", rows);
    std::string message = "(no error)";
    try {
      run_stats({"regress", file, "--y", "y", "--poly", "x:2"});
    } catch (const util::UserError& e) {
      message = e.what();
    }
    EXPECT_NE(message.find(file + ": 'y' on an intercept and a polynomial of degree 2 in 'x'"),
              std::string::npos) << message;
    EXPECT_NE(message.find("outside the range of double precision"), std::string::npos) << message;
    EXPECT_EQ(message.find("exact"), std::string::npos) << message;
  }
}

// StRD Filip (y on a degree-10 polynomial in x, condition number 5e9) through `--poly x:10`:
// every certified value to LRE >= 13, exactly the library's fit_polynomial(), and the text names
// the method and the condition number. Bad --poly specifications are refused.
TEST_F(StatsCommand, RegressPolynomialFilip) {
  const auto lines = testing::read_lines(testing::strd_path("Filip.dat"));
  const auto rows = testing::strd_data_rows(lines);
  ASSERT_EQ(rows.size(), 82u);
  std::vector<double> x, y;
  std::vector<std::string> csv;
  for (const auto& r : rows) {
    y.push_back(r.at(0));
    x.push_back(r.at(1));
    csv.push_back(format17(r.at(1)) + "," + format17(r.at(0)));
  }
  const std::string file = write_csv(dir_, "filip.csv", "x,y", csv);
  const json j = json::parse(run_stats({"regress", file, "--y", "y", "--poly", "x:10", "--json"}));
  EXPECT_EQ(j["method"], "householder_qr_binary128");
  EXPECT_EQ(j["polynomial_degree"], 10);
  EXPECT_EQ(j["x_columns"], json::array({"x"}));
  EXPECT_EQ(j["rank"], 11);
  EXPECT_NEAR(std::log10(j["condition_number"].get<double>()), std::log10(5.21e9), 0.01);
  const LinearFit fit = fit_polynomial(x, y, 10, true, "x");
  const json& c = j["coefficients"];
  ASSERT_EQ(c.size(), 11u);
  EXPECT_EQ(c[10]["name"], "x^10");
  // certified values, Filip.dat lines 31-43
  const double b[] = {-1467.48961422980, -2772.17959193342, -2316.37108160893,
                      -1127.97394098372, -354.478233703349, -75.1242017393757,
                      -10.8753180355343, -1.06221498588947, -0.670191154593408E-01,
                      -0.246781078275479E-02, -0.402962525080404E-04};
  const double sd[] = {298.084530995537,  559.779865474950,       466.477572127796,
                       227.204274477751,  71.6478660875927,       15.2897178747400,
                       2.23691159816033,  0.221624321934227,      0.142363763154724E-01,
                       0.535617408889821E-03, 0.896632837373868E-05};
  for (std::size_t k = 0; k < 11; ++k) {
    EXPECT_EQ(c[k]["estimate"].get<double>(), fit.coefficients[k]);
    EXPECT_EQ(c[k]["sd"].get<double>(), fit.standard_deviations[k]);
    EXPECT_GE(testing::lre(c[k]["estimate"].get<double>(), b[k]), 13) << k;
    EXPECT_GE(testing::lre(c[k]["sd"].get<double>(), sd[k]), 13) << k;
  }
  EXPECT_GE(testing::lre(j["residual_sd"].get<double>(), 0.334801051324544E-02), 13);
  EXPECT_GE(testing::lre(j["r_squared"].get<double>(), 0.996727416185620), 13);

  const std::string text = run_stats({"regress", file, "--y", "y", "--poly", "x:10"});
  EXPECT_NE(text.find("'y' on an intercept and a polynomial of degree 10 in 'x'; 82 rows"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("Householder QR in binary128 (quad) precision"), std::string::npos) << text;
  EXPECT_NE(text.find("condition number of the column-scaled design 5.21e+09"), std::string::npos)
      << text;
  EXPECT_NE(text.find("x^10"), std::string::npos) << text;

  const auto message = [](const std::vector<std::string>& args) {
    try {
      run_stats(args);
    } catch (const std::exception& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  for (const char* bad : {"x", "x:", ":3", "x:0", "x:31", "x:2.5", "x:ten"}) {
    const std::string m = message({"regress", file, "--y", "y", "--poly", bad});
    EXPECT_NE(m.find(file + ": --poly '" + bad + "' is not COLUMN:DEGREE"), std::string::npos)
        << m;
    EXPECT_NE(m.find("a degree from 1 to 30"), std::string::npos) << m;
  }
  EXPECT_NE(message({"regress", file, "--y", "y"}).find("--x COLUMN[,COLUMN...] or a polynomial"),
            std::string::npos);
  EXPECT_NE(message({"regress", file, "--y", "y", "--poly", "z:2"}).find("no column named 'z'"),
            std::string::npos);
  EXPECT_NE(message({"regress", file, "--y", "y", "--poly", "y:2"}).find("is both the response"),
            std::string::npos);
  // --x and --poly exclude each other (CLI11)
  EXPECT_NE(message({"regress", file, "--y", "y", "--x", "x", "--poly", "x:2"}).find("excludes"),
            std::string::npos);
}

// Two predictors given as a comma list or as repeated --x, no intercept, and a row with an empty
// cell (skipped and counted): the uncentred R-squared of the library.
TEST_F(StatsCommand, RegressNoInterceptSkipsIncompleteRows) {
  const std::string file =
      write_csv(dir_, "timing.csv", "polys,pixels,ms",
                {"1000,50000,2.531", "2500,120000,6.174", "4000,30000,8.362", "5200,,12.385",
                 "7000,90000,14.853", "8800,160000,19.247", "10000,60000,20.588"});
  const json j = json::parse(
      run_stats({"regress", file, "--y", "ms", "--x", "polys,pixels", "--no-intercept", "--json"}));
  const LinearFit fit = fit_least_squares(
      {{1000, 2500, 4000, 7000, 8800, 10000}, {50000, 120000, 30000, 90000, 160000, 60000}},
      {2.531, 6.174, 8.362, 14.853, 19.247, 20.588}, false, {"polys", "pixels"});
  EXPECT_EQ(j["intercept"], false);
  EXPECT_EQ(j["n"], 6);
  EXPECT_EQ(j["n_missing"], 1);
  EXPECT_EQ(j["df"], 4);
  EXPECT_EQ(j["r_squared_definition"], "uncentred");
  ASSERT_EQ(j["coefficients"].size(), 2u);
  EXPECT_EQ(j["coefficients"][0]["name"], "polys");
  EXPECT_EQ(j["coefficients"][1]["estimate"].get<double>(), fit.coefficients[1]);
  EXPECT_EQ(j["coefficients"][0]["sd"].get<double>(), fit.standard_deviations[0]);
  EXPECT_EQ(j["r_squared"].get<double>(), *fit.r_squared);
  const json repeated = json::parse(run_stats(
      {"regress", file, "--y", "ms", "--x", "polys", "--x", "pixels", "--no-intercept", "--json"}));
  EXPECT_EQ(repeated["coefficients"], j["coefficients"]);
  const std::string text =
      run_stats({"regress", file, "--y", "ms", "--x", "polys,pixels", "--no-intercept"});
  EXPECT_NE(text.find("'ms' on 'polys', 'pixels'; 6 rows (1 skipped: empty cells)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("(uncentred)"), std::string::npos) << text;
}

// An exact fit: t undefined, written as null with the reason; never NaN.
TEST_F(StatsCommand, RegressExactFitHasNullT) {
  const std::string file = write_csv(dir_, "exact.csv", "x,y", {"1,3", "2,5", "3,7", "4,9"});
  const std::string out = run_stats({"regress", file, "--y", "y", "--x", "x", "--json"});
  EXPECT_EQ(out.find("NaN"), std::string::npos) << out;
  const json j = json::parse(out);
  // y = 1 + 2x is exact in binary: the residuals, and with them every SD, are exactly 0
  EXPECT_EQ(j["residual_sd"].get<double>(), 0);
  EXPECT_TRUE(j["coefficients"][1]["t_value"].is_null());
  EXPECT_TRUE(j["coefficients"][1]["p_value"].is_null());
  EXPECT_NE(j["coefficients"][1]["reason"].get<std::string>().find("the fit is exact"),
            std::string::npos);
  const std::string constant = write_csv(dir_, "constant.csv", "x,y", {"1,3", "2,3", "3,3", "4,3"});
  const json jc = json::parse(run_stats({"regress", constant, "--y", "y", "--x", "x", "--json"}));
  EXPECT_TRUE(jc["r_squared"].is_null());
  EXPECT_NE(jc["r_squared_reason"].get<std::string>().find("y is constant"), std::string::npos);
}

TEST_F(StatsCommand, RegressBadInputIsALocatedUserError) {
  const std::string file =
      write_csv(dir_, "t.csv", "polys,verts,fov,ms",
                {"100,300,60,1.1", "250,750,60,2.4", "400,1200,60,3.9", "520,1560,60,5.3"});
  auto message = [](std::vector<std::string> args) -> std::string {
    try {
      run_stats(std::move(args));
    } catch (const util::UserError& e) {
      return e.what();
    }
    return "(no UserError)";
  };
  const std::string unknown = message({"regress", file, "--y", "ms", "--x", "polys,pixels"});
  EXPECT_NE(unknown.find(file + ":1: no column named 'pixels' (available: polys, verts, fov, ms)"),
            std::string::npos)
      << unknown;
  const std::string unknown_y = message({"regress", file, "--y", "time", "--x", "polys"});
  EXPECT_NE(unknown_y.find("no column named 'time'"), std::string::npos) << unknown_y;
  const std::string both = message({"regress", file, "--y", "ms", "--x", "polys,ms"});
  EXPECT_NE(both.find(file + ": column 'ms' is both the response (--y) and a predictor (--x or "
                      "--poly)"),
            std::string::npos)
      << both;
  const std::string twice = message({"regress", file, "--y", "ms", "--x", "polys,polys"});
  EXPECT_NE(twice.find("names column 'polys' twice"), std::string::npos) << twice;
  // 3 vertices per polygon: proportional columns
  const std::string rank = message({"regress", file, "--y", "ms", "--x", "polys,verts"});
  EXPECT_NE(rank.find(file + ": 'ms' on an intercept and 2 predictor(s), 4 complete row(s)"),
            std::string::npos)
      << rank;
  EXPECT_NE(rank.find("rank 2 for 3 parameters"), std::string::npos) << rank;
  // a constant column duplicates the intercept; without an intercept it is fine
  EXPECT_NE(message({"regress", file, "--y", "ms", "--x", "polys,fov"}).find("rank 2"),
            std::string::npos);
  EXPECT_NO_THROW(run_stats({"regress", file, "--y", "ms", "--x", "polys,fov", "--no-intercept"}));
  const std::string few = message({"regress", file, "--y", "ms", "--x", "polys,verts,fov"});
  EXPECT_NE(few.find("4 observation(s) for 4 parameter(s)"), std::string::npos) << few;
}

// The built program: `renderaudit stats describe --json` prints the library's numbers and exits 0;
// an unknown column exits 2 with the located message on stderr.
TEST_F(StatsCommand, EndToEndThroughTheBinary) {
  const auto x = testing::exponential_sample(99, 2, 84);
  const std::string file = column_csv(dir_, "a.csv", x);
  const std::string out_path = (dir_ / "out.json").string();
  const std::string err_path = (dir_ / "err.txt").string();
  const std::string binary = RA_BINARY;
  auto run = [&](const std::string& column) {  // stdout to out.json, stderr to err.txt
    util::ChildSpec spec;
    spec.argv = {binary, "stats", "describe", file, "--column", column, "--json"};
    spec.stdout_path = out_path;
    spec.stderr_path = err_path;
    spec.stdin_null = true;
    return util::wait_child(util::start_child(spec).pid);
  };
  const int status = run("error_px");
  std::ifstream err_in(err_path);
  const std::string err((std::istreambuf_iterator<char>(err_in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(WEXITSTATUS(status), 0)
      << "`renderaudit stats` failed (is register_stats_command called in app/main.cpp?): " << err;
  std::ifstream out_in(out_path);
  const json j = json::parse(out_in);
  EXPECT_EQ(j["description"]["sd"].get<double>(), describe(x).sd);

  const int bad_status = run("nope");
  EXPECT_EQ(WEXITSTATUS(bad_status), ra::app::kExitUsage);
  std::ifstream err2(err_path);
  const std::string bad_err((std::istreambuf_iterator<char>(err2)),
                            std::istreambuf_iterator<char>());
  EXPECT_NE(bad_err.find("no column named 'nope'"), std::string::npos) << bad_err;
}

}  // namespace
// Why: records files end with a seal line and a run's records are one file per shard; `stats
// describe` read neither (`1 cells, but the header has 37 columns`), and selecting one platform,
// kind or view meant filtering by hand. A run directory and --where do it; values by hand.
TEST_F(StatsCommand, DescribeReadsARunsRecordsAndSelectsRowsWithWhere) {
  const std::string dir = dir_.string();
  std::filesystem::create_directories(dir + "/records");
  std::ofstream(dir + "/records/a.csv")
      << "platform,kind,pe\np,point,1\nq,point,5\np,line,\n# complete rows=3 fnv1a64=1\n";
  {  // a compressed one beside it (records/*.csv.zst, the default format)
    std::ofstream b(dir + "/records/b.csv.zst", std::ios::binary);
    util::ZstdFrameWriter z(b);
    z.write("platform,kind,pe\np,point,3\nq,point,7\n# complete rows=2 fnv1a64=2\n");
    z.end_frame();
  }
  json d = json::parse(run_stats({"describe", dir, "--column", "pe", "--where", "platform=p",
                                  "--json"}));
  EXPECT_EQ(d["description"]["n"], 2);  // 1 and 3; p's line has no pe
  EXPECT_EQ(d["n_missing"], 1);
  EXPECT_DOUBLE_EQ(d["description"]["mean"].get<double>(), 2.0);
  d = json::parse(run_stats({"describe", dir, "--column", "pe", "--json"}));
  EXPECT_EQ(d["description"]["n"], 4);  // every row of both files: 1, 5, 3, 7
  EXPECT_DOUBLE_EQ(d["description"]["mean"].get<double>(), 4.0);
  // one records file alone, seal line and all
  d = json::parse(run_stats({"describe", dir + "/records/a.csv", "--column", "pe", "--json"}));
  EXPECT_EQ(d["description"]["n"], 2);
  EXPECT_DOUBLE_EQ(d["description"]["median"].get<double>(), 3.0);
  d = json::parse(run_stats({"describe", dir + "/records/b.csv.zst", "--column", "pe", "--json"}));
  EXPECT_EQ(d["description"]["n"], 2);  // the compressed file alone: 3, 7
  EXPECT_DOUBLE_EQ(d["description"]["mean"].get<double>(), 5.0);
}

}  // namespace ra::stats
