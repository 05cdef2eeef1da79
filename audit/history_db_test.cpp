// The history database: round trip, schema versioning, clear errors, and what survives a killed
// appender and two appenders at once (real processes, fork + SIGKILL).
#include "audit/history_db.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sqlite3.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>

#include "util/errors.h"
#include "tests/cli_harness.h"

namespace fs = std::filesystem;
using ra::testing_cli::error_message;
using ra::testing_cli::fresh_dir;

namespace ra::audit {
namespace {

// An audit with `metric_rows` metric rows; values derived from `k` so audits differ.
AuditSummary make_summary(int k, std::size_t metric_rows = 6) {
  AuditSummary s;
  s.date_utc = "2026-11-" + std::to_string(10 + k) + "T03:00:00Z";
  s.experiment = "nightly";
  s.experiment_hash = "0123456789abcdef";
  s.seed = 18446744073709551557ull;  // above INT64_MAX: must survive SQLite's signed integers
  s.baseline_run = "/runs/base-" + std::to_string(k);
  s.current_run = "/runs/cur-" + std::to_string(k);
  s.baseline_drivers = {{"osmesa-llvmpipe", "llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 Mesa 22.3.6"}};
  s.current_drivers = {{"osmesa-llvmpipe", "llvmpipe (LLVM 16.0.6, 256 bits)", "4.5 Mesa 23.1.0"},
                       {"osmesa-softpipe", "softpipe", "3.3 Mesa 23.1.0"}};
  s.verdict = k % 2 ? Verdict::kChanged : Verdict::kUnchanged;
  s.changed_primitives = 3 * k;
  s.flaky_primitives = k;
  s.failed_primitives = 0;
  s.significant_tests = 2;
  for (std::size_t i = 0; i < metric_rows; ++i)
    s.metrics.push_back({"osmesa-llvmpipe", "triangle", "te_u_" + std::to_string(i), int(1 + i % 4),
                         int64_t(100 + i), 0.25 * k + 1e-3 * i, 0.5 + 1e-4 * i});
  s.classes = {{"osmesa-llvmpipe", "point", "true-visible", 1, 950},
               {"osmesa-llvmpipe", "point", "false-invisible", 1, 3 + k},
               {"osmesa-softpipe", "point", "crash", 2, 1}};
  s.speed = {{"osmesa-llvmpipe", "osmesa-llvmpipe", "triangle", 4, 200, 0.74 + 0.01 * k, 0.71, 0.77,
              310.5, 229.75, "faster"},
             {"osmesa-llvmpipe", "osmesa-llvmpipe", "point", 1, 5, NAN, NAN, NAN, 7.5, 7.25,
              "unknown"}};
  return s;
}

void expect_same(const AuditSummary& a, const AuditSummary& b) {
  EXPECT_EQ(a.date_utc, b.date_utc);
  EXPECT_EQ(a.experiment, b.experiment);
  EXPECT_EQ(a.experiment_hash, b.experiment_hash);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.baseline_run, b.baseline_run);
  EXPECT_EQ(a.current_run, b.current_run);
  EXPECT_EQ(a.verdict, b.verdict);
  EXPECT_EQ(a.changed_primitives, b.changed_primitives);
  EXPECT_EQ(a.flaky_primitives, b.flaky_primitives);
  EXPECT_EQ(a.failed_primitives, b.failed_primitives);
  EXPECT_EQ(a.significant_tests, b.significant_tests);
  ASSERT_EQ(a.baseline_drivers.size(), b.baseline_drivers.size());
  ASSERT_EQ(a.current_drivers.size(), b.current_drivers.size());
  for (std::size_t i = 0; i < a.current_drivers.size(); ++i) {
    EXPECT_EQ(a.current_drivers[i].platform, b.current_drivers[i].platform);
    EXPECT_EQ(a.current_drivers[i].renderer, b.current_drivers[i].renderer);
    EXPECT_EQ(a.current_drivers[i].version, b.current_drivers[i].version);
  }
  ASSERT_EQ(a.metrics.size(), b.metrics.size());
  for (std::size_t i = 0; i < a.metrics.size(); ++i) {
    const MetricSummary &x = a.metrics[i], &y = b.metrics[i];
    EXPECT_EQ(x.platform, y.platform);
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.metric, y.metric);
    EXPECT_EQ(x.view_group, y.view_group);
    EXPECT_EQ(x.n, y.n);
    // Exact: SQLite REAL is an IEEE double. NaN (no data) round-trips as NaN.
    if (std::isnan(x.median))
      EXPECT_TRUE(std::isnan(y.median));
    else
      EXPECT_EQ(x.median, y.median);
    if (std::isnan(x.iqr))
      EXPECT_TRUE(std::isnan(y.iqr));
    else
      EXPECT_EQ(x.iqr, y.iqr);
  }
  ASSERT_EQ(a.classes.size(), b.classes.size());
  for (std::size_t i = 0; i < a.classes.size(); ++i) {
    EXPECT_EQ(a.classes[i].visibility, b.classes[i].visibility);
    EXPECT_EQ(a.classes[i].view_group, b.classes[i].view_group);
    EXPECT_EQ(a.classes[i].count, b.classes[i].count);
  }
  ASSERT_EQ(a.speed.size(), b.speed.size());
  auto same_real = [](double x, double y) { return std::isnan(x) ? std::isnan(y) : x == y; };
  for (std::size_t i = 0; i < a.speed.size(); ++i) {
    const SpeedSummary &x = a.speed[i], &y = b.speed[i];
    EXPECT_EQ(x.platform, y.platform);
    EXPECT_EQ(x.baseline_platform, y.baseline_platform);
    EXPECT_EQ(x.kind, y.kind);
    EXPECT_EQ(x.view_group, y.view_group);
    EXPECT_EQ(x.n, y.n);
    EXPECT_TRUE(same_real(x.ratio, y.ratio) && same_real(x.low, y.low) &&
                same_real(x.high, y.high));
    EXPECT_EQ(x.baseline_median_us, y.baseline_median_us);
    EXPECT_EQ(x.current_median_us, y.current_median_us);
    EXPECT_EQ(x.verdict, y.verdict);
  }
}

