// The shared part of the figure families (figure_planner.h).
#include "plots/figure_planner.h"

#include <cctype>
#include <cstdio>

#include "analysis/paper_tables.h"
#include "util/number_text.h"

namespace ra::plots {

void FigurePlanner::add(Figure f) {
  f.id = sanitize_id(f.id);
  std::string id = f.id;
  for (int k = 2; ids.count(id); ++k) id = f.id + "_" + std::to_string(k);
  f.id = id;
  ids.insert(id);
  plan.figures.push_back(std::move(f));
}

void FigurePlanner::skip(const std::string& section, const std::string& what, const std::string& reason) {
  plan.skipped.push_back({section, what, reason});
}

std::string FigurePlanner::group_label(const an::ViewGroup& g) const {
  return g.label + ": " + util::significant(g.meta().fov_deg, 6) + " deg, " + std::to_string(g.meta().width) +
         "x" + std::to_string(g.meta().height);
}

std::string sanitize_id(const std::string& s) {
  std::string out;
  for (char c : s) {
    const char l = char(std::tolower(static_cast<unsigned char>(c)));
    out += (std::isalnum(static_cast<unsigned char>(l)) || l == '.' || l == '-' || l == '_') ? l : '_';
  }
  return out;
}

// The x 10^k the paper's tables use for a metric column; -1 when no table shows it.
int table_exponent(const std::string& column) {
  for (const auto& spec : an::metric_table_specs())
    if (column == spec.column) return spec.scale_exponent;
  return -1;
}

// "PEnorm x 10^3 (sqrt(W*H) units)": the numbers on the axis are the metric times 10^k.
std::string axis_label(const std::string& symbol, const std::string& units, int exponent) {
  std::string s = symbol;
  if (exponent > 0) s += " x 10^" + std::to_string(exponent);
  return s + " (" + units + ")";
}

std::string views_text(const nlohmann::json& views) {
  std::string s;
  for (std::size_t i = 0; i < views.size(); ++i) s += (i ? ", " : "") + views[i].dump();
  return s;
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

// "A-D" or "A" or "A, C".
std::string groups_text(const std::vector<std::string>& labels) {
  if (labels.empty()) return "";
  if (labels.size() == 1) return labels[0];
  bool consecutive = true;
  for (std::size_t i = 1; i < labels.size(); ++i)
    consecutive = consecutive && an::view_group_label(int(i)) == labels[i] &&
                  an::view_group_label(0) == labels[0];
  return consecutive ? labels.front() + "-" + labels.back() : join(labels, ", ");
}

std::string groups_phrase(const std::vector<std::string>& labels) {
  return (labels.size() == 1 ? "view group " : "view groups ") + groups_text(labels);
}

std::string box_plot_title(const std::string& symbol, const BoxPlotContent& content) {
  if (content.boxes.size() <= 1) return "Box plot of " + symbol;
  const bool groups = content.categories.size() > 1, platforms = content.series.size() > 1;
  return "Box plots of " + symbol +
         (groups && platforms ? " by view group and platform"
          : groups            ? " by view group"
          : platforms         ? " by platform"
                              : "");
}

const char* section_of(geometry::Kind kind) { return an::kind_label_plural(kind); }

}  // namespace ra::plots
