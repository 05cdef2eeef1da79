// plot_run: plans every figure of a run from figures.json and the records, draws them with VTK
// (see the header for the list and the files).
#include "plots/plot_run.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "analysis/figure_data.h"
#include "analysis/paper_tables.h"
#include "analysis/run_records.h"
#include "plots/figure_builders.h"
#include "plots/figure_planner.h"
#include "plots/figure_renderer.h"
#include "plots/headless_display.h"
#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/progress_line.h"
#include "util/shell_quote.h"
#include "util/json_file.h"
#include "metrics/records.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace ra::plots {
namespace {

constexpr int kFigureIndexSchemaVersion = 1;

json figure_json(const IndexedFigure& f, const FigureLayout& layout) {
  json j{{"id", f.id},           {"kind", f.kind}, {"section", f.section}, {"title", f.title},
         {"caption", f.caption}, {"note", f.note}, {"png", f.png},         {"pdf", f.pdf},
         {"csv", f.csv}};
  j["layout"] = {{"width", layout.width},         {"height", layout.height},
                 {"plot_left", layout.plot_left}, {"plot_right", layout.plot_right},
                 {"plot_top", layout.plot_top},   {"plot_bottom", layout.plot_bottom},
                 {"x_min", layout.x_min},         {"x_max", layout.x_max},
                 {"y_min", layout.y_min},         {"y_max", layout.y_max},
                 {"x_log10", layout.x_log10},     {"y_log10", layout.y_log10}};
  return j;
}

}  // namespace

FigurePlan plan_figures(const std::string& run_dir, unsigned jobs) {
  const std::string path = rundir::run_folder::figure_data(run_dir);
  if (!fs::exists(path))
    throw util::UserError(path + " not found: run `renderaudit analyze " + util::shell_quote(run_dir) + "` first");
  json doc;
  try {
    doc = util::parse_json_document(util::read_file(path), path);
  } catch (const json::exception& e) {
    throw util::UserError(path + ": not valid JSON: " + e.what());
  }
  rundir::require_document_header(doc, "figures", an::kFiguresSchemaVersion, path,
                                  "run `renderaudit analyze " + run_dir + "` again");
  const an::RunTally tally = an::read_tally(run_dir);

  an::LoadOptions lo;
  lo.jobs = jobs;
  const an::RunRecords run = an::load_run_records(run_dir, lo);

  FigurePlan plan;
  std::set<std::string> ids;
  FigurePlanner p{run_dir, doc, run, tally, plan, ids};
  try {
    for (geometry::Kind kind : an::kAllKinds) {
      const auto kinds = run.kinds();
      if (std::find(kinds.begin(), kinds.end(), kind) == kinds.end()) {
        p.skip(section_of(kind), "every figure of " + std::string(section_of(kind)),
               std::string("the run has no records of ") + section_of(kind));
        continue;
      }
      plan_tally_figures(p, kind);
      plan_distribution_figures(p, kind);
      plan_comparison_figures(p, kind);
      plan_speed_error_figures(p, kind);
    }
    plan_conformance_overview(p);
  } catch (const json::exception& e) {
    throw util::UserError(path + ": unexpected content: " + e.what() +
                          " (run `renderaudit analyze " + util::shell_quote(run_dir) + "` again)");
  }
  return plan;
}

PlotResult plot_run(const PlotOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  if (!fs::is_directory(options.run_dir))
    throw util::UserError(options.run_dir + ": no such run directory");
  FigurePlan plan = plan_figures(options.run_dir, options.jobs);

  PlotResult result;
  result.figures_dir = rundir::run_folder::figures(options.run_dir);
  result.index_path = rundir::run_folder::figure_index(options.run_dir);
  result.skipped = plan.skipped;

  // Figures of an earlier plot are replaced as a whole: the directory describes the last plot.
  fs::remove_all(result.figures_dir);
  fs::create_directories(result.figures_dir);

  HeadlessDisplay display;
  result.display = display.display();
  result.private_xvfb = display.private_server();
  std::vector<FigureLayout> layouts;
  {
    FigureRenderer renderer;
    std::map<int, std::unique_ptr<FigureRenderer>> short_renderers;  // by height: Figure::height
    const auto renderer_for = [&](const Figure& f) -> FigureRenderer& {
      if (f.height <= 0) return renderer;
      auto& r = short_renderers[f.height];
      if (!r) r = std::make_unique<FigureRenderer>(1123, f.height);
      return *r;
    };
    util::ProgressLine line;  // one line rewritten on a terminal, a line per figure in a log
    for (std::size_t i = 0; i < plan.figures.size(); ++i) {
      const Figure& f = plan.figures[i];
      if (options.progress)
        line.show("[" + std::to_string(i + 1) + "/" + std::to_string(plan.figures.size()) + "] " +
                  f.id);
      const RenderedFigure r = renderer_for(f).render(f, result.figures_dir + "/" + f.id);
      IndexedFigure x{f.id,          figure_kind_name(f), f.section,     f.title,
                      f.caption,     r.note,              f.id + ".png", f.id + ".pdf",
                      f.id + ".csv"};
      layouts.push_back(r.layout);
      result.figures.push_back(std::move(x));
    }
    line.end();
  }
  display.stop();

  result.seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_figure_index(options.run_dir, result, layouts);
  return result;
}

void write_figure_index(const std::string& run_dir, const PlotResult& result,
                        const std::vector<FigureLayout>& layouts) {
  json figures = json::array();
  for (std::size_t i = 0; i < result.figures.size(); ++i)
    figures.push_back(figure_json(result.figures[i], layouts.at(i)));
  json skipped = json::array();
  for (const auto& s : result.skipped)
    skipped.push_back({{"section", s.section}, {"what", s.what}, {"reason", s.reason}});
  json index = rundir::document_header("figure-index", kFigureIndexSchemaVersion, false);
  index["run_dir"] = run_dir;
  index["png_route"] = "VTK: vtkWindowToImageFilter -> vtkPNGWriter";
  index["pdf_route"] = "VTK: vtkPDFExporter (vector)";
  index["display"] = result.private_xvfb ? "private Xvfb " + result.display : result.display;
  index["figures"] = figures;
  index["skipped"] = skipped;
  index["seconds"] = result.seconds;
  util::write_file_atomic(result.index_path, index.dump(2) + "\n");
}

PlotResult read_figure_index(const std::string& run_dir) {
  const std::string path = rundir::run_folder::figure_index(run_dir);
  if (!fs::exists(path))
    throw util::UserError(path + " not found: run `renderaudit plot " + run_dir + "` first");
  PlotResult r;
  r.figures_dir = rundir::run_folder::figures(run_dir);
  r.index_path = path;
  try {
    const json doc = util::parse_json_document(util::read_file(path), path);
    rundir::require_document_header(doc, "figure-index", kFigureIndexSchemaVersion, path,
                                    "run `renderaudit plot " + run_dir + "` again");
    for (const json& f : doc.at("figures"))
      r.figures.push_back({f.at("id"), f.at("kind"), f.value("section", ""), f.value("title", ""),
                           f.value("caption", ""), f.value("note", ""), f.at("png"), f.at("pdf"),
                           f.at("csv")});
    for (const json& s : doc.value("skipped", json::array()))
      r.skipped.push_back({s.value("section", ""), s.value("what", ""), s.value("reason", "")});
    r.display = doc.value("display", "");
    r.seconds = doc.value("seconds", 0.0);
  } catch (const json::exception& e) {
    throw util::UserError(path + ": malformed (" + std::string(e.what()) +
                          "); run `renderaudit plot " + run_dir + "` again");
  }
  return r;
}

}  // namespace ra::plots