void set_pragma(const std::string& path, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path.c_str(), &db), SQLITE_OK);
  ASSERT_EQ(sqlite3_exec(db, sql.c_str(), nullptr, nullptr, nullptr), SQLITE_OK);
  sqlite3_close(db);
}

int64_t pragma_value(const std::string& path, const std::string& pragma) {
  sqlite3* db = nullptr;
  sqlite3_open(path.c_str(), &db);
  sqlite3_stmt* s = nullptr;
  sqlite3_prepare_v2(db, ("PRAGMA " + pragma).c_str(), -1, &s, nullptr);
  const int64_t v = sqlite3_step(s) == SQLITE_ROW ? sqlite3_column_int64(s, 0) : -1;
  sqlite3_finalize(s);
  sqlite3_close(db);
  return v;
}

TEST(HistoryDb, RoundTripOfSummariesOldestFirst) {
  const std::string db = fresh_dir("history_roundtrip") + "/nested/dir/history.sqlite";
  AuditSummary first = make_summary(1);
  first.metrics[2].median = NAN;  // n = 0 groups have no median
  first.metrics[2].iqr = NAN;
  const AuditSummary second = make_summary(2);
  append_history(db, first);  // creates nested/dir/ and the schema
  EXPECT_EQ(append_history(db, second, AppendOptions{}), 2);

  const std::vector<HistoryEntry> all = read_history(db);
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].id, 1);
  EXPECT_EQ(all[1].id, 2);
  expect_same(first, all[0].summary);
  expect_same(second, all[1].summary);

  const std::vector<HistoryEntry> last = read_history(db, 1);
  ASSERT_EQ(last.size(), 1u);
  EXPECT_EQ(last[0].id, 2);
  EXPECT_EQ(last[0].summary.date_utc, "2026-11-12T03:00:00Z");
  EXPECT_EQ(history_audit_count(db), 2);
  EXPECT_EQ(history_integrity(db), "ok");
  EXPECT_EQ(pragma_value(db, "user_version"), kHistorySchemaVersion);
  // Rollback journal: the database is one file between writes.
  EXPECT_FALSE(fs::exists(db + "-journal"));
  EXPECT_FALSE(fs::exists(db + "-wal"));
}

