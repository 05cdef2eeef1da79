// The audit history in SQLite (history_db.h): schema, append in one transaction, snapshot reads.
#include "audit/history_db.h"

#include <sqlite3.h>

#include <algorithm>
#include <optional>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <system_error>
#include <utility>

#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::audit {
namespace {

// Marks the file as ours in its header (PRAGMA application_id): "RAHD".
constexpr int32_t kApplicationId = 0x52414844;

constexpr const char* kSchemaSql = R"sql(
CREATE TABLE audits (
  id INTEGER PRIMARY KEY,
  date_utc TEXT NOT NULL,
  experiment TEXT NOT NULL,
  experiment_hash TEXT NOT NULL,
  seed TEXT NOT NULL,
  baseline_run TEXT NOT NULL,
  current_run TEXT NOT NULL,
  verdict TEXT NOT NULL CHECK (verdict IN ('unchanged', 'changed', 'failed', 'baseline')),
  changed_primitives INTEGER NOT NULL,
  flaky_primitives INTEGER NOT NULL,
  failed_primitives INTEGER NOT NULL,
  significant_tests INTEGER NOT NULL
);
CREATE TABLE drivers (
  audit_id INTEGER NOT NULL REFERENCES audits(id),
  role TEXT NOT NULL CHECK (role IN ('baseline', 'current')),
  platform TEXT NOT NULL,
  renderer TEXT NOT NULL,
  version TEXT NOT NULL,
  UNIQUE (audit_id, role, platform)
);
CREATE TABLE metrics (
  audit_id INTEGER NOT NULL REFERENCES audits(id),
  platform TEXT NOT NULL,
  kind TEXT NOT NULL,
  view_group INTEGER NOT NULL,
  metric TEXT NOT NULL,
  n INTEGER NOT NULL,
  median REAL,
  iqr REAL,
  UNIQUE (audit_id, platform, kind, view_group, metric)
);
CREATE TABLE classes (
  audit_id INTEGER NOT NULL REFERENCES audits(id),
  platform TEXT NOT NULL,
  kind TEXT NOT NULL,
  view_group INTEGER NOT NULL,
  visibility TEXT NOT NULL,
  count INTEGER NOT NULL,
  UNIQUE (audit_id, platform, kind, view_group, visibility)
);
CREATE INDEX metrics_by_series ON metrics (metric, platform, kind, view_group);
)sql";

// Added in schema version 2.
constexpr const char* kNightsSql = R"sql(
CREATE TABLE nights (
  id INTEGER PRIMARY KEY,
  date_utc TEXT NOT NULL,
  source TEXT NOT NULL,
  commit_hash TEXT NOT NULL,
  previous_commit TEXT NOT NULL,
  verdict TEXT NOT NULL,
  culprits TEXT NOT NULL,
  run_dir TEXT NOT NULL,
  note TEXT NOT NULL
);
)sql";

// Added in schema version 4.
constexpr const char* kSpeedSql = R"sql(
CREATE TABLE IF NOT EXISTS speed (
  audit_id INTEGER NOT NULL REFERENCES audits(id),
  platform TEXT NOT NULL,
  baseline_platform TEXT NOT NULL,
  kind TEXT NOT NULL,
  view_group INTEGER NOT NULL,
  n INTEGER NOT NULL,
  ratio REAL,
  low REAL,
  high REAL,
  baseline_median_us REAL,
  current_median_us REAL,
  verdict TEXT NOT NULL,
  UNIQUE (audit_id, platform, kind, view_group)
);
)sql";

// Schema version 3 lets an audit row be a baseline night (verdict 'baseline'). A file of an
// earlier version has the narrower check; widening a CHECK constraint changes no stored row, so
// SQLite's documented way for such a change applies: the table's CREATE text rewritten in
// sqlite_schema and the schema version bumped, in the caller's write transaction
// (https://www.sqlite.org/lang_altertable.html#otheralter).
constexpr const char* kVerdictCheckBefore3 = "CHECK (verdict IN ('unchanged', 'changed', 'failed'))";
constexpr const char* kVerdictCheck = "CHECK (verdict IN ('unchanged', 'changed', 'failed', 'baseline'))";

