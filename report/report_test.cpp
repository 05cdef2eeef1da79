// End to end, as CI runs it (no DISPLAY): run -> report, the report running `analyze` and `plot`
// itself; then the PDF is read back with poppler's pdfinfo / pdftotext and compared with what the
// analysis and plot stages wrote.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>

#include "tests/cli_harness.h"

namespace {

using namespace ra::testing_cli;
namespace fs = std::filesystem;



std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// A small run: points only (lines and triangles have no records, so their figures are skipped
// and the report must say so), one view group of two orientations.
std::string small_run(const std::string& name) {
  const std::string dir = fresh_dir(name);
  write_text(dir + "/exp.toml",
             "name = \"report_e2e\"\nseed = 11\nplatforms = [\"osmesa-llvmpipe\"]\n"
             "[views]\norientations = 2\nfov_deg = [150]\nwindows = [128]\nnear = 0.01\n"
             "far = 10.0\n[primitives]\npoints = 600\nlines = 0\ntriangles = 0\n");
  const Outcome o = run_renderaudit("run " + dir + "/exp.toml --out " + dir + "/run -q");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  return dir + "/run";
}

// Why: `renderaudit report` must work where CI runs it (no display), run the stages it needs,
// and produce a PDF with one page per figure after the text pages, holding every table's title;
// the HTML must show every figure.
TEST(ReportCommand, HeadlessReportHasEveryTableAndOnePagePerFigure) {
  ::unsetenv("DISPLAY");  // as on CI, whatever the developer's session has
  const std::string run = small_run("report_e2e");

  // Without --no-run... first with it: nothing analysed yet, the exact commands are named.
  const Outcome refused = run_renderaudit("report " + run + " --no-run");
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("renderaudit analyze " + run), std::string::npos) << refused.output;
  EXPECT_NE(refused.output.find("renderaudit plot " + run), std::string::npos) << refused.output;

