// `renderaudit history [--db FILE] [--last N] [--out DIR] [--metric NAME...]`: the recent audits
// of the history database (audit/history_db.h) as a table, and a trend figure per metric
// (plots/trend_figure.h) as PNG + PDF + CSV.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "app/commands.h"
#include "audit/history_db.h"
#include "stats/change_points.h"
#include "stats/descriptive.h"
#include "plots/trend_figure.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::app {
namespace {

struct HistoryOptions {
  std::string db;  // named explicitly: the working directory says nothing about which history
  std::size_t last = 20;
  std::string out_dir;  // empty: DIR-of-db/history
  std::vector<std::string> metrics;
};

// Left-aligned text columns, numbers right-aligned, two spaces apart.
std::string text_table(const std::vector<std::vector<std::string>>& rows,
                       const std::vector<bool>& right) {
  std::vector<std::size_t> width(rows.front().size(), 0);
  for (const auto& r : rows)
    for (std::size_t c = 0; c < r.size(); ++c) width[c] = std::max(width[c], r[c].size());
  std::string out;
  for (const auto& r : rows) {
    std::string line;
    for (std::size_t c = 0; c < r.size(); ++c) {
      const std::string pad(width[c] - r[c].size(), ' ');
      line += (c ? "  " : "") + (right[c] ? pad + r[c] : r[c] + pad);
    }
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out += line + "\n";
  }
  return out;
}

// The folders of a run's path, the last one last ("/srv/runs/n-2/" -> srv, runs, n-2).
std::vector<std::string> folders(const std::string& run) {
  std::vector<std::string> out;
  for (const fs::path& part : fs::path(run).lexically_normal())
    if (!part.empty() && part != "/" && part != ".") out.push_back(part.string());
  return out;
}

// The last `n` folders of `f`, joined with '/'.
std::string last_folders(const std::vector<std::string>& f, std::size_t n) {
  std::string s;
  for (std::size_t i = f.size() - std::min(n, f.size()); i < f.size(); ++i)
    s += (s.empty() ? "" : "/") + f[i];
  return s;
}

// How the table names an audit's current and baseline run: the run folder's name, with the folder
// above it where the name is "run" (a night of `renderaudit watch` keeps its run in
// nights/<UTC>/run), and more of the path until the two names differ. An audit of two platforms of
// one run (`audit --between`) has the same folder on both sides: its baseline reads "same run", the
// platforms being in the compares column.
std::pair<std::string, std::string> run_labels(const std::string& current,
                                               const std::string& baseline) {
  const std::vector<std::string> c = folders(current), b = folders(baseline);
  if (c.empty() || b.empty())
    return {c.empty() ? current : last_folders(c, 1), b.empty() ? baseline : last_folders(b, 1)};
  auto start = [](const std::vector<std::string>& f) -> std::size_t {
    return f.back() == "run" ? 2 : 1;
  };
  std::size_t nc = start(c), nb = start(b);
  if (c == b) return {last_folders(c, nc), "same run"};
  while (last_folders(c, nc) == last_folders(b, nb) && (nc < c.size() || nb < b.size()))
    ++nc, ++nb;
  return {last_folders(c, nc), last_folders(b, nb)};
}

// What an audit compared: a run with its baseline ("two runs", what `make nightly` appends), or two
// platforms of one run (`audit --between`: the same directory on both sides), "P1 vs P2".
std::string compares_text(const audit::AuditSummary& s) {
  if (s.verdict == audit::Verdict::kBaseline) return "nothing (baseline recorded)";
  if (s.baseline_run != s.current_run) return "two runs";
  auto platforms = [](const std::vector<audit::DriverIdentity>& drivers) {
    std::string p;
    for (const audit::DriverIdentity& d : drivers) p += (p.empty() ? "" : ",") + d.platform;
    return p.empty() ? std::string("?") : p;
  };
  return platforms(s.baseline_drivers) + " vs " + platforms(s.current_drivers);
}

std::string drivers_text(const std::vector<audit::DriverIdentity>& drivers) {
  std::string s;
  for (const audit::DriverIdentity& d : drivers)
    s += (s.empty() ? "" : "; ") + d.platform + ": " + d.renderer + ", " + d.version;
  return s.empty() ? "(none recorded)" : s;
}

// View group 1..4 is A..D (audit_summary.h).
std::string group_name(int view_group) {
  return view_group >= 1 && view_group <= 26 ? std::string(1, char('A' + view_group - 1))
                                             : std::to_string(view_group);
}

std::string figure_id(const std::string& metric) {
  std::string id = "trend_";
  for (char c : metric) {
    const char l = char(std::tolower(static_cast<unsigned char>(c)));
    id += (std::isalnum(static_cast<unsigned char>(l)) || l == '.' || l == '-') ? l : '_';
  }
  return id;
}

// One trend per metric: a series per platform x kind x view group, a point per audit.
std::vector<plots::TrendData> trends(const std::vector<audit::HistoryEntry>& h,
                                     const std::vector<std::string>& metrics) {
  std::vector<plots::TrendData> out;
  for (const std::string& metric : metrics) {
    plots::TrendData t;
    t.id = figure_id(metric);
    t.metric = metric;
    std::map<std::tuple<std::string, std::string, int>, plots::TrendSeries> series;
    for (std::size_t a = 0; a < h.size(); ++a) {
      t.audits.push_back("#" + std::to_string(h[a].id));
      t.dates.push_back(h[a].summary.date_utc);
      for (const audit::MetricSummary& m : h[a].summary.metrics) {
        if (m.metric != metric) continue;
        plots::TrendSeries& s = series[{m.platform, m.kind, m.view_group}];
        s.name = m.platform + " " + m.kind + " " + group_name(m.view_group);
        s.points.push_back({a, m.median, m.iqr, uint64_t(std::max<int64_t>(0, m.n))});
      }
    }
    for (auto& [key, s] : series) t.series.push_back(std::move(s));
    out.push_back(std::move(t));
  }
  return out;
}

// Drawing time per platform x kind x view group over the audits that timed it (`audit --speed`):
// the current side's median render_us, and the nights where it stepped (stats/change_points.h,
// on log times: a step is a ratio). Printed, and drawn as one more trend (no IQR is stored: each
// box is flat).
struct SpeedSeries {
  std::string name;
  std::vector<std::size_t> audits;  // index into the history shown
  std::vector<double> median_us;
  std::vector<stats::ChangePoint> changes;  // index into audits / median_us
};

std::vector<SpeedSeries> speed_series(const std::vector<audit::HistoryEntry>& h) {
  std::map<std::tuple<std::string, std::string, int>, SpeedSeries> series;
  for (std::size_t a = 0; a < h.size(); ++a)
    for (const audit::SpeedSummary& s : h[a].summary.speed) {
      if (!(s.current_median_us > 0)) continue;
      SpeedSeries& x = series[{s.platform, s.kind, s.view_group}];
      x.name = s.platform + " " + s.kind + " " + group_name(s.view_group);
      x.audits.push_back(a);
      x.median_us.push_back(s.current_median_us);
    }
  std::vector<SpeedSeries> out;
  for (auto& [key, x] : series) {
    std::vector<double> logs;
    for (double t : x.median_us) logs.push_back(std::log(t));
    x.changes = stats::e_divisive(logs);
    out.push_back(std::move(x));
  }
  return out;
}

void print_speed_series(const std::vector<audit::HistoryEntry>& h,
                        const std::vector<SpeedSeries>& series) {
  if (series.empty()) return;
  std::printf("\ndrawing time (median render_us of the timed sample, per audit with --speed; change "
              "points: E-Divisive on log time, at least 3 audits a side, p < 0.01):\n");
  for (const SpeedSeries& x : series) {
    std::printf("  %s: %zu audits, %.4g us last", x.name.c_str(), x.audits.size(),
                x.median_us.back());
    if (x.changes.empty()) std::printf("; no change point\n");
    for (std::size_t c = 0; c < x.changes.size(); ++c) {
      const std::size_t at = x.changes[c].index;
      const std::size_t from = c ? x.changes[c - 1].index : 0;
      const std::size_t to = c + 1 < x.changes.size() ? x.changes[c + 1].index : x.audits.size();
      auto median_of = [&](std::size_t b, std::size_t e) {
        std::vector<double> v(x.median_us.begin() + long(b), x.median_us.begin() + long(e));
        return stats::median(v);
      };
      const double before = median_of(from, at), after = median_of(at, to);
      std::printf("; step at #%lld (%s): %.4g -> %.4g us (%.3fx, p %.3g)",
                  static_cast<long long>(h[x.audits[at]].id),
                  h[x.audits[at]].summary.date_utc.c_str(), before, after, after / before,
                  x.changes[c].p_value);
    }
    if (!x.changes.empty()) std::printf("\n");
  }
}

plots::TrendData speed_trend(const std::vector<audit::HistoryEntry>& h,
                             const std::vector<SpeedSeries>& series) {
  plots::TrendData t;
  t.id = "trend_render_us";
  t.metric = "render_us";
  for (const audit::HistoryEntry& e : h) {
    t.audits.push_back("#" + std::to_string(e.id));
    t.dates.push_back(e.summary.date_utc);
  }
  std::string changes;
  for (const SpeedSeries& x : series) {
    plots::TrendSeries s;
    s.name = x.name;
    for (std::size_t i = 0; i < x.audits.size(); ++i)
      s.points.push_back({x.audits[i], x.median_us[i], NAN, 0});
    for (const stats::ChangePoint& c : x.changes)
      changes += (changes.empty() ? "" : ", ") + x.name + " at #" +
                 std::to_string(h[x.audits[c.index]].id);
    t.series.push_back(std::move(s));
  }
  t.note = "Drawing time: the median render_us (microseconds) of the sample `audit --speed` "
           "drew on the current side; no IQR is kept, so each box is a line. Change points "
           "(E-Divisive, at least 3 audits a side, p < 0.01): " +
           (changes.empty() ? std::string("none") : changes) + ".";
  return t;
}

// The nights of `renderaudit watch`, when the database holds any: one line each, its culprits
// below it.
void print_nights(const HistoryOptions& o) {
  const std::vector<audit::NightEntry> nights = audit::read_nights(o.db, o.last);
  if (nights.empty()) return;
  std::printf("%zu night%s of renderaudit watch (the last ones):\n\n", nights.size(),
              nights.size() == 1 ? "" : "s");
  std::vector<std::vector<std::string>> rows = {{"night", "date (UTC)", "commit", "verdict", "note"}};
  for (const audit::NightEntry& n : nights)
    rows.push_back({"#" + std::to_string(n.id), n.date_utc, n.commit.substr(0, 12), n.verdict,
                    n.note.size() > 100 ? n.note.substr(0, 97) + "..." : n.note});
  const std::string table = text_table(rows, {true, false, false, false, false});
  std::size_t line = 0;
  for (std::size_t at = 0; at < table.size(); ++line) {
    const std::size_t nl = table.find('\n', at);
    std::printf("%s\n", table.substr(at, nl - at).c_str());
    at = nl + 1;
    if (line == 0) continue;
    const std::string& culprits = nights[line - 1].culprits;
    for (std::size_t c = 0; c < culprits.size();) {
      const std::size_t end = std::min(culprits.find('\n', c), culprits.size());
      std::printf("        culprit: %s\n", culprits.substr(c, end - c).c_str());
      c = end + 1;
    }
  }
  std::printf("\n");
}

void run_history(const HistoryOptions& o, int& exit_code) {
  print_nights(o);
  const std::vector<audit::HistoryEntry> h = audit::read_history(o.db, o.last);
  const int64_t total = audit::history_audit_count(o.db);
  std::printf("%s: %lld audit%s", o.db.c_str(), static_cast<long long>(total),
              total == 1 ? "" : "s");
  if (h.empty()) {
    std::printf(" (nothing to show yet: `renderaudit audit` appends one per run)\n");
    exit_code = kExitOk;
    return;
  }
  std::printf(", the last %zu:\n\n", h.size());

  std::vector<std::vector<std::string>> rows = {{"id", "date (UTC)", "verdict", "changed", "flaky",
                                                 "failed", "tests", "compares", "current run",
                                                 "baseline run"}};
  const std::vector<bool> right = {true, false, false, true, true, true, true, false, false, false};
  for (const audit::HistoryEntry& e : h) {
    const audit::AuditSummary& s = e.summary;
    // a baseline night compared nothing: no counts of changes or tests
    const bool compared = s.verdict != audit::Verdict::kBaseline;
    auto count = [&](int64_t n) { return compared ? std::to_string(n) : std::string("-"); };
    const auto [current, baseline] = run_labels(s.current_run, s.baseline_run);
    rows.push_back({"#" + std::to_string(e.id), s.date_utc, audit::verdict_name(s.verdict),
                    count(s.changed_primitives), count(s.flaky_primitives),
                    std::to_string(s.failed_primitives), count(s.significant_tests),
                    compares_text(s), current, baseline});
  }
  std::printf("%s", text_table(rows, right).c_str());
  std::printf(
      "\n(changed: primitives whose pixels changed and stayed changed on re-render; flaky: "
      "changed only once; failed: crash or timeout records; tests: distribution tests "
      "rejected; compares: a run against its baseline, or two platforms of one run; a baseline "
      "night compares nothing; same run: the baseline side is the current run, two of its "
      "platforms or a baseline night)\n\ndrivers "
      "(current run; baseline when it differs):\n");
  for (const audit::HistoryEntry& e : h) {
    const audit::AuditSummary& s = e.summary;
    std::printf("  #%lld  %s\n", static_cast<long long>(e.id),
                drivers_text(s.current_drivers).c_str());
    const std::string base = drivers_text(s.baseline_drivers);
    if (base != drivers_text(s.current_drivers))
      std::printf("  %*s  baseline: %s\n", int(std::to_string(e.id).size()) + 1, "", base.c_str());
  }

  const std::vector<SpeedSeries> speed = speed_series(h);
  print_speed_series(h, speed);

  // Metrics to draw: those asked for, or every metric in the audits shown, in first-seen order.
  std::vector<std::string> present;
  for (const audit::HistoryEntry& e : h)
    for (const audit::MetricSummary& m : e.summary.metrics)
      if (std::find(present.begin(), present.end(), m.metric) == present.end())
        present.push_back(m.metric);
  std::vector<std::string> metrics = o.metrics.empty() ? present : o.metrics;
  for (const std::string& m : metrics)
    if (std::find(present.begin(), present.end(), m) == present.end()) {
      std::string list;
      for (const std::string& p : present) list += (list.empty() ? "" : ", ") + p;
      throw util::UserError("no metric '" + m + "' in the last " + std::to_string(h.size()) +
                            " audits of " + o.db + " (present: " + (list.empty() ? "none" : list) +
                            ")");
    }
  if (metrics.empty()) {
    std::printf("\nno metric summaries in these audits: no trend figures\n");
    exit_code = kExitOk;
    return;
  }
  const std::string out_dir =
      o.out_dir.empty() ? (fs::path(o.db).parent_path() / "history").string() : o.out_dir;
  std::vector<plots::TrendData> all = trends(h, metrics);
  if (!speed.empty()) all.push_back(speed_trend(h, speed));
  const std::vector<plots::RenderedFigure> figures = plots::draw_trend_figures(all, out_dir);
  std::printf("\ntrend figures (median and IQR per platform, kind and view group) in %s:\n",
              out_dir.c_str());
  for (const plots::RenderedFigure& f : figures)
    std::printf("  %s  (+ .pdf, .csv)\n", f.png.c_str());
  exit_code = kExitOk;
}

}  // namespace

void register_history_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "history",
      "The audit history: the recent audits (date, verdict, runs, drivers, changed / flaky /\n"
      "failed counts) as a table, and a trend figure per metric (median and IQR per platform,\n"
      "kind and view group, over the audits) as PNG + vector PDF + CSV. Needs no display.");
  struct Options {
    HistoryOptions o;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  cmd->add_option("--db", opts->o.db,
                  "history database: `audit` appends to history.sqlite beside the run it audits "
                  "(outputs/history.sqlite for outputs/RUN); `make nightly` to "
                  "outputs/nightly/history.sqlite")
      ->required();
  cmd->add_option("--last,-n", opts->o.last, "show the last N audits (default: 20)")
      ->check(CLI::Range(std::size_t(1), std::size_t(1000000)));
  cmd->add_option("--out,-o", opts->o.out_dir,
                  "directory for the trend figures (default: the db's directory /history)");
  cmd->add_option("--metric,-m", opts->o.metrics,
                  "records column to draw, e.g. te_u (repeatable; default: every metric stored)");
  cmd->callback([opts, &exit_code] { run_history(opts->o, exit_code); });
}

}  // namespace ra::app
