// The one reader of records files (schema: metrics/records.h, docs/records.md), plain CSV or
// zstd-compressed CSV (rundir/records_format.h: chosen by the ".zst" ending). Every
// stage that reads records goes through it: the file is read in blocks of 4 MiB (decompressed in
// pieces of 1 MiB), each row is split
// in place (cells are views into the buffer, nothing is copied), and only the cells a caller asks
// for are converted, with std::from_chars (locale-independent, exact). The header must equal
// records_header() or, for a file of schema version 2 or 3, records_header_v2() or _v3() (its missing cells read as
// empty); '#' lines (the seal of a shard file, rundir/shard_file.h) are skipped and a
// CRLF file reads as an LF one. Every error is a ra::util::UserError "FILE:LINE: what is wrong".
#pragma once

#include <array>
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "metrics/records.h"

namespace ra::rundir {

// One row of a records file while its callback runs (the cells do not outlive the call).
class RecordRow {
 public:
  std::string_view cell(metrics::RecordColumn c) const { return cells_[static_cast<std::size_t>(c)]; }
  const std::string& file() const { return *file_; }
  std::int64_t line() const { return line_; }  // 1-based; the header is line 1

  // The cell as an integer; an empty or malformed cell is an error naming the column.
  template <typename Int>
  Int integer(metrics::RecordColumn c) const {
    const std::string_view f = cell(c);
    Int v{};
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || end != f.data() + f.size() || f.empty()) not_an_integer(c);
    return v;
  }
  // An integer, or `absent` for an empty cell.
  template <typename Int>
  Int optional_integer(metrics::RecordColumn c, Int absent) const {
    return cell(c).empty() ? absent : integer<Int>(c);
  }
  // A finite number, or nullopt for an empty cell (not applicable).
  std::optional<double> number(metrics::RecordColumn c) const;
  // A finite number; an empty cell is an error.
  double required_number(metrics::RecordColumn c) const;
  // The status and visibility cells, checked against their names.
  metrics::CaseStatus status() const;
  metrics::Visibility visibility() const;
  metrics::Conformance conformance() const;  // empty: kNotCompared

  [[noreturn]] void fail(const std::string& why) const;  // "FILE:LINE: why"

 private:
  friend class RecordsFileReader;
  [[noreturn]] void not_an_integer(metrics::RecordColumn c) const;
  std::array<std::string_view, metrics::kRecordColumnCount> cells_{};
  const std::string* file_ = nullptr;
  std::int64_t line_ = 0;
};

// Calls `row` for every record of the file at `path`, in file order. Throws ra::util::UserError when the
// file cannot be read, its header is not the records header, or a row has the wrong number of
// cells; `row` may throw too (RecordRow::fail names file and line).
void for_each_record_row(const std::string& path, const std::function<void(const RecordRow&)>& row);
// The same, passing every piece of the file's text (decompressed) to `text` in order, before the
// rows in it: a check over the whole text (the seal of a shard file) in the same pass.
void for_each_record_row(const std::string& path, const std::function<void(const RecordRow&)>& row,
                         const std::function<void(std::string_view)>& text);

// The schema version of the file's header line (4; 3 or 2 for records_header_v3() or _v2()); 0 when the
// file is unreadable or its first line is not a records header.
int records_schema_version(const std::string& path);

// The whole record of a row (every column converted and checked).
metrics::Record parse_record(const RecordRow& row);

// Reads a records file (.csv or .csv.zst); calls `row` for each record. Throws UserError naming file and line on a
// malformed row or an unexpected header (a schema change is an error, not a silent shift). A
// convenience over for_each_record_row, which converts only the cells a caller needs.
void read_records(const std::string& path, const std::function<void(const metrics::Record&)>& row);

}  // namespace ra::rundir
