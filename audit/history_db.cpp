// The audit history in SQLite (history_db.h): append in one transaction, snapshot reads.
#include "audit/history_db.h"

#include <algorithm>
#include <optional>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <system_error>
#include <utility>

#include "audit/history_sqlite.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::audit {

using history_sqlite::check_schema;
using history_sqlite::Connection;
using history_sqlite::create_or_migrate;
using history_sqlite::open_existing;
using history_sqlite::open_for_append;
using history_sqlite::SchemaState;
using history_sqlite::Statement;

void append_night(const std::string& db_path, const NightEntry& n) {
  Connection c = open_for_append(db_path, kHistoryBusyTimeoutMs);
  c.exec("BEGIN IMMEDIATE", "cannot begin writing the history");
  create_or_migrate(c);
  Statement s(c,
              "INSERT INTO nights (date_utc, source, commit_hash, previous_commit, verdict, "
              "culprits, run_dir, note) VALUES (?, ?, ?, ?, ?, ?, ?, ?)");
  s.bind(1, n.date_utc).bind(2, n.source).bind(3, n.commit).bind(4, n.previous_commit);
  s.bind(5, n.verdict).bind(6, n.culprits).bind(7, n.run_dir).bind(8, n.note);
  s.run_once();
  c.exec("COMMIT", "cannot commit the history");
}

std::vector<NightEntry> read_nights(const std::string& db_path, std::size_t last) {
  Connection c = open_existing(db_path);
  c.exec("BEGIN", "cannot read the history");
  std::vector<NightEntry> out;
  const SchemaState state = check_schema(c);
  if (state == SchemaState::kEmpty || state == SchemaState::kVersion1) return out;
  Statement s(c,
              "SELECT id, date_utc, source, commit_hash, previous_commit, verdict, culprits, "
              "run_dir, note FROM (SELECT * FROM nights ORDER BY id DESC LIMIT ?) ORDER BY id");
  s.bind(1, last == 0 ? int64_t(-1) : int64_t(last));
  while (s.step())
    out.push_back({s.integer(0), s.text(1), s.text(2), s.text(3), s.text(4), s.text(5),
                   s.text(6), s.text(7), s.text(8)});
  return out;
}

std::string default_history_path(const std::string& current_run_dir) {
  const std::filesystem::path run = std::filesystem::absolute(current_run_dir).lexically_normal();
  return ((run.has_filename() ? run : run.parent_path()).parent_path() / "history.sqlite").string();
}

void append_history(const std::string& db_path, const AuditSummary& s) {
  append_history(db_path, s, AppendOptions{});
}

