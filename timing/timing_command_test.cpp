// End to end: `renderaudit run experiments/timing_smoke.toml` (a [timing] file: the same as
// `renderaudit timing`) on llvmpipe writes a timing.json
// with real, positive times, fits with positive H2 / H4 coefficients, Table 6 for every scene and
// method, the GPU timer's availability, the CSV files and figures beside it, and its report; with
// study_runs = 2 also Table 6 and c over the two runs, with the wins of each method.
#include <gtest/gtest.h>
#include <sstream>
#include <map>
#include <algorithm>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "tests/cli_harness.h"
#include "util/atomic_file.h"

namespace ra {
namespace {

using testing_cli::fresh_dir;
using testing_cli::run_renderaudit;

double param(const nlohmann::json& fit, const std::string& name) {
  for (const auto& p : fit.at("parameters"))
    if (p.at("name") == name) return p.at("value").get<double>();
  ADD_FAILURE() << "no parameter " << name;
  return NAN;
}

TEST(TimingCommand, SmokeStudyOnLlvmpipe) {
  const std::string dir = fresh_dir("timing_smoke");
  const auto o = run_renderaudit("run " RA_SOURCE_DIR "/experiments/timing_smoke.toml --out " +
                                 dir + " --platform osmesa-llvmpipe --quiet");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("Table 6"), std::string::npos) << o.output;

