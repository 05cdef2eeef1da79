// The history database's SQLite layer (history_sqlite.h): the schema and its migrations.
#include "audit/history_sqlite.h"

#include <filesystem>
#include <system_error>

#include "audit/history_db.h"

namespace fs = std::filesystem;

namespace ra::audit::history_sqlite {
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

int64_t count_tables(Connection& c) {
  Statement s(c, "SELECT count(*) FROM sqlite_master");
  return s.step() ? s.integer(0) : 0;
}

}  // namespace

int64_t Connection::pragma_int(const char* name) {
  Statement s(*this, (std::string("PRAGMA ") + name).c_str());
  return s.step() ? s.integer(0) : 0;
}

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

Connection open_existing(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw util::UserError("no history database at " + path +
                          " (`renderaudit audit` creates it; --db FILE chooses another)");
  return Connection(path, SQLITE_OPEN_READWRITE, kHistoryBusyTimeoutMs);
}

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

}  // namespace ra::audit::history_sqlite