int64_t append_history(const std::string& db_path, const AuditSummary& s,
                       const AppendOptions& options) {
  Connection c = open_for_append(db_path, options.busy_timeout_ms);
  if (options.cache_pages > 0) c.exec("PRAGMA cache_size = " + std::to_string(options.cache_pages));

  // IMMEDIATE: take the write lock now, waiting up to the busy timeout for another appender.
  c.exec("BEGIN IMMEDIATE", "cannot begin writing the history");
  create_or_migrate(c);

  Statement audit(c,
                  "INSERT INTO audits (date_utc, experiment, experiment_hash, seed, baseline_run, "
                  "current_run, verdict, changed_primitives, flaky_primitives, failed_primitives, "
                  "significant_tests) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11)");
  audit.bind(1, s.date_utc)
      .bind(2, s.experiment)
      .bind(3, s.experiment_hash)
      .bind(4, std::to_string(s.seed))
      .bind(5, s.baseline_run)
      .bind(6, s.current_run)
      .bind(7, std::string(verdict_name(s.verdict)))
      .bind(8, s.changed_primitives)
      .bind(9, s.flaky_primitives)
      .bind(10, s.failed_primitives)
      .bind(11, s.significant_tests);
  audit.run_once();
  const int64_t id = sqlite3_last_insert_rowid(c.get());

  std::size_t rows = 0;
  auto written = [&] {
    ++rows;
    if (options.after_row) options.after_row(rows);
  };
  Statement driver(c,
                   "INSERT INTO drivers (audit_id, role, platform, renderer, version) "
                   "VALUES (?1, ?2, ?3, ?4, ?5)");
  for (const auto& [role, list] :
       {std::pair<std::string, const std::vector<DriverIdentity>*>{"baseline", &s.baseline_drivers},
        {"current", &s.current_drivers}}) {
    for (const DriverIdentity& d : *list) {
      driver.bind(1, id).bind(2, role).bind(3, d.platform).bind(4, d.renderer).bind(5, d.version);
      driver.run_once();
      written();
    }
  }
  // One prepared INSERT, run once for each of `list`, `bind` giving a row's values after audit_id.
  const auto insert_each = [&](const char* sql, const auto& list, const auto& bind) {
    Statement insert(c, sql);
    for (const auto& row : list) {
      bind(insert.bind(1, id), row);
      insert.run_once();
      written();
    }
  };
  insert_each(
      "INSERT INTO metrics (audit_id, platform, kind, view_group, metric, n, median, "
      "iqr) VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8)",
      s.metrics, [](Statement& st, const MetricSummary& m) {
        st.bind(2, m.platform).bind(3, m.kind).bind(4, int64_t(m.view_group));
        st.bind(5, m.metric).bind(6, m.n).bind_real(7, m.median).bind_real(8, m.iqr);
      });
  insert_each(
      "INSERT INTO classes (audit_id, platform, kind, view_group, visibility, count) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6)",
      s.classes, [](Statement& st, const ClassCount& k) {
        st.bind(2, k.platform).bind(3, k.kind).bind(4, int64_t(k.view_group));
        st.bind(5, k.visibility).bind(6, k.count);
      });
  insert_each(
      "INSERT INTO speed (audit_id, platform, baseline_platform, kind, view_group, n, ratio, low, "
      "high, baseline_median_us, current_median_us, verdict) "
      "VALUES (?1, ?2, ?3, ?4, ?5, ?6, ?7, ?8, ?9, ?10, ?11, ?12)",
      s.speed, [](Statement& st, const SpeedSummary& x) {
        st.bind(2, x.platform).bind(3, x.baseline_platform).bind(4, x.kind);
        st.bind(5, int64_t(x.view_group)).bind(6, x.n).bind_real(7, x.ratio);
        st.bind_real(8, x.low).bind_real(9, x.high).bind_real(10, x.baseline_median_us);
        st.bind_real(11, x.current_median_us).bind(12, x.verdict);
      });
  c.exec("COMMIT", "cannot commit the audit to the history");
  return id;
}