// One connection; every failure becomes a UserError naming the file.
class Connection {
 public:
  Connection(const std::string& path, int flags, int busy_timeout_ms) : path_(path) {
    const int rc = sqlite3_open_v2(path.c_str(), &db_, flags, nullptr);
    if (rc != SQLITE_OK) {
      const std::string msg = db_ ? sqlite3_errmsg(db_) : sqlite3_errstr(rc);
      sqlite3_close_v2(db_);
      db_ = nullptr;
      throw util::UserError(path + ": cannot open the history database: " + msg);
    }
    sqlite3_extended_result_codes(db_, 1);
    sqlite3_busy_timeout(db_, busy_timeout_ms);
    sqlite3_exec(db_, "PRAGMA foreign_keys = ON", nullptr, nullptr, nullptr);  // cannot fail
  }
  ~Connection() {
    // Still in a transaction (an exception unwound past it): roll back, never half-commit.
    if (db_ && !sqlite3_get_autocommit(db_))
      sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    sqlite3_close_v2(db_);
  }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;

  sqlite3* get() const { return db_; }
  const std::string& path() const { return path_; }

  [[noreturn]] void fail(const std::string& what) const {
    throw util::UserError(path_ + ": " + what + ": " + sqlite3_errmsg(db_));
  }
  void exec(const std::string& sql, const char* what = "cannot read or write the history") {
    char* err = nullptr;
    if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &err) != SQLITE_OK) {
      const std::string msg = err ? err : sqlite3_errmsg(db_);
      sqlite3_free(err);
      throw util::UserError(path_ + ": " + what + ": " + msg);
    }
  }
  int64_t pragma_int(const char* name);

 private:
  std::string path_;
  sqlite3* db_ = nullptr;
};

// A prepared statement with 1-based binds and 0-based column reads.
class Statement {
 public:
  Statement(Connection& c, const char* sql) : c_(c) {
    if (sqlite3_prepare_v2(c.get(), sql, -1, &s_, nullptr) != SQLITE_OK)
      c.fail("cannot read or write the history");
  }
  ~Statement() { sqlite3_finalize(s_); }
  Statement(const Statement&) = delete;
  Statement& operator=(const Statement&) = delete;

  Statement& bind(int i, const std::string& v) {
    check(sqlite3_bind_text(s_, i, v.data(), int(v.size()), SQLITE_TRANSIENT));
    return *this;
  }
  Statement& bind(int i, int64_t v) {
    check(sqlite3_bind_int64(s_, i, v));
    return *this;
  }
  // Non-finite values are stored as NULL (SQLite has no NaN) and read back as NaN.
  Statement& bind_real(int i, double v) {
    check(std::isfinite(v) ? sqlite3_bind_double(s_, i, v) : sqlite3_bind_null(s_, i));
    return *this;
  }
  // True while there is a row; false when done.
  bool step() {
    const int rc = sqlite3_step(s_);
    if (rc == SQLITE_ROW) return true;
    if (rc == SQLITE_DONE) return false;
    c_.fail("cannot read or write the history");
  }
  void run_once() {
    step();
    sqlite3_reset(s_);
    sqlite3_clear_bindings(s_);
  }
  void reset() {
    sqlite3_reset(s_);
    sqlite3_clear_bindings(s_);
  }
  int64_t integer(int col) const { return sqlite3_column_int64(s_, col); }
  double real(int col) const {
    return sqlite3_column_type(s_, col) == SQLITE_NULL ? std::numeric_limits<double>::quiet_NaN()
                                                       : sqlite3_column_double(s_, col);
  }
  std::string text(int col) const {
    const auto* p = sqlite3_column_text(s_, col);
    return p ? std::string(reinterpret_cast<const char*>(p), size_t(sqlite3_column_bytes(s_, col)))
             : std::string();
  }

 private:
  void check(int rc) {
    if (rc != SQLITE_OK) c_.fail("cannot bind a value");
  }
  Connection& c_;
  sqlite3_stmt* s_ = nullptr;
};

