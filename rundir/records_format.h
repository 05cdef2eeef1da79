// The two encodings of a records file (docs/records.md, "Files"): plain CSV (`<id>.csv`) and the
// same CSV bytes compressed with zstd in independent frames (`<id>.csv.zst`, util/zstd_stream.h).
// Both hold the same header, rows and seal; every reader of records takes either.
#pragma once

#include <optional>
#include <string>
#include <string_view>

namespace ra::rundir {

enum class RecordsFormat { kCsv, kCsvZst };

const char* records_format_name(RecordsFormat f);  // "csv", "csv.zst"
std::optional<RecordsFormat> parse_records_format(std::string_view name);
const char* records_extension(RecordsFormat f);  // ".csv", ".csv.zst"

// True for a file name a records file may have: "*.csv" or "*.csv.zst".
bool is_records_file_name(std::string_view path);
// The file name without ".csv" or ".csv.zst" (the shard id for a shard's records file).
// Used by tests to name the shard of a records file.
std::string records_file_stem(std::string_view file_name);

}  // namespace ra::rundir
