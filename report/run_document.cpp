// The document of a run's report; see run_document.h.
#include "report/run_document.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <sstream>

#include "rundir/records_format.h"
#include "plots/headless_display.h"
#include "plots/plot_run.h"
#include "report/document.h"
#include "report/conclusion.h"
#include "report/html_writer.h"
#include "report/pdf_writer.h"
#include "analysis/run_completeness.h"
#include "analysis/run_records.h"
#include "analysis/run_tally.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/child_process.h"
#include "util/errors.h"
#include "rundir/manifest.h"
#include "rundir/study_dir.h"
#include "util/number_text.h"
#include "util/shell_quote.h"


namespace fs = std::filesystem;
using nlohmann::json;

namespace ra::report {
namespace {

std::string str(const json& j) {
  if (j.is_string()) return j.get<std::string>();
  if (j.is_null()) return "";
  return j.dump();
}

// Kinds in the paper's order: points, lines, triangles, then anything else.
int kind_rank(const std::string& kind) {
  return kind == "point" ? 0 : kind == "line" ? 1 : kind == "triangle" ? 2 : 3;
}

// The keys of a map ordered by platform, then kind in the paper's order, then the rest.
template <typename Map>
std::vector<typename Map::key_type> paper_order(const Map& m) {
  std::vector<typename Map::key_type> keys;
  for (const auto& kv : m) keys.push_back(kv.first);
  std::stable_sort(keys.begin(), keys.end(), [](const auto& a, const auto& b) {
    if (std::get<0>(a) != std::get<0>(b)) return std::get<0>(a) < std::get<0>(b);
    return kind_rank(std::get<1>(a)) < kind_rank(std::get<1>(b));
  });
  return keys;
}

Block heading(const std::string& text, int level, const std::string& anchor = "") {
  Block b;
  b.kind = Block::Kind::kHeading;
  b.level = level;
  b.text = text;
  b.anchor = anchor;
  return b;
}
Block paragraph(const std::string& text) {
  Block b;
  b.kind = Block::Kind::kParagraph;
  b.text = text;
  return b;
}
Block table_block(Table t) {
  Block b;
  b.kind = Block::Kind::kTable;
  b.table = std::move(t);
  return b;
}
// Which renderaudit made the run and which the report: once when they are the same build.
std::string version_line(const json& tool) {
  const std::string run_version = tool.value("version", rundir::project_version()) + " (commit " +
                                  tool.value("commit", rundir::project_commit()) + ")";
  const std::string this_version =
      rundir::project_version() + " (commit " + rundir::project_commit() + ")";
  return (run_version == this_version
              ? "Run and report by renderaudit " + this_version
              : "Run by renderaudit " + run_version + ", report by renderaudit " + this_version) +
         "; report generated " + rundir::utc_now_iso8601() + ".";
}

Block bullets(std::vector<std::string> items) {
  Block b;
  b.kind = Block::Kind::kBullets;
  b.items = std::move(items);
  return b;
}

// The analysis tables (*.md) in the order of DIR/analysis/README.md, then any others by name.
std::vector<std::string> table_files(const std::string& analysis_dir) {
  std::vector<std::string> order;
  std::set<std::string> seen;
  const std::string readme = analysis_dir + "/README.md";
  if (fs::exists(readme)) {
    std::stringstream ss(util::read_file(readme));
    std::string line;
    while (std::getline(ss, line)) {
      if (line.rfind("| ", 0) != 0) continue;
      const std::string name = line.substr(2, line.find(' ', 2) - 2);
      if (name.size() > 3 && name.substr(name.size() - 3) == ".md" && !seen.count(name)) {
        seen.insert(name);
        order.push_back(name);
      }
    }
  }
  std::vector<std::string> rest;
  for (const auto& e : fs::directory_iterator(analysis_dir))
    if (e.path().extension() == ".md" && !seen.count(e.path().filename().string()))
      rest.push_back(e.path().filename().string());
  std::sort(rest.begin(), rest.end());
  order.insert(order.end(), rest.begin(), rest.end());
  std::vector<std::string> out;
  for (const auto& n : order)
    if (n != "README.md" && n != "report.md" && n != "view_equivalence.md" &&
        n != "conformance.md" && n != "violations.md" &&  // section 4 shows these
        n != "paper_comparison.md" && n != "paper_differences.md" &&  // so does 6
        fs::exists(analysis_dir + "/" + n))
      out.push_back(n);
  return out;
}

// The analysis files a section shows whole, in order, headings one level down; table titles are
// collected for the result.
void add_markdown_files(const std::string& analysis_dir, const std::vector<std::string>& names,
                        Document& d, std::vector<std::string>& table_titles) {
  for (const std::string& n : names) {
    if (!fs::exists(analysis_dir + "/" + n)) continue;
    for (Block& b : parse_markdown(util::read_file(analysis_dir + "/" + n), 1)) {
      if (b.kind == Block::Kind::kTable && !b.table.title.empty())
        table_titles.push_back(plain_text(b.table.title));
      d.blocks.push_back(std::move(b));
    }
  }
}

// Pairwise figures grow with the square of the platforms. Beyond this many platforms, the PDF's
// cross-platform bihistograms are the pairs with the baseline platform (the experiment file's
// first) only: n - 1 pairs per group and metric instead of n (n - 1) / 2. The HTML report and
// DIR/figures/ keep every pair.
constexpr std::size_t kPdfAllPairsMax = 3;

// Whether figure `f` is a cross-platform bihistogram that does not involve `baseline` (its title
// names the platforms as "..., P1 (above) vs P2 (below)", plots/plot_run.cpp).
bool pair_without(const FigureRef& f, const std::string& baseline) {
  if (f.id.find(".platforms.") == std::string::npos) return false;
  return f.title.find(", " + baseline + " (above)") == std::string::npos &&
         f.title.find(" vs " + baseline + " (below)") == std::string::npos;
}

// The run as its manifest describes it: the experiment's name (the directory's when it has none).
std::string run_name(const std::string& run_dir, const rundir::ManifestExperiment& exp) {
  return exp.name.empty() ? fs::path(run_dir).filename().string() : exp.name;
}

std::string or_unknown(const std::string& text) { return text.empty() ? "?" : text; }

// The title page: what was run, by which renderaudit, and the conclusion; then the contents.
void add_title_page(Document& d, const std::string& run_dir, const rundir::RunManifest& m,
                    const analysis::RunTally& tally) {
  const rundir::ManifestExperiment exp = m.experiment.value_or(rundir::ManifestExperiment{});
  const std::string name = run_name(run_dir, exp);
  d.title = "renderaudit report: " + name;
  d.footer = "renderaudit report: " + name + " (" + run_dir + ")";
  d.subtitle = {
      "How accurately, and how fast, OpenGL renderers draw points, line segments and triangles: "
      "the rendering-error audit of Hagedorn et al., J. Res. NIST 113 (2008), section 4, "
      "reproduced on this run.",
      "Run directory: " + run_dir + ". Experiment " + name + " (" + or_unknown(exp.file) +
          ", hash " + or_unknown(exp.hash) + "), seed " +
          (exp.seed ? std::to_string(*exp.seed) : "") + ".",
      version_line(m.tool.is_object() ? m.tool : json::object())};
  // The conclusion first, on the title page; the contents and the detail after it.
  for (Block& b : conclusion_blocks(run_dir, tally)) d.blocks.push_back(std::move(b));
  Block contents;
  contents.kind = Block::Kind::kContents;
  d.blocks.push_back(contents);
}

// 1. The run's provenance: experiment, completeness, times, tool, host; the drivers; the file.
void add_provenance(Document& d, const std::string& run_dir, const rundir::RunManifest& m,
                    const analysis::RunTally& tally,
                    const analysis::RunCompleteness& completeness) {
  const rundir::ManifestExperiment exp = m.experiment.value_or(rundir::ManifestExperiment{});
  const std::string name = run_name(run_dir, exp);
  const json tool = m.tool.is_object() ? m.tool : json::object();
  const json host = m.host.is_object() ? m.host : json::object();
  // 1. Provenance.
  d.blocks.push_back(heading("1. Experiment and provenance", 1, "provenance"));
  {
    Table t;
    t.title = "The run (manifest.json, schema version " + (m.schema_version ? std::to_string(*m.schema_version) : "") + ")";
    t.header = {"what", "value"};
    t.right = {false, false};
    std::string plist;
    for (std::size_t i = 0; i < exp.platforms.size(); ++i) plist += (i ? ", " : "") + exp.platforms[i];
    const std::vector<rundir::ManifestInvocation> invocations =
        m.invocations.value_or(std::vector<rundir::ManifestInvocation>{});
    double elapsed = 0;
    for (const rundir::ManifestInvocation& inv : invocations)
      elapsed += inv.elapsed_s.value_or(0.0);
    auto row = [&](const std::string& k, const std::string& v) { t.rows.push_back({k, v}); };
    row("experiment", name + " (" + or_unknown(exp.file) + ")");
    row("experiment hash", or_unknown(exp.hash));
    row("seed", exp.seed ? std::to_string(*exp.seed) : "");
    row("platforms", plist);
    // What the records say, checked against the plan; the manifest's own word in brackets.
    row("completeness", completeness.one_line());
    for (std::size_t i = 0; i < completeness.problems.size() && i < 10; ++i)
      row(i == 0 ? "what is missing" : "", completeness.problems[i]);
    if (completeness.problems.size() > 10)
      row("", "... and " + std::to_string(completeness.problems.size() - 10) + " more");
    row("records", std::to_string(tally.records) + " in " + std::to_string(tally.files) + " files");
    row("started / finished (UTC)", or_unknown(m.started) + " / " + or_unknown(m.finished));
    row("run time", util::fixed(elapsed, 1) + " s over " + std::to_string(invocations.size()) +
                        " invocation(s)");
    row("tool", tool.value("name", std::string("renderaudit")) + " " + tool.value("version", "?") +
                    ", commit " + tool.value("commit", "?"));
    row("host", host.value("hostname", "?") + ": " + host.value("cpu", "?") + ", " +
                    str(host.value("cores", json())) + " cores, " + host.value("os", "?"));
    d.blocks.push_back(table_block(std::move(t)));
  }
  {
    Table t;
    t.title = "Drivers: what each platform's OpenGL said about itself (manifest.json, drivers/)";
    t.header = {"platform", "GL_RENDERER", "GL_VERSION", "GL_VENDOR", "GL_SUBPIXEL_BITS",
                "effective subpixel grid (measured)", "timer query"};
    t.right = {false, false, false, false, true, false, false};
    const json drivers = m.drivers.is_object() ? m.drivers : json::object();
    for (const auto& [platform, dj] : drivers.items()) {
      const json e = dj.value("effective_subpixel", json());
      const std::string effective =
          e.is_object() ? e.value("text", "?") + " (" + str(e.value("matches", json())) + " of " +
                              str(e.value("triangles", json())) + " triangles)"
                        : "not measured";
      t.rows.push_back({platform, dj.value("renderer", "?"), dj.value("version", "?"),
                        dj.value("vendor", "?"), str(dj.value("subpixel_bits", json())), effective,
                        str(dj.value("timer_query", json()))});
    }
    if (t.rows.empty()) t.notes.push_back("manifest.json lists no driver.");
    t.notes.push_back(
        "GL_SUBPIXEL_BITS is what the driver says (GL requires at least 4); the effective grid is "
        "what its pixels show: the subpixel grid (bits, rounding) under which the reference "
        "rasterizer lights the same pixels as the driver for the most of 96 calibration triangles "
        "(runner/effective_subpixel.h). A driver whose effective grid is finer than it says only "
        "undersells itself; one whose grid is coarser than it says snaps more than it promises, "
        "and one coarser than 4 bits breaks GL's rule.");
    d.blocks.push_back(table_block(std::move(t)));
  }
  const std::string toml = rundir::run_folder::experiment(run_dir);
  if (fs::exists(toml)) {
    d.blocks.push_back(heading("The experiment file (experiment.toml, copied into the run)", 2));
    Block b;
    b.kind = Block::Kind::kPreformatted;
    b.text = util::read_file(toml);
    d.blocks.push_back(b);
  }
}

// 2. Shards that failed, records that are not ok, figures not drawn.
void add_failures(Document& d, const rundir::RunManifest& m, const analysis::RunTally& tally,
                  const plots::PlotResult& figures) {
  // 2. Failures.
  d.blocks.push_back(heading("2. Failures and invalid cases", 1, "failures"));
  {
    const std::vector<rundir::ManifestShardNote>& failures = m.failures_or_none();
    if (failures.empty()) {
      d.blocks.push_back(paragraph(
          "No shard crashed or timed out (manifest.json: \"failures\" is empty)."));
    } else {
      Table t;
      t.title = "Shards that crashed or timed out (manifest.json \"failures\"): " +
                std::to_string(failures.size());
      t.header = {"shard (platform.kind.view.index range)", "what happened"};
      t.right = {false, false};
      for (const rundir::ManifestShardNote& f : failures)
        t.rows.push_back({f.shard, or_unknown(f.reason)});
      t.notes.push_back("Their records are missing from every statistic; run the same `renderaudit "
                        "run` command again to retry them (finished shards are kept).");
      d.blocks.push_back(table_block(std::move(t)));
    }
    if (tally.non_ok_counts.empty()) {
      d.blocks.push_back(paragraph("Every record has status ok: no invalid (non-finite) input, "
                                   "no per-primitive crash or timeout."));
    } else {
      Table t;
      t.title = "Records whose status is not ok (excluded from every metric)";
      t.header = {"platform", "kind", "status", "records"};
      t.right = {false, false, false, true};
      for (const auto& k : paper_order(tally.non_ok_counts)) {
        const auto n = tally.non_ok_counts.at(k);
        t.rows.push_back({std::get<0>(k), std::get<1>(k), std::get<2>(k), std::to_string(n)});
      }
      d.blocks.push_back(table_block(std::move(t)));
      Table e;
      e.title = "The first " +
                std::to_string(std::min<std::size_t>(30, tally.non_ok_examples.size())) +
                " of them";
      e.header = {"platform", "kind", "view", "primitive index", "status", "records file:line"};
      e.right = {false, false, true, true, false, false};
      for (std::size_t i = 0; i < tally.non_ok_examples.size() && i < 30; ++i) {
        const auto& x = tally.non_ok_examples[i];
        e.rows.push_back({x.platform, x.kind, std::to_string(x.view), std::to_string(x.index),
                          x.status, x.file + ":" + std::to_string(x.line)});
      }
      d.blocks.push_back(table_block(std::move(e)));
    }
    if (figures.skipped.empty()) {
      d.blocks.push_back(paragraph("Every planned figure was drawn."));
    } else {
      d.blocks.push_back(paragraph("Figures not drawn for lack of data:"));
      std::vector<std::string> items;
      for (const auto& s : figures.skipped) items.push_back(s.section + ": " + s.what + ": " + s.reason + ".");
      d.blocks.push_back(bullets(items));
    }
  }
}

// 3. Render time per primitive.
void add_timing(Document& d, const analysis::RunTally& tally) {
  d.blocks.push_back(heading("3. Time per primitive", 1, "timing"));
  d.blocks.push_back(paragraph(
      "render_us is the time of a primitive's drawing in microseconds, measured by the runner "
      "on the clock the records' clock column names: on the host, the CPU time of the draw call "
      "and glFinish; on a GPU with a timer, the device's own. A large primitive is drawn and timed alone; small ones are drawn "
      "in batches of up to 64 under one glFinish and each gets an equal share of the batch's "
      "time (records column batch_size). Medians and IQRs (Hyndman-Fan 6) over the "
      "records with status ok; the analysis table 'Render time beside error' breaks them down by "
      "view group. Times depend on the machine and its load, unlike the errors. " +
      std::string(analysis::kDeviceClockNote)));
  for (const auto& [key, time] : tally.render_time)
    if (analysis::is_vulkan_platform(key.first)) {
      d.blocks.push_back(paragraph(analysis::kVulkanRenderTimeNote));
      break;
    }
  {
    Table t;
    t.title = "Median render time per primitive, by platform and kind";
    t.header = {"platform", "kind", "cases", "median us", "IQR us", "true-visible",
                "median us (true-visible)", "primitives per second (1 / median)"};
    t.right = {false, false, true, true, true, true, true, true};
    for (const auto& k : paper_order(tally.render_time)) {
      const analysis::RenderTime& r = tally.render_time.at(k);
      const double med = r.median_us;
      t.rows.push_back({k.first, k.second, std::to_string(r.cases), util::fixed(med, 2),
                        util::fixed(r.iqr_us, 2), std::to_string(r.true_visible),
                        r.median_us_true_visible ? util::fixed(*r.median_us_true_visible, 2)
                                                 : "no data",
                        med > 0 ? util::fixed(1e6 / med, 0) : "n/a"});
    }
    if (t.rows.empty()) t.notes.push_back("No record has a render time.");
    d.blocks.push_back(table_block(std::move(t)));
  }

}

// 4. Conformance: the analysis' conformance and violations pages, the reference comparison.
void add_conformance(RunDocument& c, const std::string& run_dir, const analysis::RunTally& tally) {
  Document& d = c.doc;
  // 4. Conformance.
  d.blocks.push_back(heading("4. Does each driver rasterize as GL allows?", 1, "conformance"));
  {
    const std::string dir = rundir::run_folder::analysis(run_dir);
    if (fs::exists(dir + "/conformance.md")) {
      for (Block& b : parse_markdown(util::read_file(dir + "/conformance.md"), 1)) {
        if (b.kind == Block::Kind::kTable && !b.table.title.empty())
          c.table_titles.push_back(plain_text(b.table.title));
        d.blocks.push_back(std::move(b));
      }
    } else {
      d.blocks.push_back(paragraph("analysis/conformance.md is missing: run `renderaudit analyze " +
                                   util::shell_quote(run_dir) + "`."));
    }
    if (fs::exists(dir + "/violations.md")) {
      // The first violations, worst first; the whole list is analysis/violations.md.
      std::string text = util::read_file(dir + "/violations.md");
      std::size_t cut = 0;
      for (int rows = 0; rows < 22 && cut != std::string::npos; ++rows)
        cut = text.find("\n| ", cut + 1);
      if (cut != std::string::npos) text = text.substr(0, cut) + "\n";
      for (Block& b : parse_markdown(text, 2)) d.blocks.push_back(std::move(b));
    }
  }
  d.blocks.push_back(paragraph(
      "ref_diff counts the pixels in the symmetric difference between what a platform lit and "
      "what the project's exact reference rasterizer (the GL rules, no driver) lights for the same "
      "primitive; 0 means the pixel sets are identical. The rate is the share of records (status "
      "ok) with ref_diff = 0, over all compared records and over those where either rasterizer "
      "lit a pixel (invisible primitives agree trivially)."));
  {
    Table t;
    t.title = "Share of primitives whose pixels equal the reference rasterizer's, by platform, "
              "kind and view group";
    t.header = {"platform", "kind", "view group", "compared", "identical", "rate %",
                "lit by either", "identical", "rate % (lit)"};
    t.right = {false, false, false, true, true, true, true, true, true};
    for (const auto& k : paper_order(tally.reference)) {
      const analysis::ReferenceAgreement& cf = tally.reference.at(k);
      std::string group(1, char('A' + std::get<2>(k)));
      const auto label = tally.group_labels.find(k);
      if (label != tally.group_labels.end()) group += " (" + label->second + ")";
      t.rows.push_back({std::get<0>(k), std::get<1>(k), group, std::to_string(cf.compared),
                        std::to_string(cf.identical), util::fixed(100 * cf.rate(), 2),
                        std::to_string(cf.drawn), std::to_string(cf.drawn_identical),
                        cf.drawn ? util::fixed(100 * cf.drawn_rate(), 2) : "n/a"});
    }
    if (t.rows.empty()) t.notes.push_back("No record carries a reference comparison (ref_diff).");
    d.blocks.push_back(table_block(std::move(t)));
  }

}

// 5-7. View equivalence, the paper's tables beside this run's, every analysis table.
void add_analysis_tables(RunDocument& c, const std::string& run_dir) {
  Document& d = c.doc;
  // 5. View equivalence.
  const std::string analysis = rundir::run_folder::analysis(run_dir);
  d.blocks.push_back(heading("5. View pooling: the equivalence tests", 1, "equivalence"));
  {
    const std::string csv = analysis + "/view_equivalence.csv", md = analysis + "/view_equivalence.md";
    if (fs::exists(csv)) {
      const Table full = read_csv_table(csv);
      d.blocks.push_back(paragraph("Every statistic (t, F, Levene W, degrees of freedom, Box-Cox "
                                   "lambda and shift) is in analysis/view_equivalence.csv: " +
                                   full.title + "."));
    }
    if (fs::exists(md)) {
      std::vector<Block> blocks = parse_markdown(util::read_file(md), 1);
      // The file's own title repeats this section's heading.
      if (!blocks.empty() && blocks.front().kind == Block::Kind::kHeading) blocks.erase(blocks.begin());
      for (Block& b : blocks) {
        if (b.kind == Block::Kind::kTable && !b.table.title.empty())
          c.table_titles.push_back(plain_text(b.table.title));
        d.blocks.push_back(std::move(b));
      }
    } else {
      d.blocks.push_back(paragraph("analysis/view_equivalence.md is missing: run `renderaudit "
                                   "analyze " + run_dir + "`."));
    }
  }

  // 6. The paper.
  if (fs::exists(analysis + "/paper_comparison.md")) {
    d.blocks.push_back(heading("6. Beside the paper", 1, "paper"));
    d.blocks.push_back(paragraph(
        "Each median and IQR of the paper's Tables 3-10 that this run's views reproduce, beside "
        "the paper's two platforms, then every cell beyond 3 standard errors of the paper with "
        "the reason established for it."));
    add_markdown_files(analysis, {"paper_comparison.md", "paper_differences.md"}, d,
                       c.table_titles);
  }

  // 7. Tables.
  d.blocks.push_back(heading("7. Tables", 1, "tables"));
  d.blocks.push_back(paragraph(
      "Every table of the analysis (DIR/analysis/, also as .csv, .md and .tex). Tables 2-11 "
      "mirror the paper's; 's' and 'e' tables supplement them with the non-normalized metrics."));
  if (fs::is_directory(analysis)) {
    for (const std::string& file : table_files(analysis)) {
      std::vector<Block> blocks = parse_markdown(util::read_file(analysis + "/" + file), 1);
      for (Block& b : blocks) {
        if (b.kind == Block::Kind::kTable && !b.table.title.empty())
          c.table_titles.push_back(plain_text(b.table.title));
        d.blocks.push_back(std::move(b));
      }
    }
  }

}

// 8. The figures; beyond kPdfAllPairsMax platforms the PDF keeps the pairs with the first only.
void add_figure_section(RunDocument& c, const plots::PlotResult& figures,
                        const std::vector<std::string>& platforms) {
  Document& d = c.doc;
  // 8. Figures.
  d.blocks.push_back(heading("8. Figures", 1, "figures"));
  d.blocks.push_back(paragraph(
      "Drawn by `renderaudit plot` with VTK charts: PNG through vtkWindowToImageFilter and "
      "vtkPNGWriter, vector PDF through vtkPDFExporter (the pages that follow), the numbers "
      "drawn as CSV beside each (DIR/figures/). Metric values are shown x 10^k with the k of the "
      "tables. Box plots restrict the y range to the box bodies, as the paper's do, and say on "
      "the figure which extremes lie outside."));
  add_figures(figures, d);
  // the overview is the first page's picture; a figure page of its own would be a short page
  for (const FigureRef& f : d.figures)
    if (f.id == "conformance.overview") c.html_only.insert(f.id);
  if (platforms.size() > kPdfAllPairsMax) {
    c.pdf_pairs_with = platforms.front();
    std::size_t left_out = 0;
    for (const FigureRef& f : d.figures)
      if (pair_without(f, platforms.front())) c.html_only.insert(f.id), ++left_out;
    const std::size_t n = platforms.size();
    d.blocks.insert(d.blocks.end() - 1,
                    paragraph("This run has " + std::to_string(n) + " platforms. The PDF shows "
                              "the cross-platform bihistograms of the pairs with the baseline "
                              "platform " + platforms.front() + " (the experiment's first): " +
                              std::to_string(n - 1) + " of the " +
                              std::to_string(n * (n - 1) / 2) + " pairs of each view group and "
                              "metric (" + std::to_string(left_out) + " figures left "
                              "out), and the cross-platform tests of those pairs only. "
                              "report.html, figures/ and analysis/ hold every pair."));
  }
}

}  // namespace

// The list of figures, then one page per figure of the index (paths relative to DIR/report).
void add_figures(const plots::PlotResult& figures, Document& d) {
  Block list;
  list.kind = Block::Kind::kFigureList;
  d.blocks.push_back(list);
  int number = 0;
  for (const auto& f : figures.figures) {
    FigureRef r;
    r.number = ++number;
    r.id = f.id, r.section = f.section, r.title = f.title, r.caption = f.caption, r.note = f.note;
    r.png = "../figures/" + f.png;
    r.pdf = "../figures/" + f.pdf;
    r.pdf_path = (fs::path(figures.figures_dir) / f.pdf).string();
    d.figures.push_back(r);
  }
}

// `doc` with only the figures the PDF shows, numbered 1, 2, ... in order; with `pairs_with` set,
// the rows of pairwise tables (columns "Platform a", "Platform b") are those of its pairs.
Document pdf_document(const Document& doc, const std::set<std::string>& html_only,
                      const std::string& pairs_with) {
  Document pdf = doc;
  if (!pairs_with.empty())
    for (Block& b : pdf.blocks) {
      if (b.kind != Block::Kind::kTable) continue;
      Table& t = b.table;
      const auto a = std::find(t.header.begin(), t.header.end(), "Platform a");
      const auto z = std::find(t.header.begin(), t.header.end(), "Platform b");
      if (a == t.header.end() || z == t.header.end()) continue;
      const std::size_t ia = std::size_t(a - t.header.begin()), iz = std::size_t(z - t.header.begin());
      const std::size_t before = t.rows.size();
      std::vector<std::vector<std::string>> kept;
      for (auto& row : t.rows)
        if (row.size() > std::max(ia, iz) &&
            (plain_text(row[ia]) == pairs_with || plain_text(row[iz]) == pairs_with))
          kept.push_back(std::move(row));
      t.rows = std::move(kept);
      t.notes.push_back("This PDF shows the " + std::to_string(t.rows.size()) + " of " +
                        std::to_string(before) + " rows that pair " + pairs_with +
                        " with another platform; report.html and the CSV file hold every pair.");
    }
  pdf.figures.clear();
  for (const FigureRef& f : doc.figures)
    if (!html_only.count(f.id)) {
      pdf.figures.push_back(f);
      pdf.figures.back().number = int(pdf.figures.size());
    }
  return pdf;
}

RunDocument build_run_document(const std::string& run_dir, const plots::PlotResult& figures,
                               const analysis::RunTally& tally,
                               const analysis::RunCompleteness& completeness) {
  const std::string manifest_path = rundir::run_folder::manifest(run_dir);
  const rundir::RunManifest m = rundir::read_manifest_file_or_empty(manifest_path);
  RunDocument c;
  add_title_page(c.doc, run_dir, m, tally);
  add_provenance(c.doc, run_dir, m, tally, completeness);
  add_failures(c.doc, m, tally, figures);
  add_timing(c.doc, tally);
  add_conformance(c, run_dir, tally);
  add_analysis_tables(c, run_dir);
  add_figure_section(c, figures, m.experiment.value_or(rundir::ManifestExperiment{}).platforms);
  return c;
}

}  // namespace ra::report