  std::ifstream in(dir + "/timing.json");
  ASSERT_TRUE(in.good());
  const nlohmann::json j = nlohmann::json::parse(in);
  EXPECT_EQ(j.at("schema"), "renderaudit-timing");
  EXPECT_EQ(j.at("schema_version"), 1);
  EXPECT_FALSE(j.at("tool").at("commit").get<std::string>().empty());
  EXPECT_FALSE(j.at("host").at("hostname").get<std::string>().empty());
  ASSERT_EQ(j.at("platforms").size(), 1u);
  const nlohmann::json& p = j.at("platforms")[0];
  EXPECT_EQ(p.at("name"), "osmesa-llvmpipe");
  EXPECT_TRUE(p.at("error").is_null());
  // one run (study_runs absent): nothing of the repeated runs is written
  EXPECT_FALSE(j.contains("repeated"));
  EXPECT_FALSE(j.at("experiment").at("settings").contains("study_runs"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/table6_repeated.csv"));
  EXPECT_NE(p.at("renderer").at("renderer").get<std::string>().find("llvmpipe"), std::string::npos);

  // GPU timer availability is reported, and used when supported
  const nlohmann::json& tq = p.at("timer_query");
  ASSERT_TRUE(tq.at("supported").is_boolean());
  EXPECT_EQ(tq.at("used").get<bool>(), tq.at("supported").get<bool>());
  if (tq.at("supported").get<bool>()) {
    EXPECT_GT(tq.at("counter_bits").get<int>(), 0);
    EXPECT_FALSE(p.at("cpu_vs_gpu").is_null());
    EXPECT_EQ(p.at("system_task").at("gpu_us").size(), 200u);
  } else {
    EXPECT_TRUE(p.at("cpu_vs_gpu").is_null());
  }

  // the system task: every rendering kept, real positive times, c = q99 - min >= 0
  const nlohmann::json& st = p.at("system_task");
  EXPECT_EQ(st.at("scene"), "terrain");  // system_task_scene, system_task_frame of the file
  EXPECT_EQ(st.at("frame"), 2);
  ASSERT_EQ(st.at("cpu_us").size(), 200u);
  for (const auto& t : st.at("cpu_us")) EXPECT_GT(t.get<double>(), 0);
  EXPECT_GT(st.at("min_us").get<double>(), 0);
  EXPECT_GE(st.at("c_us").get<double>(), 0);
  EXPECT_NEAR(st.at("c_us").get<double>(),
              st.at("q99_us").get<double>() - st.at("min_us").get<double>(), 1e-9);

  // fits: h1..h4 without and with intercept; H2 and H4 coefficients positive
  ASSERT_EQ(p.at("fits").size(), 8u);
  for (const auto& f : p.at("fits")) {
    EXPECT_EQ(f.at("n").get<int>(), 90);
    if (f.at("intercept").get<bool>()) continue;
    if (f.at("heuristic") == "h2") {
      EXPECT_GT(param(f, "c"), 0) << f.dump();
    }
    if (f.at("heuristic") == "h4") {
      EXPECT_GT(param(f, "c1"), 0) << f.dump();
      EXPECT_GT(param(f, "c2"), 0) << f.dump();
    }
  }

  // Table 6, recomputed independently from frames.csv: for each scene and method the mean over
  // the path's frames of ((predicted - measured) / 1000)^2, in ms^2.
  const nlohmann::json& t6 = p.at("table6_ms2");
  ASSERT_EQ(t6.size(), 3u);
  std::map<std::string, std::map<std::string, std::pair<double, int>>> sums;  // scene, method
  {
    std::ifstream frames(dir + "/frames.csv");
    std::string head, row;
    std::getline(frames, head);
    std::vector<std::string> names;
    std::stringstream hs(head);
    for (std::string c; std::getline(hs, c, ',');) names.push_back(c);
    auto column = [&](const std::string& n) {
      return std::size_t(std::find(names.begin(), names.end(), n) - names.begin());
    };
    while (std::getline(frames, row)) {
      std::vector<std::string> cells;
      std::stringstream rs(row);
      for (std::string c; std::getline(rs, c, ',');) cells.push_back(c);
      const double measured = std::stod(cells.at(column("measured_us")));
      for (const char* method : {"h1", "h2", "h3", "h4", "h1+b", "h2+b", "h3+b", "h4+b", "pos"}) {
        const double e = (std::stod(cells.at(column(std::string("pred_") + method + "_us"))) -
                          measured) / 1000.0;
        auto& [sum, n] = sums[cells.at(column("scene"))][method];
        sum += e * e;
        ++n;
      }
    }
  }
  for (const char* scene : {"city", "terrain", "forest"})
    for (const char* method : {"h1", "h2", "h3", "h4", "h1+b", "h2+b", "h3+b", "h4+b", "pos"}) {
      const auto [sum, n] = sums[scene][method];
      ASSERT_EQ(n, 6) << scene << " " << method;
      EXPECT_NEAR(t6.at(scene).at(method).get<double>(), sum / n, 1e-9 * (1 + sum / n))
          << scene << " " << method;
    }
  for (const auto& s : p.at("scenes")) {
    EXPECT_EQ(s.at("frames_measured").get<int>(), 6);
    EXPECT_GT(s.at("frame_base_us").get<double>(), 0);
    EXPECT_GT(s.at("triangles").get<int64_t>(), 0);
  }

  // the CSV files and figures
  std::ifstream objects(dir + "/object_samples.csv");
  std::string header, line;
  std::getline(objects, header);
  EXPECT_EQ(header.rfind("platform,scene,object,alpha,gamma,phi,triangles,vertices,transformed,"
                         "pixels,state_changes,repetitions,cpu_median_us",
                         0),
            0u);
  int rows = 0;
  while (std::getline(objects, line)) ++rows;
  EXPECT_EQ(rows, 90);
  EXPECT_TRUE(std::filesystem::exists(dir + "/frames.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir + "/pos_tables.csv"));
  for (const char* ext : {".png", ".pdf", ".csv"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/figures/system_task_density_osmesa-llvmpipe" +
                                        std::string(ext)));
    EXPECT_TRUE(std::filesystem::exists(dir + "/figures/path_osmesa-llvmpipe_city_h4" +
                                        std::string(ext)));
  }

  // The report: timing.md's tables (Table 6 with the value of timing.json) and every figure of
  // figures/index.json, one page each.
  std::ifstream md_in(dir + "/timing.md");
  const std::string md((std::istreambuf_iterator<char>(md_in)), std::istreambuf_iterator<char>());
  EXPECT_NE(md.find("### Table 6, osmesa-llvmpipe"), std::string::npos);
  char h4_city[32];
  std::snprintf(h4_city, sizeof h4_city, "%.4g", t6.at("city").at("h4").get<double>());
  EXPECT_NE(md.find(h4_city), std::string::npos) << h4_city;
  std::ifstream index_in(dir + "/figures/index.json");
  const nlohmann::json index = nlohmann::json::parse(index_in);
  const size_t figures = index.at("figures").size();
  EXPECT_EQ(figures, 1u + 3 * 5);  // the density, then 3 scenes x (h1-h4, pos)
  // study.json marks the folder; analyze and plot have nothing left to do on it
  std::ifstream study_in(dir + "/study.json");
  const nlohmann::json study = nlohmann::json::parse(study_in);
  EXPECT_EQ(study.at("kind"), "timing");
  EXPECT_EQ(study.at("document"), "timing.md");
  const auto a = run_renderaudit("analyze " + dir);
  EXPECT_EQ(a.exit_code, 0) << a.output;
  EXPECT_NE(a.output.find("a timing study is analysed as it runs"), std::string::npos) << a.output;
  const auto r = run_renderaudit("report " + dir);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto info = testing_cli::run_command("pdfinfo " + dir + "/report/report.pdf");
  EXPECT_NE(info.output.find("Pages:"), std::string::npos) << info.output;
  const auto text = testing_cli::run_command("pdftotext " + dir + "/report/report.pdf -");
  EXPECT_NE(text.output.find("Table 6, osmesa-llvmpipe"), std::string::npos);
  EXPECT_NE(r.output.find(std::to_string(figures) + " figures"), std::string::npos) << r.output;
  std::filesystem::remove_all(dir);
}

// study_runs = 2: the smoke study measured twice, one run after the other. The study's files are
// run 1's; timing.json, timing.md, table6_repeated.csv and the report add Table 6 and c over both
// runs, each run's ranking, and how often each method won (once per scene and run).
TEST(TimingCommand, RepeatedRunsGiveSpreadAndWins) {
  const std::string dir = fresh_dir("timing_runs");
  std::string text = util::read_file(RA_SOURCE_DIR "/experiments/timing_smoke.toml");
  const std::size_t at = text.find("[timing]\n");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + 9, "study_runs = 2\n");
  testing_cli::write_text(dir + "/runs.toml", text);
  const auto o = run_renderaudit("timing " + dir + "/runs.toml --out " + dir +
                                 "/out --platform osmesa-llvmpipe --quiet --no-figures");
  ASSERT_EQ(o.exit_code, 0) << o.output;
  EXPECT_NE(o.output.find("osmesa-llvmpipe over 2 runs (0 failed"), std::string::npos) << o.output;
  const std::string out = dir + "/out";
  const nlohmann::json j = nlohmann::json::parse(util::read_file(out + "/timing.json"));
  EXPECT_EQ(j.at("experiment").at("settings").at("study_runs"), 2);
  const nlohmann::json& rep = j.at("repeated");
  EXPECT_EQ(rep.at("runs"), 2);
  EXPECT_EQ(rep.at("primary_run"), 1);
  ASSERT_EQ(rep.at("platforms").size(), 1u);
  const nlohmann::json& rp = rep.at("platforms")[0];
  const nlohmann::json& p = j.at("platforms")[0];
  EXPECT_EQ(rp.at("name"), "osmesa-llvmpipe");
  EXPECT_EQ(rp.at("runs"), 2);
  EXPECT_EQ(rp.at("failed"), 0);
  EXPECT_EQ(rp.at("wall_s").size(), 2u);
  EXPECT_EQ(rp.at("wall_s")[0].get<double>(), p.at("wall_s").get<double>());

  // c over the runs: run 1's is the study's c; mean of the two inside its t interval
  const nlohmann::json& c = rp.at("system_task_c");
  ASSERT_EQ(c.at("per_run_us").size(), 2u);
  const double c1 = c.at("per_run_us")[0], c2 = c.at("per_run_us")[1];
  EXPECT_EQ(c1, p.at("system_task").at("c_us").get<double>());
  EXPECT_GE(c2, 0);
  EXPECT_NEAR(c.at("mean_us").get<double>(), (c1 + c2) / 2, 1e-9 * (1 + c1 + c2));
  EXPECT_EQ(c.at("min_us").get<double>(), std::min(c1, c2));
  EXPECT_EQ(c.at("max_us").get<double>(), std::max(c1, c2));
  EXPECT_LE(c.at("ci_low_us").get<double>(), std::min(c1, c2));  // t_0.975(1) = 12.7 > 1
  EXPECT_GE(c.at("ci_high_us").get<double>(), std::max(c1, c2));

  // Table 6 over the runs: run 1's value is the study's Table 6; every method ranked once per run;
  // the wins of each scene add up to the runs, as do those among the paper's forms
  const std::vector<std::string> methods{"h1", "h2", "h3", "h4", "h1+b", "h2+b", "h3+b", "h4+b", "pos"};
  EXPECT_EQ(rp.at("methods").get<std::vector<std::string>>(), methods);
  for (const char* scene : {"city", "terrain", "forest"}) {
    for (const std::string& m : methods) {
      const nlohmann::json& cell = rp.at("table6_ms2").at(scene).at(m);
      ASSERT_EQ(cell.at("per_run").size(), 2u) << scene << " " << m;
      const double a = cell.at("per_run")[0], b = cell.at("per_run")[1];
      EXPECT_EQ(a, p.at("table6_ms2").at(scene).at(m).get<double>()) << scene << " " << m;
      EXPECT_NEAR(cell.at("mean").get<double>(), (a + b) / 2, 1e-9 * (1 + a + b));
      EXPECT_NEAR(cell.at("sd").get<double>(), std::fabs(a - b) / std::sqrt(2.0), 1e-9 * (1 + a + b));
    }
    const nlohmann::json& rk = rp.at("ranking").at(scene);
    ASSERT_EQ(rk.at("per_run").size(), 2u);
    int wins = 0, paper_wins = 0;
    for (const auto& [m, k] : rk.at("wins").items()) wins += k.get<int>();
    for (const auto& [m, k] : rk.at("paper_wins").items()) paper_wins += k.get<int>();
    EXPECT_EQ(wins, 2) << scene;
    EXPECT_EQ(paper_wins, 2) << scene;
    for (const auto& order : rk.at("per_run")) {
      std::vector<std::string> sorted = order.get<std::vector<std::string>>();
      std::sort(sorted.begin(), sorted.end());
      std::vector<std::string> all = methods;
      std::sort(all.begin(), all.end());
      EXPECT_EQ(sorted, all);
      EXPECT_GE(rk.at("wins").at(order[0].get<std::string>()).get<int>(), 1);
    }
  }

  // the CSV: one row per scene and method, wins adding up to the runs per scene
  std::ifstream csv(out + "/table6_repeated.csv");
  std::string head, line;
  std::getline(csv, head);
  EXPECT_EQ(head, "platform,scene,method,runs,mean_ms2,sd_ms2,min_ms2,max_ms2,ci_low_ms2,"
                  "ci_high_ms2,confidence,wins,paper_wins,rank_per_run,ms2_per_run");
  std::map<std::string, int> csv_wins;
  int rows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> cells;
    std::stringstream rs(line);
    for (std::string cell; std::getline(rs, cell, ',');) cells.push_back(cell);
    ASSERT_GE(cells.size(), 12u) << line;
    csv_wins[cells[1]] += std::stoi(cells[11]);
    ++rows;
  }
  EXPECT_EQ(rows, 3 * 9);
  EXPECT_EQ(csv_wins, (std::map<std::string, int>{{"city", 2}, {"forest", 2}, {"terrain", 2}}));
  EXPECT_TRUE(std::filesystem::exists(out + "/system_task_c_repeated.csv"));

  // timing.md and the report made from it show the repeated Table 6 and the wins
  const std::string md = util::read_file(out + "/timing.md");
  EXPECT_NE(md.find("### Table 6 over 2 runs, osmesa-llvmpipe"), std::string::npos);
  EXPECT_NE(md.find("### Which method was best, osmesa-llvmpipe: runs won out of 2"), std::string::npos);
  EXPECT_NE(md.find("### System task c (99%) over 2 runs"), std::string::npos);
  EXPECT_NE(md.find("### Table 6, osmesa-llvmpipe"), std::string::npos);  // run 1's
  const auto r = run_renderaudit("report " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto pdf = testing_cli::run_command("pdftotext " + out + "/report/report.pdf -");
  EXPECT_NE(pdf.output.find("Table 6 over 2 runs, osmesa-llvmpipe"), std::string::npos);
  EXPECT_NE(pdf.output.find("Which method was best"), std::string::npos);
  std::filesystem::remove_all(dir);
}

// Bad input: exit code 2, a located message, nothing written.
TEST(TimingCommand, BadInputWritesNothing) {
  const std::string dir = fresh_dir("timing_bad");
  const std::string exp = dir + "/bad.toml";
  testing_cli::write_text(exp, "[timing]\nobject_samples = 5\n[[scene]]\nkind = \"forest\"\n");
  const auto o = run_renderaudit("timing " + exp + " --out " + dir + "/out --quiet");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_NE(o.output.find("bad.toml:2:18: 'timing.object_samples' = 5 is out of range (allowed: 10 "
                          "to 10000000)"),
            std::string::npos)
      << o.output;
  EXPECT_FALSE(std::filesystem::exists(dir + "/out"));
  const auto p = run_renderaudit("timing " RA_SOURCE_DIR
                                 "/experiments/timing_smoke.toml --platform reference --out " +
                                 dir + "/out2");
  EXPECT_EQ(p.exit_code, 2);
  EXPECT_NE(p.output.find("not a platform of"), std::string::npos) << p.output;
  const auto q = run_renderaudit("timing " + dir + "/missing.toml --out " + dir + "/out3");
  EXPECT_EQ(q.exit_code, 2);
  EXPECT_NE(q.output.find("cannot read the experiment file"), std::string::npos) << q.output;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ra
