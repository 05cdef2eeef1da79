#include "analysis/conformance_summary.h"

#include <algorithm>
#include <filesystem>

#include "analysis/run_records.h"
#include "rundir/records_reader.h"
#include "stats/table_writer.h"
#include "util/program_name.h"
#include "util/shell_quote.h"

namespace ra::analysis {

void ConformanceTally::select_group(std::string_view platform, std::string_view kind, int group) {
  if (group == std::get<2>(key_) && platform == std::get<0>(key_) && kind == std::get<1>(key_))
    return;
  key_ = GroupKey{std::string(platform), std::string(kind), group};
  counts_ = nullptr;
  reference_ = nullptr;
}

void ConformanceTally::add(const rundir::RecordRow& row) {
  using C = metrics::RecordColumn;
  ConformanceSummary& s = summary_;
  select_group(row.cell(C::kPlatform), row.cell(C::kKind), row.integer<int>(C::kViewGroup));
  const auto& [platform, kind, group] = key_;
  if (!s.group_labels.count(key_))
    s.group_labels[key_] = std::string(row.cell(C::kFovDeg)) + " deg, " +
                           std::string(row.cell(C::kWidth)) + "x" +
                           std::string(row.cell(C::kHeight));
  const metrics::CaseStatus status = row.status();
  if (status != metrics::CaseStatus::kOk) {
    ++s.non_ok_counts[{platform, kind, metrics::status_name(status)}];
    if (s.non_ok_examples.size() < kNonOkExamples)
      s.non_ok_examples.push_back({platform, kind, metrics::status_name(status),
                                   row.integer<int>(C::kView),
                                   row.integer<std::uint64_t>(C::kIndex), file_,
                                   static_cast<std::uint64_t>(row.line())});
    return;
  }
  if (!row.cell(C::kRefDiff).empty()) {
    const auto diff = row.integer<long long>(C::kRefDiff);
    const auto pixels = row.optional_integer<long long>(C::kPixels, 0);
    if (reference_ == nullptr) reference_ = &s.reference[key_];
    ReferenceAgreement& r = *reference_;
    ++r.compared;
    r.identical += diff == 0;
    if (pixels > 0 || diff > 0) {
      ++r.drawn;
      r.drawn_identical += diff == 0;
    }
  }
  const metrics::Conformance c = row.conformance();
  if (c == metrics::Conformance::kNotCompared) {
    ++s.not_compared;
    return;
  }
  if (counts_ == nullptr) counts_ = &s.groups[key_];
  ConformanceCounts& n = *counts_;
  ++n.compared;
  switch (c) {
    case metrics::Conformance::kExact: ++n.exact; break;
    case metrics::Conformance::kSnapped: ++n.snapped; break;
    case metrics::Conformance::kWithinSpec: ++n.within_spec; break;
    case metrics::Conformance::kViolation: ++n.violation; break;
    case metrics::Conformance::kNotCompared: break;
  }
  if (c != metrics::Conformance::kViolation) return;
  Violation v{platform, kind, row.integer<int>(C::kView), group,
              row.integer<std::uint64_t>(C::kIndex),
              row.optional_integer<std::int64_t>(C::kViolatingPixels, 0),
              std::string(row.cell(C::kViolatedRules))};
  n.violating_pixels += std::uint64_t(std::max<std::int64_t>(v.violating_pixels, 0));
  std::string_view rules = v.rules;
  while (!rules.empty()) {  // '+'-joined
    const std::size_t plus = rules.find('+');
    ++n.rules[std::string(rules.substr(0, plus))];
    rules = plus == std::string_view::npos ? std::string_view() : rules.substr(plus + 1);
  }
  s.violations.push_back(std::move(v));
}

void append_conformance(ConformanceSummary& into, ConformanceSummary&& later) {
  for (auto& [key, n] : later.groups) {
    ConformanceCounts& to = into.groups[key];
    to.compared += n.compared;
    to.exact += n.exact;
    to.snapped += n.snapped;
    to.within_spec += n.within_spec;
    to.violation += n.violation;
    to.violating_pixels += n.violating_pixels;
    for (const auto& [rule, count] : n.rules) to.rules[rule] += count;
  }
  for (auto& v : later.violations) into.violations.push_back(std::move(v));
  into.not_compared += later.not_compared;
  for (const auto& [key, r] : later.reference) {
    ReferenceAgreement& to = into.reference[key];
    to.compared += r.compared;
    to.identical += r.identical;
    to.drawn += r.drawn;
    to.drawn_identical += r.drawn_identical;
  }
  for (auto& [key, label] : later.group_labels)
    into.group_labels.try_emplace(key, std::move(label));  // the first file's label stays
  for (const auto& [key, count] : later.non_ok_counts) into.non_ok_counts[key] += count;
  for (auto& e : later.non_ok_examples) {
    if (into.non_ok_examples.size() >= kNonOkExamples) break;
    into.non_ok_examples.push_back(std::move(e));
  }
}

void finish_conformance(ConformanceSummary& s) {
  std::sort(s.violations.begin(), s.violations.end(), [](const Violation& a, const Violation& b) {
    return std::tie(b.violating_pixels, a.platform, a.kind, a.view, a.index) <
           std::tie(a.violating_pixels, b.platform, b.kind, b.view, b.index);
  });
}

ConformanceSummary summarize_conformance(const std::vector<std::string>& records_files,
                                         const std::string& run_dir) {
  ConformanceSummary s;
  for (const std::string& path : records_files) {
    ConformanceTally file(run_dir.empty()
                              ? path
                              : std::filesystem::path(path).lexically_relative(run_dir).string());
    rundir::for_each_record_row(path, [&](const rundir::RecordRow& row) { file.add(row); });
    append_conformance(s, file.take());
  }
  finish_conformance(s);
  return s;
}

stats::Table conformance_table(const ConformanceSummary& s) {
  stats::Table t;
  t.file_stem = "conformance";
  t.title = "Conformance with the OpenGL rasterization rules: share of records (%) per class, "
            "with Clopper-Pearson 95% intervals";
  t.notes = {
      "exact: the pixels equal the exact reference rasterizer's; snapped: they equal the "
      "reference with vertices snapped to the platform's effective subpixel grid (measured, "
      "drivers/PLATFORM.json); within-spec: neither, but every differing pixel is one GL allows "
      "(polygons: centre within the snapping and rounding allowance of an edge; lines: the rules "
      "of GL 4.6 section 14.5.1; points: the pixel of a snapped position); violation: at least "
      "one pixel no conforming implementation could light or leave dark.",
      "violating px: the sum of violating_pixels; rules: how many records broke each rule "
      "(metrics/conformance.h names them). Records of the reference platform and records "
      "written before schema version 3 carry no verdict and are not counted."};
  for (const auto& [key, n] : s.groups)
    if (std::get<0>(key).rfind("vk-", 0) == 0) {
      t.notes.push_back(
          "Vulkan platforms (vk-*) are judged by the Vulkan rules: points and polygons as GL's; "
          "default lines on a device with strictLines as 1 px wide rectangles (reference and "
          "allowance of the rectangle, rule line-rectangle); Bresenham lines by GL's line rules "
          "(docs/vulkan.md).");
      break;
    }
  t.columns = {{"platform", stats::Align::kLeft}, {"kind", stats::Align::kLeft}, {"group", stats::Align::kLeft},
               {"records"}, {"exact %"}, {"snapped %"}, {"within-spec %"}, {"violation %"},
               {"violating px"}, {"rules broken", stats::Align::kLeft}};
  for (const auto& [key, n] : s.groups) {
    const auto& [platform, kind, group] = key;
    std::string rules;
    for (const auto& [rule, count] : n.rules)
      rules += (rules.empty() ? "" : ", ") + rule + " " + std::to_string(count);
    t.rows.push_back({stats::text_cell(platform), stats::text_cell(kind), stats::text_cell(view_group_label(group)),
                      stats::count_cell(n.compared), stats::share_cell(n.exact, n.compared),
                      stats::share_cell(n.snapped, n.compared), stats::share_cell(n.within_spec, n.compared),
                      stats::share_cell(n.violation, n.compared), stats::count_cell(n.violating_pixels),
                      stats::text_cell(rules.empty() ? "-" : rules)});
  }
  if (t.rows.empty()) t.notes.push_back("No record of this run carries a conformance verdict.");
  return t;
}

std::string violations_markdown(const ConformanceSummary& s, const std::string& run_dir,
                                std::size_t limit) {
  std::string md = "# Conformance violations\n\n";
  if (s.violations.empty()) {
    std::uint64_t compared = 0;
    for (const auto& [key, n] : s.groups) compared += n.compared;
    return md + "None: every one of the " + std::to_string(compared) +
           " records with a verdict is exact, snapped or within the GL rules.\n";
  }
  md += std::to_string(s.violations.size()) +
        " records break a GL rasterization rule (metrics/conformance.h). Worst first" +
        (s.violations.size() > limit ? " (the first " + std::to_string(limit) + ")" : "") +
        "; `renderaudit show` draws one (black: the violating pixels).\n\n";
  using stats::Align;
  md += stats::markdown_header(
      {"platform", "kind", "view", "index", "violating px", "rules", "draw it"},
      {Align::kLeft, Align::kLeft, Align::kRight, Align::kRight, Align::kRight, Align::kLeft,
       Align::kLeft});
  for (std::size_t i = 0; i < s.violations.size() && i < limit; ++i) {
    const Violation& v = s.violations[i];
    md += "| " + v.platform + " | " + v.kind + " | " + std::to_string(v.view) + " | " +
          std::to_string(v.index) + " | " + std::to_string(v.violating_pixels) + " | " + v.rules +
          " | `" + util::program_for_commands() + " " +
          util::shell_command({"show", run_dir, "-p", v.platform, "-k", v.kind, "-v",
                               std::to_string(v.view), "-i", std::to_string(v.index)}) +
          "` |\n";
  }
  return md;
}

}  // namespace ra::analysis
