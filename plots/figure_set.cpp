// Drawing a study's figures and their index (figure_set.h).
#include "plots/figure_set.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <system_error>

#include "plots/figure_renderer.h"
#include "plots/headless_display.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::plots {

std::vector<std::string> write_figure_set(const std::vector<Figure>& figures, const std::string& dir) {
  std::vector<std::string> written;
  if (figures.empty()) return written;
  const std::string fig_dir = dir + "/figures";
  std::error_code ec;
  std::filesystem::create_directories(fig_dir, ec);
  if (!std::filesystem::is_directory(fig_dir))
    throw util::UserError("cannot create the figure directory " + fig_dir + ": " + ec.message());
  HeadlessDisplay display;
  {
    FigureRenderer renderer;
    for (const Figure& f : figures) {
      const std::string tmp = fig_dir + "/.tmp-" + f.id;
      const RenderedFigure rf = renderer.render(f, tmp);
      for (const std::string& p : {rf.png, rf.pdf, rf.csv}) {
        const std::string final_path = fig_dir + "/" + f.id + p.substr(p.rfind('.'));
        util::commit_file(p, final_path);
        written.push_back(final_path);
      }
    }
  }
  display.stop();
  nlohmann::json index = {{"schema", "renderaudit-figure-index"}, {"schema_version", 1},
                          {"run_dir", dir}, {"figures", nlohmann::json::array()},
                          {"skipped", nlohmann::json::array()}};
  for (const Figure& f : figures)
    index["figures"].push_back({{"id", f.id}, {"kind", figure_kind_name(f)},
                                {"section", f.section}, {"title", f.title},
                                {"caption", f.caption}, {"note", f.note},
                                {"png", f.id + ".png"}, {"pdf", f.id + ".pdf"},
                                {"csv", f.id + ".csv"}});
  util::write_file_atomic(fig_dir + "/index.json", index.dump(2) + "\n");
  written.push_back(fig_dir + "/index.json");
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
