// Drawing a study's figures and their index (figure_set.h).
#include "plots/figure_set.h"

#include <chrono>
#include <filesystem>
#include <system_error>

#include "plots/figure_renderer.h"
#include "plots/headless_display.h"
#include "plots/plot_run.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::plots {

std::vector<std::string> write_figure_set(const std::vector<Figure>& figures, const std::string& dir) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<std::string> written;
  if (figures.empty()) return written;
  PlotResult result;
  result.figures_dir = rundir::run_folder::figures(dir);
  result.index_path = rundir::run_folder::figure_index(dir);
  std::error_code ec;
  std::filesystem::create_directories(result.figures_dir, ec);
  if (!std::filesystem::is_directory(result.figures_dir))
    throw util::UserError("cannot create the figure directory " + result.figures_dir + ": " +
                          ec.message());
  HeadlessDisplay display;
  result.display = display.display();
  result.private_xvfb = display.private_server();
  std::vector<FigureLayout> layouts;
  {
    FigureRenderer renderer;
    for (const Figure& f : figures) {
      const std::string tmp = result.figures_dir + "/.tmp-" + f.id;
      const RenderedFigure rf = renderer.render(f, tmp);
      for (const std::string& p : {rf.png, rf.pdf, rf.csv}) {
        const std::string final_path = result.figures_dir + "/" + f.id + p.substr(p.rfind('.'));
        util::commit_file(p, final_path);
        written.push_back(final_path);
      }
      // The figure's own note, as the studies' indexes always had (the regulation study's scatter
      // notes name the points the renderer also names in the drawn note).
      result.figures.push_back({f.id, figure_kind_name(f), f.section, f.title, f.caption, f.note,
                                f.id + ".png", f.id + ".pdf", f.id + ".csv"});
      layouts.push_back(rf.layout);
    }
  }
  display.stop();
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  write_figure_index(dir, result, layouts);
  written.push_back(result.index_path);
  return written;
}

Figure& StudyFigures::add(const std::string& id, const std::string& title,
                          const std::string& x_label, const std::string& y_label,
                          const std::string& caption, FigureContent content) {
  Figure f;
  f.id = id;
  f.title = title;
  f.x_label = x_label;
  f.y_label = y_label;
  f.caption = caption;
  f.section = section_;
  f.content = std::move(content);
  figures_.push_back(std::move(f));
  return figures_.back();
}

ScatterSeries& SeriesInOrder::operator[](const std::string& name) {
  auto it = by_name_.find(name);
  if (it == by_name_.end()) {
    order_.push_back(name);
    it = by_name_.emplace(name, ScatterSeries{}).first;
    it->second.name = name;
  }
  return it->second;
}

std::vector<ScatterSeries> SeriesInOrder::series() const {
  std::vector<ScatterSeries> out;
  for (const std::string& n : order_) out.push_back(by_name_.at(n));
  return out;
}

}  // namespace ra::plots