TEST(HistoryDb, AVersion1DatabaseGainsTheNightsAndKeepsItsAudits) {
  // Why: the nights of `renderaudit watch` share the history file with the audits; a database
  // written before them must read as it did and take nights from its next append.
  const std::string db = fresh_dir("history_nights") + "/history.sqlite";
  append_history(db, make_summary(1));
  set_pragma(db, "DROP TABLE nights");
  set_pragma(db, "PRAGMA user_version = 1");  // as version 1 wrote it
  EXPECT_EQ(history_audit_count(db), 1);
  EXPECT_TRUE(read_nights(db).empty());
  NightEntry n;
  n.date_utc = "2026-11-28T02:00:00Z";
  n.source = "/srv/mesa";
  n.commit = std::string(40, 'b');
  n.previous_commit = std::string(40, 'a');
  n.verdict = "changed";
  n.culprits = "c2 one (3 primitives of egl-llvmpipe)\nc3 two (1 primitives of egl-llvmpipe)";
  n.note = "4 primitives changed";
  append_night(db, n);
  append_history(db, make_summary(2));
  EXPECT_EQ(pragma_value(db, "user_version"), kHistorySchemaVersion);
  EXPECT_EQ(history_audit_count(db), 2);
  const std::vector<NightEntry> nights = read_nights(db);
  ASSERT_EQ(nights.size(), 1u);
  EXPECT_EQ(nights[0].id, 1);
  EXPECT_EQ(nights[0].commit, n.commit);
  EXPECT_EQ(nights[0].culprits, n.culprits);
  EXPECT_EQ(nights[0].verdict, "changed");
  EXPECT_EQ(history_integrity(db), "ok");
}

TEST(HistoryDb, AVersion3DatabaseGainsTheSpeedTableAndKeepsItsAudits) {
  // Why: drawing-time verdicts go into a table of their own; a history written before it must
  // read as it did (no speed rows) and take them from its next append.
  const std::string db = fresh_dir("history_speed") + "/history.sqlite";
  AuditSummary old = make_summary(1);
  old.speed.clear();
  append_history(db, old);
  set_pragma(db, "DROP TABLE speed; PRAGMA user_version = 3");  // as version 3 wrote it
  std::vector<HistoryEntry> all = read_history(db);
  ASSERT_EQ(all.size(), 1u);
  expect_same(old, all[0].summary);
  append_history(db, make_summary(2));
  EXPECT_EQ(pragma_value(db, "user_version"), kHistorySchemaVersion);
  all = read_history(db);
  ASSERT_EQ(all.size(), 2u);
  expect_same(old, all[0].summary);
  expect_same(make_summary(2), all[1].summary);
  EXPECT_EQ(history_integrity(db), "ok");
}

