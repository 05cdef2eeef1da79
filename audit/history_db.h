// The audit history: every `renderaudit audit` appends its AuditSummary (audit_summary.h) to an
// SQLite database (default outputs/history.sqlite); `renderaudit history` reads it back for the
// table of recent audits and the trend figures.
//
// Schema (version kHistorySchemaVersion, stored in PRAGMA user_version; docs/operations.md):
//   audits   one row per audit: id (1, 2, ... in append order), date_utc, experiment,
//            experiment_hash, seed (decimal text: SQLite integers are signed), baseline_run,
//            current_run, verdict ('unchanged' | 'changed' | 'failed' | 'baseline': a run audited
//            against itself, the first night of a series), changed_primitives,
//            flaky_primitives, failed_primitives, significant_tests
//   drivers  (audit_id, role 'baseline' | 'current', platform) -> renderer, version
//   metrics  (audit_id, platform, kind, view_group, metric) -> n, median, iqr
//            (median / iqr NULL when not finite, e.g. n = 0)
//   classes  (audit_id, platform, kind, view_group, visibility) -> count
//   nights   (version 2) one row per night of `renderaudit watch`: id, date_utc, source, commit,
//            previous_commit, verdict ('baseline established' | 'nothing new' | 'unchanged' |
//            'changed' | 'build failed' | 'run failed' | 'moved backwards' | 'fetch failed' |
//            'upstream gone'), culprits (one "HASH SUBJECT (N primitives)" per line), run_dir,
//            note. A version 1 database gains
//            the table at its next append.
//   (version 3: audits.verdict may be 'baseline'; a version 1 or 2 database takes it from its
//   next append on.)
//   speed    (version 4) (audit_id, platform, kind, view_group) -> baseline_platform, n, ratio,
//            low, high (current / baseline drawing time and its 95% interval), baseline_median_us,
//            current_median_us, verdict ('same' | 'faster' | 'slower' | 'unknown'); rows only
//            for audits that timed the drawing (`audit --speed`). An earlier database gains the
//            table at its next append.
// Child rows reference audits(id); an audit is written in one transaction, so a reader sees all of
// it or none of it.
//
// Durability and concurrency:
// - One transaction per append (BEGIN IMMEDIATE ... COMMIT). A process killed mid-append leaves a
//   hot rollback journal that the next connection rolls back: the database holds the whole audit
//   or none of it.
// - Rollback journal (SQLite's default, journal_mode=DELETE), not WAL: the database is written a
//   few times a day in millisecond transactions, so WAL's readers-beside-a-writer buys nothing,
//   while a rollback-journal database is one self-contained file between writes (safe to copy as a
//   CI artifact) and works on network filesystems, where WAL's shared-memory index does not.
// - Concurrent appenders (two audits at once) serialise on SQLite's file lock: BEGIN IMMEDIATE
//   takes the write lock up front (no deadlock between two readers upgrading), and a busy timeout
//   (kHistoryBusyTimeoutMs) makes the second one wait instead of failing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "audit/audit_summary.h"

namespace ra::audit {

constexpr int kHistorySchemaVersion = 4;
constexpr int kHistoryBusyTimeoutMs = 30000;  // how long an appender or reader waits for the lock

// The history an audit appends to when none is named: history.sqlite beside the current run
// directory (outputs/history.sqlite for outputs/RUN), never a path relative to the working directory.
std::string default_history_path(const std::string& current_run_dir);

// Appends `s` as one audit, in one transaction. Creates the parent directory, the file and the
// schema when missing. Throws ra::util::UserError naming the file when it cannot be opened or written,
// is not a renderaudit history database, or has a newer schema version than this program reads.
void append_history(const std::string& db_path, const AuditSummary& s);

// Test hooks and knobs for append_history.
struct AppendOptions {
  // Called inside the transaction after each child row (driver, metric, class) is inserted, with
  // the number of rows inserted so far: lets a test kill the process mid-transaction.
  std::function<void(std::size_t rows_written)> after_row;
  // > 0: PRAGMA cache_size in pages for this connection. A small cache spills uncommitted pages
  // into the database file before COMMIT, so an interruption leaves real work to roll back.
  int cache_pages = 0;
  int busy_timeout_ms = kHistoryBusyTimeoutMs;
};
// As above; returns the new audit's id.
int64_t append_history(const std::string& db_path, const AuditSummary& s,
                       const AppendOptions& options);

// One stored audit.
struct HistoryEntry {
  int64_t id = 0;  // audits.id: the audit's sequence number in this database
  AuditSummary summary;
};

// The last `last` audits (0: all), oldest first, read in one transaction (a consistent snapshot).
// Metric and class rows are ordered by platform, kind, view group, then metric / visibility.
// Throws ra::util::UserError naming the file when it is missing ("no history database at FILE"), is not
// a history database, or has a newer schema version.
std::vector<HistoryEntry> read_history(const std::string& db_path, std::size_t last = 0);

// Number of audits stored (0 for an empty database). Same errors as read_history.
int64_t history_audit_count(const std::string& db_path);

// "ok" when SQLite's integrity check and foreign-key check find nothing, else their findings, one
// per line. Same errors as read_history.
// Used by tests as an independent check of the database after writes.
std::string history_integrity(const std::string& db_path);

// One night of `renderaudit watch` (triage/watch.h).
struct NightEntry {
  int64_t id = 0;
  std::string date_utc, source, commit, previous_commit, verdict, culprits, run_dir, note;
};

// Appends a night, in one transaction (creating the database as append_history does).
void append_night(const std::string& db_path, const NightEntry& night);

// The last `last` nights (0: all), oldest first; none in a database without nights.
std::vector<NightEntry> read_nights(const std::string& db_path, std::size_t last = 0);

}  // namespace ra::audit
