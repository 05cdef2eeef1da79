// The history database's SQLite layer (audit/history_db.h holds the schema's description): one
// connection, prepared statements, the schema's version check, its creation and migrations, and
// opening the file for reading or appending. Every failure becomes a UserError naming the file.
#pragma once

#include <sqlite3.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "util/errors.h"

namespace ra::audit::history_sqlite {

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

// What the schema check found.
enum class SchemaState { kEmpty, kVersion1, kVersion2, kVersion3, kCurrent };

// Checks the file's schema version; inside a transaction, so that the answer holds for it.
SchemaState check_schema(Connection& c);

// Opens an existing database for reading. Read-write when the file allows it: a connection that
// finds a hot journal (a writer killed mid-append) must be able to roll it back.
Connection open_existing(const std::string& path);

// In a write transaction: the schema created in an empty file, the nights table added to a
// version 1 file, the baseline verdict allowed in a version 1 or 2 file.
void create_or_migrate(Connection& c);

// Opens (creating the file and its folder when missing) a database to append to.
Connection open_for_append(const std::string& db_path, int busy_timeout_ms);

}  // namespace ra::audit::history_sqlite
