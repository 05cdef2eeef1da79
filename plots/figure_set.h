// Draws a study's figures into DIR/figures/ (STEM.png, STEM.pdf, STEM.csv per figure) and writes
// DIR/figures/index.json, the index `renderaudit report` reads (written by plot_run.h's
// write_figure_index, as `plot` writes it), in drawing order. Each figure is drawn under a temporary name and renamed, so that it is either
// complete or absent; the index is written last. Starts a private Xvfb when DISPLAY is unset.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "plots/figure.h"

namespace ra::plots {

// Returns the paths written. Throws UserError when DIR/figures cannot be created.
std::vector<std::string> write_figure_set(const std::vector<Figure>& figures, const std::string& dir);

// The figures of one study, in drawing order and in one report section: the one way the studies
// (terrain_lod/, regulation/) assemble theirs. Each is added with its words (axis labels with
// units, a caption sentence for the report) and content; write() draws them (write_figure_set).
class StudyFigures {
 public:
  explicit StudyFigures(std::string section) : section_(std::move(section)) {}
  // The figure added, to set a note on it.
  Figure& add(const std::string& id, const std::string& title, const std::string& x_label,
              const std::string& y_label, const std::string& caption, FigureContent content);
  std::vector<std::string> write(const std::string& dir) const {
    return write_figure_set(figures_, dir);
  }

 private:
  std::string section_;
  std::vector<Figure> figures_;
};

// Scatter series by name, in the order the names first appear (one series per lambda, per
// policy, ...).
class SeriesInOrder {
 public:
  ScatterSeries& operator[](const std::string& name);  // a new, empty series on first use
  std::vector<ScatterSeries> series() const;           // in first-use order
  const std::vector<std::string>& names() const { return order_; }

 private:
  std::map<std::string, ScatterSeries> by_name_;
  std::vector<std::string> order_;
};

}  // namespace ra::plots
