// The paper's published values of its metric tables, as data (experiments/papers/
// nist2008-tables.toml): per table, the view groups A-D (FOV, window) and Platform I and II's
// median and IQR, as printed (metric x 10^scale_exponent). NaN: a cell the extracted paper lost.
// The comparison with a run is paper_comparison_table (paper_tables.h).
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace ra::analysis {

struct PaperTableValues {
  std::string number;  // "3", "4", "6", "7", "9", "10"
  std::string column;  // the records column, e.g. "pe_norm"
  int scale_exponent = 0;
  int page = 0;                                          // 0: not marked in the extracted text
  std::string reading;                                   // how the extracted text was read
  std::array<double, 4> fov_deg{}, window{};             // groups A-D
  std::array<std::array<double, 4>, 2> median{}, iqr{};  // [platform I / II][group]
};

// One established reason why our cells differ from the paper's ([[difference]] in the file): the
// cells it covers (tables, statistics, view groups, platforms whose name contains a text; empty:
// all) and the explanation, with where its evidence is.
struct PaperDifference {
  std::vector<std::string> tables;      // "10", ...; empty: every table
  std::vector<std::string> statistics;  // "median", "IQR"; empty: both
  std::vector<std::string> groups;      // "A" ... "D"; empty: all
  std::string platform_contains;        // "" matches every platform
  std::string explanation;
  bool covers(const std::string& table, const std::string& statistic, const std::string& group,
              const std::string& platform) const;
};

struct PaperValues {
  std::vector<PaperTableValues> tables;
  std::vector<PaperDifference> differences;
  // Primitives per view group behind each of the paper's cells (100,000 per view x 2 views); 0:
  // not given, and z uses our SE alone.
  double primitives_per_view_group = 0;
};

// Parses the file; UserError "FILE:LINE:COLUMN: ..." naming the key on bad input.
PaperValues load_paper_values(const std::string& path);

// experiments/papers/nist2008-tables.toml from the working directory, else from beside the
// program's build folder (BUILD/../experiments/...); "" when neither exists.
std::string default_paper_values_path();

}  // namespace ra::analysis