std::vector<HistoryEntry> read_history(const std::string& db_path, std::size_t last) {
  Connection c = open_existing(db_path);
  // One read transaction: the audits and their rows come from the same snapshot.
  c.exec("BEGIN", "cannot read the history");
  std::vector<HistoryEntry> out;
  if (check_schema(c) == SchemaState::kEmpty) {
    c.exec("COMMIT");
    return out;
  }
  {
    Statement a(c,
                "SELECT id, date_utc, experiment, experiment_hash, seed, baseline_run, "
                "current_run, verdict, changed_primitives, flaky_primitives, failed_primitives, "
                "significant_tests FROM audits ORDER BY id DESC LIMIT ?1");
    a.bind(1, last == 0 ? int64_t(-1) : int64_t(last));  // LIMIT -1: no limit
    while (a.step()) {
      HistoryEntry e;
      e.id = a.integer(0);
      AuditSummary& s = e.summary;
      s.date_utc = a.text(1);
      s.experiment = a.text(2);
      s.experiment_hash = a.text(3);
      s.seed = std::strtoull(a.text(4).c_str(), nullptr, 10);
      s.baseline_run = a.text(5);
      s.current_run = a.text(6);
      if (!parse_verdict(a.text(7), &s.verdict))
        throw util::UserError(db_path + ": audit " + std::to_string(e.id) +
                              " has an unknown verdict '" + a.text(7) + "'");
      s.changed_primitives = a.integer(8);
      s.flaky_primitives = a.integer(9);
      s.failed_primitives = a.integer(10);
      s.significant_tests = a.integer(11);
      out.push_back(std::move(e));
    }
  }
  std::reverse(out.begin(), out.end());

  // Child rows in the order they were appended (rowid order).
  Statement d(c,
              "SELECT role, platform, renderer, version FROM drivers WHERE audit_id = ?1 "
              "ORDER BY rowid");
  Statement m(c,
              "SELECT platform, kind, view_group, metric, n, median, iqr FROM metrics "
              "WHERE audit_id = ?1 ORDER BY rowid");
  Statement k(c,
              "SELECT platform, kind, view_group, visibility, count FROM classes "
              "WHERE audit_id = ?1 ORDER BY rowid");
  // A database from before the speed table has no speed rows to read.
  const bool has_speed = c.pragma_int("user_version") >= 4;
  std::optional<Statement> sp;
  if (has_speed)
    sp.emplace(c,
               "SELECT platform, baseline_platform, kind, view_group, n, ratio, low, high, "
               "baseline_median_us, current_median_us, verdict FROM speed WHERE audit_id = ?1 "
               "ORDER BY rowid");
  for (HistoryEntry& e : out) {
    if (sp) {
      sp->bind(1, e.id);
      while (sp->step()) {
        SpeedSummary x;
        x.platform = sp->text(0);
        x.baseline_platform = sp->text(1);
        x.kind = sp->text(2);
        x.view_group = int(sp->integer(3));
        x.n = sp->integer(4);
        x.ratio = sp->real(5);
        x.low = sp->real(6);
        x.high = sp->real(7);
        x.baseline_median_us = sp->real(8);
        x.current_median_us = sp->real(9);
        x.verdict = sp->text(10);
        e.summary.speed.push_back(std::move(x));
      }
      sp->reset();
    }
    d.bind(1, e.id);
    while (d.step()) {
      DriverIdentity x{d.text(1), d.text(2), d.text(3)};
      (d.text(0) == "baseline" ? e.summary.baseline_drivers : e.summary.current_drivers)
          .push_back(std::move(x));
    }
    d.reset();
    m.bind(1, e.id);
    while (m.step()) {
      MetricSummary x;
      x.platform = m.text(0);
      x.kind = m.text(1);
      x.view_group = int(m.integer(2));
      x.metric = m.text(3);
      x.n = m.integer(4);
      x.median = m.real(5);
      x.iqr = m.real(6);
      e.summary.metrics.push_back(std::move(x));
    }
    m.reset();
    k.bind(1, e.id);
    while (k.step()) {
      ClassCount x;
      x.platform = k.text(0);
      x.kind = k.text(1);
      x.view_group = int(k.integer(2));
      x.visibility = k.text(3);
      x.count = k.integer(4);
      e.summary.classes.push_back(std::move(x));
    }
    k.reset();
  }
  c.exec("COMMIT");
  return out;
}

int64_t history_audit_count(const std::string& db_path) {
  Connection c = open_existing(db_path);
  c.exec("BEGIN", "cannot read the history");
  int64_t n = 0;
  if (check_schema(c) != SchemaState::kEmpty) {
    Statement s(c, "SELECT count(*) FROM audits");
    if (s.step()) n = s.integer(0);
  }
  c.exec("COMMIT");
  return n;
}

std::string history_integrity(const std::string& db_path) {
  Connection c = open_existing(db_path);
  std::string problems;
  {
    Statement s(c, "PRAGMA integrity_check");
    while (s.step())
      if (s.text(0) != "ok") problems += s.text(0) + "\n";
  }
  {
    Statement s(c, "PRAGMA foreign_key_check");
    while (s.step())
      problems += "table " + s.text(0) + " row " + std::to_string(s.integer(1)) +
                  ": no parent row in " + s.text(2) + "\n";
  }
  return problems.empty() ? "ok" : problems;
}

}  // namespace ra::audit