  const Outcome o = run_renderaudit("report " + run);
  ASSERT_EQ(o.exit_code, 0) << o.output;
  // The commands name this program as invoked (its path unless "renderaudit" on PATH is it).
  EXPECT_TRUE(std::regex_search(o.output, std::regex("running `[^`]*renderaudit analyze "))) << o.output;
  EXPECT_TRUE(std::regex_search(o.output, std::regex("running `[^`]*renderaudit plot "))) << o.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(o.output, m, std::regex(R"((\d+) pages \((\d+) text, (\d+) figures\))")))
      << o.output;
  const int pages = std::stoi(m[1]), text_pages = std::stoi(m[2]), figure_pages = std::stoi(m[3]);

  // The figures: as many PDF pages as index.json lists, each PNG and PDF present.
  const auto index = nlohmann::json::parse(read(run + "/figures/index.json"));
  // every figure has a page of its own but the overview, which page 1 shows
  nlohmann::json figures = nlohmann::json::array();
  for (const auto& f : index.at("figures"))
    if (f.at("id") != "conformance.overview") figures.push_back(f);
  ASSERT_EQ(figures.size() + 1, index.at("figures").size());
  ASSERT_GE(figures.size(), 6u);  // visibility, conformance, 2 box plots, 2 histograms, 2 Q-Q
  EXPECT_EQ(int(figures.size()), figure_pages);
  for (const auto& f : figures) {
    EXPECT_TRUE(fs::exists(run + "/figures/" + f.at("png").get<std::string>()));
    EXPECT_TRUE(fs::exists(run + "/figures/" + f.at("pdf").get<std::string>()));
    EXPECT_TRUE(fs::exists(run + "/figures/" + f.at("csv").get<std::string>()));
  }
  std::string skipped = index.at("skipped").dump();
  EXPECT_NE(skipped.find("line segments"), std::string::npos) << skipped;
  EXPECT_NE(skipped.find("triangles"), std::string::npos) << skipped;

  // (That the private Xvfb is stopped is HeadlessDisplay's test: a display number is free again
  // at once, so another test running beside this one may be using it by now.)
  EXPECT_EQ(index.at("display").get<std::string>().rfind("private Xvfb :", 0), 0u);

  // The PDF: text pages + one page per figure, in the index's order.
  const std::string pdf = run + "/report/report.pdf";
  const std::string info = shell_output("pdfinfo '" + pdf + "'");
  EXPECT_NE(info.find("Pages:           " + std::to_string(pages) + "\n"), std::string::npos) << info;
  EXPECT_EQ(pages, text_pages + figure_pages);
  for (std::size_t i = 0; i < figures.size(); ++i) {
    const int page = text_pages + 1 + int(i);
    const std::string text = squeeze(shell_output("pdftotext -f " + std::to_string(page) + " -l " +
                                                  std::to_string(page) + " '" + pdf + "' -"));
    const std::string title = figures[i].at("title");
    EXPECT_NE(text.find(squeeze(title)), std::string::npos) << "page " << page << ": " << text;
  }

  // Every table of the analysis, by the title on the first line of its CSV, is in the text.
  const std::string all_text = squeeze(shell_output("pdftotext '" + pdf + "' -"));
  int tables = 0;
  for (const auto& e : fs::directory_iterator(run + "/analysis")) {
    if (e.path().extension() != ".csv") continue;
    std::ifstream in(e.path());
    std::string first;
    std::getline(in, first);
    ASSERT_EQ(first.rfind("# ", 0), 0u) << e.path();
    const std::string title = squeeze(first.substr(2));
    EXPECT_NE(all_text.find(title), std::string::npos) << e.path() << ": " << title;
    ++tables;
  }
  EXPECT_GE(tables, 4);  // view equivalence, Tables 2, 3, 4, 11, speed
  // Provenance, failures and timing are there too.
  for (const char* s : {"GL_RENDERER", "llvmpipe", "seed", "No shard crashed",
                        "Median render time per primitive", "Figures not drawn for lack of data"})
    EXPECT_NE(all_text.find(s), std::string::npos) << s;

  // Failures: a crashed shard in the manifest and an invalid record must be reported, and the
  // changed inputs make the analysis stale, so the report runs it again.
  std::string records_file;
  for (const auto& e : fs::directory_iterator(run + "/records"))
    if (ra::rundir::is_records_file_name(e.path().filename().string()) &&
        (records_file.empty() || e.path().string() < records_file))
      records_file = e.path().string();
  {
    std::string text = ra::testing_cli::read_records_text(records_file);
    const auto line2 = text.find('\n') + 1;
    const auto ok = text.find(",ok,", line2);
    ASSERT_LT(ok, text.find('\n', line2));
    text.replace(ok, 4, ",invalid,");
    ra::testing_cli::write_records_text(records_file, text);
    reseal_records_file(records_file);  // as a run that recorded it so would have
    auto manifest = nlohmann::json::parse(read(run + "/manifest.json"));
    manifest["failures"].push_back({{"shard", "osmesa-llvmpipe.point.v9.0-100"},
                                    {"reason", "crashed (signal 11, Segmentation fault)"}});
    write_text(run + "/manifest.json", manifest.dump(2));
  }
  const Outcome again = run_renderaudit("report " + run);
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("is older than the records"), std::string::npos) << again.output;
  const std::string failures_text = squeeze(shell_output("pdftotext '" + pdf + "' -"));
  for (const std::string& s :
       {std::string("Records whose status is not ok"), std::string("invalid"),
        "records/" + fs::path(records_file).filename().string() + ":2",
        std::string("osmesa-llvmpipe.point.v9.0-100"), std::string("crashed (signal 11")})
    EXPECT_NE(failures_text.find(s), std::string::npos) << s;

  // The HTML shows every figure, by a relative path that exists.
  const std::string html = read(run + "/report/report.html");
  for (const auto& f : figures) {
    const std::string src = "../figures/" + f.at("png").get<std::string>();
    EXPECT_NE(html.find("src=\"" + src + "\""), std::string::npos) << src;
  }

  // The first page states the conclusion per platform; the version is named once. With an
  // audit in the run (as `make nightly` leaves it), the first page gives the verdict per driver
  // and names the baseline.
  const auto first_page = [&] {
    return squeeze(shell_output("pdftotext -f 1 -l 1 '" + pdf + "' -"));
  };
  std::string page1 = first_page();
  EXPECT_NE(page1.find("Conclusion"), std::string::npos) << page1;
  EXPECT_NE(page1.find("osmesa-llvmpipe: "), std::string::npos) << page1;
  EXPECT_NE(page1.find("primitives drawn exactly as the reference rasterizer"), std::string::npos)
      << page1;
  EXPECT_NE(page1.find("Run and report by renderaudit "), std::string::npos) << page1;
  // ... and shows the finding as a picture: one image on page 1, the overview figure in the HTML
  const std::string images = shell_output("pdfimages -f 1 -l 1 -list '" + pdf + "'");
  EXPECT_NE(images.find(" image "), std::string::npos) << images;  // a row under the header
  EXPECT_NE(page1.find("Where each driver lights other pixels than the exact reference"),
            std::string::npos) << page1;
  EXPECT_NE(read(run + "/report/report.html").find("<img src=\"../figures/conformance.overview.png\""),
            std::string::npos);
  EXPECT_EQ(page1.find(", report by renderaudit"), std::string::npos) << "one build: named once";
  // (the crashed shard the manifest lists above fails the audit, and its driver)
  const Outcome audit = run_renderaudit("audit " + run + " " + run + " --no-history");
  EXPECT_EQ(audit.exit_code, 2) << audit.output;
  ASSERT_EQ(run_renderaudit("report " + run).exit_code, 0);
  page1 = first_page();
  EXPECT_NE(page1.find("Audit: failed against the baseline run " + run), std::string::npos)
      << page1;
  EXPECT_NE(page1.find("osmesa-llvmpipe osmesa-llvmpipe FAIL 1200 0 0 2 0"), std::string::npos)
      << page1;
  // a run without failures passes
  auto manifest = nlohmann::json::parse(read(run + "/manifest.json"));
  manifest["failures"] = nlohmann::json::array();
  write_text(run + "/manifest.json", manifest.dump(2));
  // audited against itself (a nightly series' first night): a baseline, no verdict, no PASS
  ASSERT_EQ(run_renderaudit("audit " + run + " " + run + " --no-history").exit_code, 0);
  ASSERT_EQ(run_renderaudit("report " + run).exit_code, 0);
  page1 = first_page();
  EXPECT_NE(page1.find("Audit: baseline established: nothing compared."), std::string::npos)
      << page1;
  EXPECT_EQ(page1.find("PASS"), std::string::npos) << page1;
  // against a copy of itself: compared, unchanged, PASS
  fs::copy(run, run + "-copy", fs::copy_options::recursive);
  ASSERT_EQ(run_renderaudit("audit " + run + " " + run + "-copy --no-history").exit_code, 0);
  ASSERT_EQ(run_renderaudit("report " + run + "-copy").exit_code, 0);
  const std::string copy_page1 =
      squeeze(shell_output("pdftotext -f 1 -l 1 '" + run + "-copy/report/report.pdf' -"));
  EXPECT_NE(copy_page1.find("Audit: unchanged against the baseline run " + run), std::string::npos)
      << copy_page1;
  EXPECT_NE(copy_page1.find("osmesa-llvmpipe osmesa-llvmpipe PASS 1200 0 0 0 0"),
            std::string::npos)
      << copy_page1;
}

}  // namespace