TEST(HistoryDb, AVersion2DatabaseTakesABaselineNight) {
  // Why: a nightly series records its first night (verdict 'baseline'), and a history written
  // before that verdict existed (its CHECK lists three verdicts) must take it from its next
  // append, keeping what it holds.
  const std::string db = fresh_dir("history_baseline") + "/history.sqlite";
  append_history(db, make_summary(1));
  set_pragma(db,
             "PRAGMA writable_schema = ON; UPDATE sqlite_master SET sql = replace(sql, "
             "\"'failed', 'baseline')\", \"'failed')\") WHERE name = 'audits'; "
             "PRAGMA writable_schema = OFF; PRAGMA user_version = 2");  // as version 2 wrote it
  AuditSummary baseline = make_summary(2);
  baseline.verdict = Verdict::kBaseline;
  baseline.baseline_run = baseline.current_run;
  EXPECT_EQ(append_history(db, baseline, AppendOptions{}), 2);
  EXPECT_EQ(pragma_value(db, "user_version"), kHistorySchemaVersion);
  const std::vector<HistoryEntry> all = read_history(db);
  ASSERT_EQ(all.size(), 2u);
  expect_same(make_summary(1), all[0].summary);
  EXPECT_EQ(all[1].summary.verdict, Verdict::kBaseline);
  EXPECT_EQ(history_integrity(db), "ok");
  // the check still refuses a verdict that is none of the four
  sqlite3* h = nullptr;
  ASSERT_EQ(sqlite3_open(db.c_str(), &h), SQLITE_OK);
  EXPECT_NE(sqlite3_exec(h, "UPDATE audits SET verdict = 'maybe' WHERE id = 1", nullptr, nullptr,
                         nullptr),
            SQLITE_OK);
  sqlite3_close(h);
}

TEST(HistoryDb, ADuplicatedMetricRowRejectsTheWholeAudit) {
  const std::string db = fresh_dir("history_dup") + "/h.sqlite";
  append_history(db, make_summary(1));
  AuditSummary bad = make_summary(2);
  bad.metrics.push_back(bad.metrics.front());
  const std::string msg = error_message<util::UserError>([&] { append_history(db, bad); });
  EXPECT_NE(msg.find(db + ": "), std::string::npos) << msg;
  EXPECT_NE(msg.find("UNIQUE constraint failed"), std::string::npos) << msg;
  EXPECT_EQ(history_audit_count(db), 1);  // the audit row of the failed append was rolled back
  EXPECT_EQ(history_integrity(db), "ok");
}

TEST(HistoryDb, ErrorsNameTheFile) {
  const std::string dir = fresh_dir("history_errors");
  std::string msg = error_message<util::UserError>([&] { read_history(dir + "/none.sqlite"); });
  EXPECT_EQ(msg, "no history database at " + dir +
                     "/none.sqlite (`renderaudit audit` creates it; --db FILE chooses another)");

  std::ofstream(dir + "/text.sqlite") << "this is not a database, just text padding it out\n"
                                      << std::string(200, 'x');
  msg = error_message<util::UserError>([&] { read_history(dir + "/text.sqlite"); });
  EXPECT_NE(msg.find(dir + "/text.sqlite: "), std::string::npos) << msg;
  EXPECT_NE(msg.find("not a database"), std::string::npos) << msg;

  set_pragma(dir + "/other.sqlite", "CREATE TABLE t (x)");
  msg = error_message<util::UserError>(
      [&] { append_history(dir + "/other.sqlite", make_summary(1)); });
  EXPECT_EQ(msg, dir +
                     "/other.sqlite: not a renderaudit history database (it has tables, but no "
                     "history schema version)");

  msg = error_message<util::UserError>(
      [&] { append_history("/proc/no/such/h.sqlite", make_summary(1)); });
  EXPECT_NE(msg.find("/proc/no/such/h.sqlite: cannot create the directory /proc/no/such"),
            std::string::npos)
      << msg;
}

TEST(HistoryDb, ANewerSchemaVersionIsRefused) {
  const std::string db = fresh_dir("history_newer") + "/h.sqlite";
  append_history(db, make_summary(1));
  set_pragma(db, "PRAGMA user_version = " + std::to_string(kHistorySchemaVersion + 1));
  const std::string expected =
      db + ": history schema version " + std::to_string(kHistorySchemaVersion + 1) +
      " is newer than this renderaudit reads (" + std::to_string(kHistorySchemaVersion) +
      "): use a newer renderaudit";
  EXPECT_EQ(error_message<util::UserError>([&] { append_history(db, make_summary(2)); }), expected);
  EXPECT_EQ(error_message<util::UserError>([&] { read_history(db); }), expected);
}

