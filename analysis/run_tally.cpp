// The run's tally for plot and report, and figures.json read back; see run_tally.h.
#include "analysis/run_tally.h"

#include <filesystem>

#include "rundir/manifest.h"
#include "rundir/run_folder.h"
#include "stats/descriptive.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"

namespace ra::analysis {

using nlohmann::json;

namespace {

json group_json(const GroupKey& key) {
  return {{"platform", std::get<0>(key)},
          {"kind", std::get<1>(key)},
          {"view_group", view_group_label(std::get<2>(key))},
          {"view_group_index", std::get<2>(key)}};
}

GroupKey group_key(const json& j) {
  return {j.at("platform").get<std::string>(), j.at("kind").get<std::string>(),
          j.at("view_group_index").get<int>()};
}

// Render times per platform and kind: every view's ok records with a time, true-visible or not.
std::map<std::pair<std::string, std::string>, RenderTime> render_times(const RunRecords& run) {
  // each view's samples are ascending (ViewData), so the pooled ones are merged, not sorted
  using Samples = std::vector<const std::vector<double>*>;
  std::map<std::pair<std::string, std::string>, std::pair<Samples, Samples>> us;  // all, visible
  for (const auto& [key, view] : run.views) {
    auto& [all, visible] = us[{run.platforms[key.platform], kind_name(key.kind)}];
    all.push_back(&view.render_us_visible);
    all.push_back(&view.render_us_other);
    visible.push_back(&view.render_us_visible);
  }
  std::map<std::pair<std::string, std::string>, RenderTime> out;
  using stats::QuantileDefinition;
  for (const auto& [key, samples] : us) {
    const std::vector<double> all = merge_sorted(samples.first);
    if (all.empty()) continue;
    const std::vector<double> visible = merge_sorted(samples.second);
    RenderTime& t = out[key];
    t.cases = all.size();
    t.median_us = stats::quantile_sorted(all, 0.5);
    t.iqr_us = stats::quantile_sorted(all, 0.75, QuantileDefinition::kHyndmanFan6) -
               stats::quantile_sorted(all, 0.25, QuantileDefinition::kHyndmanFan6);
    t.true_visible = visible.size();
    if (!visible.empty()) t.median_us_true_visible = stats::quantile_sorted(visible, 0.5);
  }
  return out;
}

}  // namespace

RunTally tally_run(const RunRecords& run, const ConformanceSummary& conformance) {
  RunTally t;
  t.records = run.record_count;
  t.files = run.files.size();
  t.verdicts = conformance.groups;
  for (auto& [key, n] : t.verdicts) n.rules.clear();
  t.reference = conformance.reference;
  t.group_labels = conformance.group_labels;
  t.non_ok_counts = conformance.non_ok_counts;
  t.non_ok_examples = conformance.non_ok_examples;
  t.render_time = render_times(run);
  return t;
}

json tally_json(const RunTally& t) {
  json groups = json::array();
  for (const auto& [key, label] : t.group_labels) {
    json g = group_json(key);
    g["label"] = label;
    if (const auto r = t.reference.find(key); r != t.reference.end())
      g["reference"] = {{"compared", r->second.compared},
                        {"identical", r->second.identical},
                        {"drawn", r->second.drawn},
                        {"drawn_identical", r->second.drawn_identical}};
    if (const auto v = t.verdicts.find(key); v != t.verdicts.end())
      g["verdicts"] = {
          {"judged", v->second.compared},     {"exact", v->second.exact},
          {"snapped", v->second.snapped},     {"within_spec", v->second.within_spec},
          {"violation", v->second.violation}, {"violating_pixels", v->second.violating_pixels}};
    groups.push_back(std::move(g));
  }
  json non_ok = json::array();
  for (const auto& [key, n] : t.non_ok_counts)
    non_ok.push_back({{"platform", std::get<0>(key)},
                      {"kind", std::get<1>(key)},
                      {"status", std::get<2>(key)},
                      {"records", n}});
  json examples = json::array();
  for (const NonOkCase& x : t.non_ok_examples)
    examples.push_back({{"platform", x.platform},
                        {"kind", x.kind},
                        {"status", x.status},
                        {"view", x.view},
                        {"index", x.index},
                        {"file", x.file},
                        {"line", x.line}});
  json times = json::array();
  for (const auto& [key, r] : t.render_time)
    times.push_back({{"platform", key.first},
                     {"kind", key.second},
                     {"cases", r.cases},
                     {"median_us", r.median_us},
                     {"iqr_us", r.iqr_us},
                     {"true_visible", r.true_visible},
                     {"median_us_true_visible",
                      r.median_us_true_visible ? json(*r.median_us_true_visible) : json()}});
  json doc = rundir::document_header("tally", kTallySchemaVersion, false);
  doc.update({{"records", t.records},
              {"files", t.files},
              {"groups", groups},
              {"non_ok", non_ok},
              {"non_ok_examples", examples},
              {"render_time", times}});
  return doc;
}

RunTally read_tally(const std::string& run_dir) {
  const std::string path = rundir::run_folder::tally(run_dir);
  if (!std::filesystem::exists(path))
    throw util::UserError(path + " not found: run `renderaudit analyze " + run_dir + "` first");
  json j;
  try {
    j = util::parse_json_document(util::read_file(path), path);
  } catch (const json::exception& e) {
    throw util::UserError(path + ": not valid JSON: " + e.what() + " (run `renderaudit analyze " +
                    run_dir + "` again)");
  }
  rundir::require_document_header(j, "tally", kTallySchemaVersion, path,
                                  "run `renderaudit analyze " + run_dir + "` again");
  RunTally t;
  try {
    t.records = j.at("records").get<std::uint64_t>();
    t.files = j.at("files").get<std::uint64_t>();
    for (const json& g : j.at("groups")) {
      const GroupKey key = group_key(g);
      t.group_labels[key] = g.at("label").get<std::string>();
      if (g.contains("reference")) {
        const json& r = g["reference"];
        t.reference[key] = {
            r.at("compared").get<std::uint64_t>(), r.at("identical").get<std::uint64_t>(),
            r.at("drawn").get<std::uint64_t>(), r.at("drawn_identical").get<std::uint64_t>()};
      }
      if (g.contains("verdicts")) {
        const json& v = g["verdicts"];
        ConformanceCounts& n = t.verdicts[key];
        n.compared = v.at("judged").get<std::uint64_t>();
        n.exact = v.at("exact").get<std::uint64_t>();
        n.snapped = v.at("snapped").get<std::uint64_t>();
        n.within_spec = v.at("within_spec").get<std::uint64_t>();
        n.violation = v.at("violation").get<std::uint64_t>();
        n.violating_pixels = v.at("violating_pixels").get<std::uint64_t>();
      }
    }
    for (const json& n : j.at("non_ok"))
      t.non_ok_counts[{n.at("platform").get<std::string>(), n.at("kind").get<std::string>(),
                       n.at("status").get<std::string>()}] = n.at("records").get<std::uint64_t>();
    for (const json& x : j.at("non_ok_examples"))
      t.non_ok_examples.push_back(
          {x.at("platform").get<std::string>(), x.at("kind").get<std::string>(),
           x.at("status").get<std::string>(), x.at("view").get<int>(),
           x.at("index").get<std::uint64_t>(), x.at("file").get<std::string>(),
           x.at("line").get<std::uint64_t>()});
    for (const json& r : j.at("render_time")) {
      RenderTime& rt =
          t.render_time[{r.at("platform").get<std::string>(), r.at("kind").get<std::string>()}];
      rt.cases = r.at("cases").get<std::uint64_t>();
      rt.median_us = r.at("median_us").get<double>();
      rt.iqr_us = r.at("iqr_us").get<double>();
      rt.true_visible = r.at("true_visible").get<std::uint64_t>();
      if (!r.at("median_us_true_visible").is_null())
        rt.median_us_true_visible = r["median_us_true_visible"].get<double>();
    }
  } catch (const json::exception& e) {
    throw util::UserError(path + ": unexpected content: " + e.what() +
                          " (run `renderaudit analyze " + run_dir + "` again)");
  }
  return t;
}

}  // namespace ra::analysis
