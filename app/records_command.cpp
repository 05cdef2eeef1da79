// `renderaudit records RUN [--platform P] [--kind K] [--view V] [--columns C,...] [--format F]`:
// one stream of a run's records on stdout, filtered, for a notebook or a shell pipe (no globbing,
// no decompressing shard files by hand). Shards are taken in the plan's order (platform, view,
// kind, first primitive), from either file format; the cells are copied as the files hold them,
// so every number is the recorded text. The seal lines are not repeated: the stream is not a
// shard file.
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/run_completeness.h"
#include "app/commands.h"
#include "metrics/records.h"
#include "rundir/experiment.h"
#include "rundir/records_format.h"
#include "rundir/records_reader.h"
#include "rundir/run_experiment.h"
#include "rundir/run_folder.h"
#include "rundir/shard.h"
#include "rundir/shard_file.h"
#include "rundir/shard_records.h"
#include "util/errors.h"
#include "util/shell_quote.h"
#include "util/standard_output.h"
#include "util/zstd_stream.h"

namespace ra::app {
namespace {

struct RecordsOptions {
  std::string dir;
  std::vector<std::string> platforms, kinds, columns;
  std::vector<int> views;
  std::string format = "csv";
  bool allow_incomplete = false;
};

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// Each name must be one of `allowed`; the error names the option and what is allowed.
void check_names(const std::vector<std::string>& names, const std::vector<std::string>& allowed,
                 const std::string& option, const std::string& dir) {
  for (const std::string& n : names)
    if (std::find(allowed.begin(), allowed.end(), n) == allowed.end())
      throw util::UserError(option + " " + n + ": not in run " + dir +
                            " (allowed: " + joined(allowed) + ")");
}

template <typename T>
bool wanted(const std::vector<T>& filter, const T& value) {
  return filter.empty() || std::find(filter.begin(), filter.end(), value) != filter.end();
}

void stream_records(const RecordsOptions& o) {
  const std::string toml = rundir::run_folder::experiment(o.dir);
  if (!std::filesystem::exists(toml))
    throw util::UserError(o.dir +
                          ": no experiment.toml (expected a run directory written by "
                          "`renderaudit run`)");
  const rundir::Experiment exp = rundir::load_run_experiment(o.dir);
  const std::optional<rundir::RecordsFormat> format = rundir::parse_records_format(o.format);
  if (!format) throw util::UserError("--format " + o.format + ": unknown (allowed: csv, csv.zst)");
  if (*format == rundir::RecordsFormat::kCsvZst && ::isatty(STDOUT_FILENO))
    throw util::UserError("--format csv.zst writes compressed bytes: redirect or pipe stdout");

  check_names(o.platforms, exp.platforms, "--platform", o.dir);
  check_names(o.kinds, {"point", "line", "triangle"}, "--kind", o.dir);
  std::vector<std::string> view_ids;
  for (const geometry::View& v : exp.views) view_ids.push_back(std::to_string(v.id));
  std::vector<std::string> asked_views;
  for (int v : o.views) asked_views.push_back(std::to_string(v));
  check_names(asked_views, view_ids, "--view", o.dir);
  std::vector<metrics::RecordColumn> columns;
  std::vector<std::string> all_columns;
  for (std::size_t c = 0; c < metrics::kRecordColumnCount; ++c)
    all_columns.push_back(metrics::record_column_name(static_cast<metrics::RecordColumn>(c)));
  for (const std::string& name : o.columns) {
    const std::optional<metrics::RecordColumn> c = metrics::find_record_column(name);
    if (!c)
      throw util::UserError("--columns " + name +
                            ": no such records column (allowed: " + joined(all_columns) + ")");
    if (std::find(columns.begin(), columns.end(), *c) != columns.end())
      throw util::UserError("--columns " + name + ": named twice (each column once)");
    columns.push_back(*c);
  }
  if (columns.empty())
    for (std::size_t c = 0; c < metrics::kRecordColumnCount; ++c)
      columns.push_back(static_cast<metrics::RecordColumn>(c));

  // The selection's shards, and those of them the run lacks: an incomplete stream is refused
  // before anything is written unless asked for, as every statistic over an incomplete run is.
  std::vector<rundir::Shard> selected;
  std::set<std::string> planned;  // ids of the shards the run is meant to hold
  for (const rundir::Shard& s : rundir::planned_shards_of_run(o.dir, exp)) planned.insert(s.id());
  std::vector<std::string> missing;
  for (const rundir::Shard& s : rundir::plan_shards(exp)) {
    if (!wanted(o.platforms, s.platform) ||
        !wanted(o.kinds, std::string(geometry::kind_name(s.kind))) || !wanted(o.views, s.view))
      continue;
    const bool present = !rundir::find_shard_records(o.dir, s, false).path.empty();
    if (!present && planned.count(s.id())) missing.push_back(s.id());
    if (present) selected.push_back(s);
  }
  if (!missing.empty() && !o.allow_incomplete)
    throw analysis::IncompleteRunError(
        o.dir + ": incomplete: " + std::to_string(missing.size()) +
        " planned shards of the selection have no records file (" + missing.front() +
        (missing.size() > 1 ? ", ..." : "") +
        "), so the stream would not be the run's records. Finish the run (the same `renderaudit "
        "run` command; `renderaudit status " + o.dir + "` says why), or pass --allow-incomplete "
        "to stream the records it holds");

  // Written to the descriptor directly, so that a reader gone (`| head`) stops the stream at
  // once and a full disk is said with its cause (util/standard_output.h).
  std::ostringstream compressed;
  std::unique_ptr<util::ZstdFrameWriter> zstd;
  if (*format == rundir::RecordsFormat::kCsvZst)
    zstd = std::make_unique<util::ZstdFrameWriter>(compressed);
  std::string text;  // written out every few MiB (one zstd frame each)
  const auto flush = [&] {
    if (zstd) {
      zstd->write(text);
      zstd->end_frame();
      util::write_stdout(compressed.str(), "the records");
      compressed.str("");
    } else {
      util::write_stdout(text, "the records");
    }
    text.clear();
  };
  for (std::size_t i = 0; i < columns.size(); ++i)
    text += (i ? "," : "") + std::string(metrics::record_column_name(columns[i]));
  text += '\n';
  for (const rundir::Shard& s : selected) {
    const std::string path = rundir::trusted_records_path(o.dir, s);  // read once to judge it
    if (path.empty()) continue;  // removed since
    rundir::for_each_record_row(path, [&](const rundir::RecordRow& row) {
      for (std::size_t i = 0; i < columns.size(); ++i) {
        if (i) text += ',';
        text += row.cell(columns[i]);
      }
      text += '\n';
      if (text.size() >= (std::size_t{4} << 20)) flush();
    });
  }
  flush();
  if (!missing.empty())
    std::fprintf(stderr,
                 "renderaudit: records: incomplete run: %zu planned shards of the selection have "
                 "no records file (`renderaudit status %s` says why)\n",
                 missing.size(), util::shell_quote(o.dir).c_str());
}

}  // namespace

void register_records_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "records",
      "A run's records as one CSV stream on stdout (header first), filtered by platform, kind\n"
      "and view, with the columns asked for; plain or zstd-compressed (docs/records.md).");
  struct Options {
    RecordsOptions o;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("dir", opts->o.dir, "run directory")->required()->check(CLI::ExistingDirectory);
  cmd->add_option("--platform", opts->o.platforms, "only this platform (repeatable)");
  cmd->add_option("--kind", opts->o.kinds, "only this kind: point, line, triangle (repeatable)");
  cmd->add_option("--view", opts->o.views, "only this view id (repeatable)");
  cmd->add_option("--columns", opts->o.columns, "these columns, in this order (comma-separated)")
      ->delimiter(',');
  cmd->add_option("--format", opts->o.format, "csv (default) or csv.zst");
  cmd->add_flag("--allow-incomplete", opts->o.allow_incomplete,
                "stream the records of a run with missing shards (said on stderr); without it "
                "such a run is refused with exit code 3 before anything is written");
  cmd->callback([opts, &exit_code] {
    try {
      stream_records(opts->o);
    } catch (const analysis::IncompleteRunError& e) {
      std::fprintf(stderr, "renderaudit records: %s\n", e.what());
      exit_code = kExitIncomplete;
      return;
    }
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
