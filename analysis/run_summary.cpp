#include "analysis/run_summary.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <tuple>
#include <vector>

#include "geometry/primitive.h"
#include "metrics/headline_metric.h"
#include "metrics/records.h"
#include "rundir/manifest.h"
#include "rundir/records_format.h"
#include "rundir/records_reader.h"
#include "rundir/run_folder.h"
#include "stats/descriptive.h"
#include "stats/table_writer.h"
#include "util/atomic_file.h"
#include "util/number_text.h"

namespace fs = std::filesystem;

namespace ra::analysis {
namespace {

struct Cell {
  std::array<uint64_t, 5> visibility{};
  uint64_t not_ok = 0, conformant = 0, compared = 0;
  std::vector<double> metric, render_us;
  std::string fov, window;
};

// What the run cost against the drivers' own drawing: the sum of render_us, and, when the last
// invocation ran every shard, wall time x jobs / drawing (1 = nothing but drawing) and the
// core-seconds no worker used. "" when the manifest lacks what it needs.
template <typename Cells>
std::string cost_paragraph(const std::string& run_dir, const Cells& cells) {
  double drawing_us = 0;
  for (const auto& [key, c] : cells)
    for (double us : c.render_us) drawing_us += us;
  rundir::RunManifest m;
  try {
    m = rundir::read_manifest_file(rundir::run_folder::manifest(run_dir));
  } catch (const std::exception&) {
    return "";
  }
  const rundir::ManifestInvocation* inv = m.last_invocation();
  std::ostringstream out;
  out << "\nDrawing (the sum of render_us): " << util::fixed(drawing_us / 1e6, 1) << " s";
  if (inv && inv->elapsed_s && m.shards && inv->shards_to_run == m.shards->total &&
      drawing_us > 0) {
    const double elapsed = *inv->elapsed_s, jobs = double(inv->jobs);
    out << "; this invocation ran every shard in " << util::fixed(elapsed, 1) << " s on " << jobs
        << " jobs, which is " << util::fixed(elapsed * jobs / (drawing_us / 1e6), 1)
        << " times the drivers' own drawing time (wall time x jobs over the drawing: the rest is "
           "starting workers, measuring and writing records)";
    if (inv->idle_core_s)
      out << ", " << util::fixed(*inv->idle_core_s, 1) << " core-seconds without a worker (shard order: "
          << (inv->shard_order.empty() ? "?" : inv->shard_order) << ")";
  }
  out << ".\n";
  return out.str();
}

}  // namespace

std::string write_run_summary(const std::string& run_dir) {
  using Key = std::tuple<std::string, std::string, int>;  // platform, kind, view
  std::map<Key, Cell> cells;
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(rundir::run_folder::records(run_dir)))
    if (ra::rundir::is_records_file_name(e.path().filename().string()))
      files.push_back(e.path().string());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    rundir::read_records(f, [&](const metrics::Record& r) {
      Cell& c = cells[{r.platform, r.kind, r.view}];
      c.fov = util::significant(r.fov_deg, 6);
      c.window = std::to_string(r.width) + "x" + std::to_string(r.height);
      if (r.status != metrics::CaseStatus::kOk) {
        ++c.not_ok;
        return;
      }
      ++c.visibility[int(r.visibility)];
      const std::optional<geometry::Kind> kind =
          geometry::parse_kind(r.kind, geometry::KindSpelling::kName);
      const double metric = kind ? metrics::summary_metric_value(r, *kind) : metrics::kNA;
      if (r.visibility == metrics::Visibility::kTrueVisible && !std::isnan(metric))
        c.metric.push_back(metric);
      if (!std::isnan(r.render_us)) c.render_us.push_back(r.render_us);
      if (r.ref_diff >= 0) {
        ++c.compared;
        c.conformant += r.ref_diff == 0;
      }
    });
  }

  std::ostringstream md;
  md << "# Run summary: " << run_dir << "\n\n"
     << "Counts of the visibility classes (paper, section 3.4), the median and IQR (Hyndman-Fan "
        "6)\n"
     << "of each kind's headline metric over true-visible cases, the share of cases whose pixels\n"
     << "equal the reference rasterizer's, and the median render time (draw + glFinish).\n\n"
     << "| platform | kind | view | FOV | window | true-vis | true-invis | false-vis | false-invis "
        "| multiple | invalid/failed | metric | median | IQR | ref-equal | median us |\n"
     << stats::markdown_compact_rule(16);
  for (auto& [key, c] : cells) {
    const auto& [platform, kind, view] = key;
    md << "| " << platform << " | " << kind << " | " << view << " | " << c.fov << " | " << c.window;
    for (uint64_t n : c.visibility) md << " | " << n;
    const std::optional<geometry::Kind> k =
        geometry::parse_kind(kind, geometry::KindSpelling::kName);
    md << " | " << c.not_ok << " | " << (k ? metrics::summary_metric_label(*k) : "n/a") << " | ";
    if (c.metric.empty()) {
      md << "n/a | n/a";
    } else {
      const stats::Description d = stats::describe(c.metric);
      md << util::significant(d.median, 5) << " | " << util::significant(d.iqr, 5);
    }
    md << " | " << (c.compared ? util::format_double("%.2f%%", 100.0 * c.conformant / c.compared) : "n/a");
    md << " | " << (c.render_us.empty() ? "n/a" : util::fixed(stats::describe(c.render_us).median, 1))
       << " |\n";
  }
  md << cost_paragraph(run_dir, cells);
  util::write_file_atomic(rundir::run_folder::summary(run_dir), md.str());
  return md.str();
}

}  // namespace ra::analysis
