// Test support for the analysis-stage tests (included by analysis/*_test.cpp only): synthetic
// records with the views of the paper's Table 1, written as a run directory with ra::write_record.
#pragma once

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "rundir/run_folder.h"
#include "stats/stats_testing.h"
#include "analysis/paper_values.h"
#include "metrics/records.h"

namespace ra::analysis::testing {

// A fresh temporary directory (stats::testing::temp_dir) removed when the test ends.
struct ScopedTempDir {
  explicit ScopedTempDir(const std::string& tag) : path(stats::testing::temp_dir(tag)) {}
  ~ScopedTempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  ScopedTempDir(const ScopedTempDir&) = delete;
  ScopedTempDir& operator=(const ScopedTempDir&) = delete;
  std::filesystem::path path;
};

// The paper's Table 1: views 1-8, orientation innermost, then FOV (30, 150), then window (128,
// 907).
inline void set_view(metrics::Record& r, int view) {
  const int v = view - 1;
  r.view = view;
  r.orientation = v % 2 + 1;
  r.view_group = v / 2;
  r.fov_deg = (v / 2) % 2 ? 150 : 30;
  r.width = r.height = v / 4 ? 907 : 128;
  r.near = 0.01;
  r.far = 10;
}

// A point record; true-visible ones carry pe (pixels) and pe_norm = pe / sqrt(W*H).
inline metrics::Record point(const std::string& platform, int view, std::uint64_t index, double pe,
                    metrics::Visibility visibility = metrics::Visibility::kTrueVisible,
                    metrics::CaseStatus status = metrics::CaseStatus::kOk) {
  metrics::Record r;
  r.platform = platform;
  set_view(r, view);
  r.kind = "point";
  r.index = index;
  r.status = status;
  r.visibility = visibility;
  r.pixels = visibility == metrics::Visibility::kTrueVisible ? 1 : 0;
  if (visibility == metrics::Visibility::kTrueVisible && status == metrics::CaseStatus::kOk) {
    r.pe = pe;
    r.pe_norm = pe / r.width;
  }
  r.render_us = 10 + static_cast<double>(index % 7);
  return r;
}

// A line record whose metric cells are empty (a runner that does not measure lines yet).
inline metrics::Record unmeasured_line(const std::string& platform, int view, std::uint64_t index) {
  metrics::Record r;
  r.platform = platform;
  set_view(r, view);
  r.kind = "line";
  r.index = index;
  r.visibility = metrics::Visibility::kTrueVisible;
  r.pixels = 10;
  r.render_us = 5;
  return r;
}

// Writes `records` as RUN/records/NAME with the records header; returns the file's path.
inline std::string write_records(const std::filesystem::path& run,
                                 const std::vector<metrics::Record>& records,
                                 const std::string& name = "x.csv") {
  const std::filesystem::path folder = rundir::run_folder::records(run.string());
  std::filesystem::create_directories(folder);
  const auto path = folder / name;
  std::ofstream out(path);
  out << metrics::records_header() << "\n";
  for (const metrics::Record& r : records) write_record(out, r);
  return path.string();
}

// The run of the paper-comparison tests: group A of platform "p1" with PE {0.30, 0.10, 0.45, 0.20}
// (view 1) and {0.25, 0.60, 0.05, 0.50, 0.40} (view 2): HF6 median 0.30, IQR 0.325.
inline void write_nine_point_run(const std::filesystem::path& run) {
  std::vector<metrics::Record> rs;
  std::uint64_t i = 0;
  for (double x : {0.30, 0.10, 0.45, 0.20}) rs.push_back(point("p1", 1, i++, x));
  for (double x : {0.25, 0.60, 0.05, 0.50, 0.40}) rs.push_back(point("p1", 2, i++, x));
  write_records(run, rs);
}

// The paper's Table 3 (PE) with only group A's cells given, Platform I and II; the rest NaN.
inline PaperTableValues table3_group_a(double median_1, double median_2, double iqr_1,
                                       double iqr_2) {
  const double nan = std::nan("");
  PaperTableValues t;
  t.number = "3";
  t.column = "pe";
  t.fov_deg = {30, 150, 30, 150};
  t.window = {128, 128, 907, 907};
  t.median = {std::array<double, 4>{median_1, nan, nan, nan}, {median_2, nan, nan, nan}};
  t.iqr = {std::array<double, 4>{iqr_1, nan, nan, nan}, {iqr_2, nan, nan, nan}};
  t.reading = "by hand";
  return t;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  for (char c : text) {
    if (c == '\n') {
      lines.push_back(line);
      line.clear();
    } else {
      line += c;
    }
  }
  if (!line.empty()) lines.push_back(line);
  return lines;
}

}  // namespace ra::analysis::testing