TEST(HistoryDb, AnAppendKilledMidTransactionLeavesTheWholeAuditOrNone) {
  const std::string db = fresh_dir("history_kill") + "/h.sqlite";
  const AuditSummary first = make_summary(1, 20);
  append_history(db, first);
  const auto size_before = fs::file_size(db);

  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    // Child: a big audit with a tiny page cache, so uncommitted pages reach the database file;
    // stop inside the transaction and wait to be killed.
    ::close(ready[0]);
    AppendOptions o;
    o.cache_pages = 10;
    o.after_row = [&](std::size_t rows) {
      if (rows == 4000) {
        (void)!::write(ready[1], "x", 1);
        ::pause();
      }
    };
    try {
      append_history(db, make_summary(2, 5000), o);
    } catch (...) {
    }
    ::_exit(3);  // not reached unless the hook failed
  }
  ::close(ready[1]);
  char c = 0;
  ASSERT_EQ(::read(ready[0], &c, 1), 1) << "the child never reached the middle of its append";
  ::close(ready[0]);
  // The child is inside its transaction: the journal holds the original pages and the database
  // file already holds uncommitted ones.
  EXPECT_TRUE(fs::exists(db + "-journal"));
  EXPECT_GT(fs::file_size(db), size_before);
  ::kill(pid, SIGKILL);
  int status = 0;
  ::waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);

  // The next connection rolls the hot journal back: only the first audit, intact.
  EXPECT_EQ(history_integrity(db), "ok");
  std::vector<HistoryEntry> h = read_history(db);
  ASSERT_EQ(h.size(), 1u);
  expect_same(first, h[0].summary);
  EXPECT_FALSE(fs::exists(db + "-journal"));

  // And the database takes the next audit.
  append_history(db, make_summary(3, 20));
  h = read_history(db);
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[1].summary.current_run, "/runs/cur-3");
  EXPECT_EQ(h[1].summary.metrics.size(), 20u);
  EXPECT_EQ(history_integrity(db), "ok");
}

TEST(HistoryDb, TwoProcessesAppendingAtOnceKeepEveryAudit) {
  const std::string db = fresh_dir("history_concurrent") + "/h.sqlite";  // not created yet
  constexpr int kPerProcess = 10;
  constexpr std::size_t kRows = 200;
  int go[2];
  ASSERT_EQ(::pipe(go), 0);
  pid_t pids[2];
  for (int p = 0; p < 2; ++p) {
    pids[p] = ::fork();
    ASSERT_GE(pids[p], 0);
    if (pids[p] == 0) {
      ::close(go[1]);
      char c;
      (void)!::read(go[0], &c, 1);  // start together: both race to create the schema too
      int failures = 0;
      for (int i = 0; i < kPerProcess; ++i) {
        try {
          append_history(db, make_summary(100 * (p + 1) + i, kRows));
        } catch (const std::exception& e) {
          std::fprintf(stderr, "appender %d: %s\n", p, e.what());
          ++failures;
        }
      }
      ::_exit(failures);
    }
  }
  ::close(go[0]);
  ::close(go[1]);  // EOF releases both children at once
  for (pid_t pid : pids) {
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "an append failed";
  }

  const std::vector<HistoryEntry> h = read_history(db);
  ASSERT_EQ(h.size(), 2u * kPerProcess);
  std::set<std::string> runs;
  for (std::size_t i = 0; i < h.size(); ++i) {
    EXPECT_EQ(h[i].id, int64_t(i + 1));
    EXPECT_EQ(h[i].summary.metrics.size(), kRows);
    EXPECT_EQ(h[i].summary.classes.size(), 3u);
    EXPECT_EQ(h[i].summary.current_drivers.size(), 2u);
    runs.insert(h[i].summary.current_run);
  }
  EXPECT_EQ(runs.size(), 2u * kPerProcess);  // every audit once
  EXPECT_EQ(history_integrity(db), "ok");
}

}  // namespace
}  // namespace ra::audit