int64_t Connection::pragma_int(const char* name) {
  Statement s(*this, (std::string("PRAGMA ") + name).c_str());
  return s.step() ? s.integer(0) : 0;
}

int64_t count_tables(Connection& c) {
  Statement s(c, "SELECT count(*) FROM sqlite_master");
  return s.step() ? s.integer(0) : 0;
}

// What the schema check found.
enum class SchemaState { kEmpty, kVersion1, kVersion2, kVersion3, kCurrent };

// Checks the file's schema version; inside a transaction, so that the answer holds for it.
SchemaState check_schema(Connection& c) {
  const int64_t version = c.pragma_int("user_version");
  if (version == 0) {
    if (count_tables(c) != 0)
      throw util::UserError(c.path() +
                            ": not a renderaudit history database (it has tables, but no "
                            "history schema version)");
    return SchemaState::kEmpty;
  }
  if (c.pragma_int("application_id") != kApplicationId)
    throw util::UserError(c.path() + ": not a renderaudit history database (application_id " +
                          std::to_string(c.pragma_int("application_id")) + ")");
  if (version > kHistorySchemaVersion)
    throw util::UserError(c.path() + ": history schema version " + std::to_string(version) +
                          " is newer than this renderaudit reads (" +
                          std::to_string(kHistorySchemaVersion) + "): use a newer renderaudit");
  if (version == 1) return SchemaState::kVersion1;  // no nights table yet
  if (version == 2) return SchemaState::kVersion2;  // no baseline verdict yet
  if (version == 3) return SchemaState::kVersion3;  // no speed table yet
  if (version < kHistorySchemaVersion)
    throw util::UserError(c.path() + ": unknown history schema version " + std::to_string(version));
  return SchemaState::kCurrent;
}

// Opens an existing database for reading. Read-write when the file allows it: a connection that
// finds a hot journal (a writer killed mid-append) must be able to roll it back.
Connection open_existing(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw util::UserError("no history database at " + path +
                          " (`renderaudit audit` creates it; --db FILE chooses another)");
  return Connection(path, SQLITE_OPEN_READWRITE, kHistoryBusyTimeoutMs);
}

// In a write transaction: the schema created in an empty file, the nights table added to a
// version 1 file, the baseline verdict allowed in a version 1 or 2 file.
void create_or_migrate(Connection& c) {
  const SchemaState state = check_schema(c);
  if (state == SchemaState::kEmpty) {
    c.exec(kSchemaSql, "cannot create the history schema");
    c.exec("PRAGMA application_id = " + std::to_string(kApplicationId));
  }
  if (state == SchemaState::kEmpty || state == SchemaState::kVersion1)
    c.exec(kNightsSql, "cannot create the history schema");
  if (state == SchemaState::kVersion1 || state == SchemaState::kVersion2) {
    const int64_t schema_version = c.pragma_int("schema_version");
    c.exec("PRAGMA writable_schema = ON", "cannot migrate the history schema");
    c.exec(std::string("UPDATE sqlite_master SET sql = replace(sql, \"") + kVerdictCheckBefore3 +
               "\", \"" + kVerdictCheck + "\") WHERE type = 'table' AND name = 'audits'",
           "cannot migrate the history schema");
    c.exec("PRAGMA schema_version = " + std::to_string(schema_version + 1),
           "cannot migrate the history schema");
    c.exec("PRAGMA writable_schema = OFF", "cannot migrate the history schema");
  }
  if (state != SchemaState::kCurrent) {
    c.exec(kSpeedSql, "cannot create the history schema");
    c.exec("PRAGMA user_version = " + std::to_string(kHistorySchemaVersion));
  }
}

Connection open_for_append(const std::string& db_path, int busy_timeout_ms) {
  const fs::path parent = fs::path(db_path).parent_path();
  if (!parent.empty()) {
    std::error_code ec;
    fs::create_directories(parent, ec);  // a concurrent appender may create it first: not an error
    if (!fs::is_directory(parent))
      throw util::UserError(db_path + ": cannot create the directory " + parent.string() + ": " +
                            ec.message());
  }
  return Connection(db_path, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE, busy_timeout_ms);
}

}  // namespace

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
