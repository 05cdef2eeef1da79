// One fast pass over the records for conformance and non-ok cases (see the header).
#include "plots/record_scan.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "metrics/records_format.h"
#include "util/errors.h"
#include "util/parallel.h"
#include "metrics/records.h"
#include "metrics/records_reader.h"

namespace fs = std::filesystem;

namespace ra::plots {
namespace {

struct Partial {
  RecordScan scan;
  std::vector<NonOkCase> examples;
};

void scan_file(const fs::path& path, const std::string& rel, std::size_t max_examples,
               Partial& out) {
  using C = RecordColumn;
  for_each_record_row(path.string(), [&](const RecordRow& row) {
    ++out.scan.records;
    const std::string platform(row.cell(C::kPlatform)), kind(row.cell(C::kKind));
    const int group = row.integer<int>(C::kViewGroup);
    const auto key = std::make_tuple(platform, kind, group);
    if (!out.scan.group_labels.count(key)) {
      out.scan.group_labels[key] = std::string(row.cell(C::kFovDeg)) + " deg, " +
                                   std::string(row.cell(C::kWidth)) + "x" +
                                   std::string(row.cell(C::kHeight));
    }
    const CaseStatus status = row.status();
    if (status != CaseStatus::kOk) {
      ++out.scan.non_ok_counts[{platform, kind, status_name(status)}];
      if (out.examples.size() < max_examples) {
        out.examples.push_back({platform, kind, status_name(status), row.integer<int>(C::kView),
                                row.integer<std::uint64_t>(C::kIndex), rel,
                                static_cast<std::size_t>(row.line())});
      }
      return;
    }
    if (const std::optional<double> us = row.number(C::kRenderUs)) {
      out.scan.render_us[{platform, kind}].push_back(*us);
      if (row.visibility() == Visibility::kTrueVisible)
        out.scan.render_us_visible[{platform, kind}].push_back(*us);
    }
    if (row.cell(C::kRefDiff).empty()) return;
    const auto diff = row.integer<long long>(C::kRefDiff);
    const auto pixels = row.optional_integer<long long>(C::kPixels, 0);
    Conformance& cf = out.scan.conformance[key];
    ++cf.compared;
    cf.identical += diff == 0;
    ++cf.classes[int(row.conformance())];
    if (pixels > 0 || diff > 0) {
      ++cf.drawn;
      cf.drawn_identical += diff == 0;
    }
  });
}

}  // namespace

RecordScan scan_records(const std::string& run_dir, std::size_t max_examples, unsigned jobs) {
  const fs::path dir = fs::path(run_dir) / "records";
  if (!fs::is_directory(dir)) throw UserError(run_dir + ": no records directory (" + dir.string() + ")");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file() && ra::is_records_file_name(e.path().filename().string())) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  if (files.empty()) throw UserError(dir.string() + ": no records files (*.csv)");

  std::vector<Partial> parts(files.size());
  run_in_parallel(files.size(), jobs, [&](std::size_t i) {
    scan_file(files[i], fs::relative(files[i], run_dir).string(), max_examples, parts[i]);
  });

  RecordScan out;
  out.files = files.size();
  for (auto& p : parts) {
    out.records += p.scan.records;
    for (const auto& [k, v] : p.scan.conformance) {
      Conformance& cf = out.conformance[k];
      cf.compared += v.compared;
      cf.identical += v.identical;
      cf.drawn += v.drawn;
      cf.drawn_identical += v.drawn_identical;
      for (int c = 0; c < 5; ++c) cf.classes[c] += v.classes[c];
    }
    for (const auto& [k, v] : p.scan.non_ok_counts) out.non_ok_counts[k] += v;
    for (const auto& [k, v] : p.scan.group_labels) out.group_labels.emplace(k, v);
    for (auto& [k, v] : p.scan.render_us) {
      auto& all = out.render_us[k];
      all.insert(all.end(), v.begin(), v.end());
    }
    for (auto& [k, v] : p.scan.render_us_visible) {
      auto& all = out.render_us_visible[k];
      all.insert(all.end(), v.begin(), v.end());
    }
    for (auto& e : p.examples)
      if (out.non_ok_examples.size() < max_examples) out.non_ok_examples.push_back(std::move(e));
  }
  return out;
}

}  // namespace ra::plots
