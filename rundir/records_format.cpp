#include "rundir/records_format.h"

namespace ra::rundir {
namespace {
bool ends_with(std::string_view s, std::string_view tail) {
  return s.size() >= tail.size() && s.substr(s.size() - tail.size()) == tail;
}
}  // namespace

const char* records_format_name(RecordsFormat f) {
  return f == RecordsFormat::kCsv ? "csv" : "csv.zst";
}

std::optional<RecordsFormat> parse_records_format(std::string_view name) {
  if (name == "csv") return RecordsFormat::kCsv;
  if (name == "csv.zst") return RecordsFormat::kCsvZst;
  return std::nullopt;
}

const char* records_extension(RecordsFormat f) {
  return f == RecordsFormat::kCsv ? ".csv" : ".csv.zst";
}

bool is_records_file_name(std::string_view path) {
  return ends_with(path, ".csv") || ends_with(path, ".csv.zst");
}

std::string records_file_stem(std::string_view file_name) {
  for (std::string_view ext : {".csv.zst", ".csv"})
    if (ends_with(file_name, ext)) return std::string(file_name.substr(0, file_name.size() - ext.size()));
  return std::string(file_name);
}

}  // namespace ra::rundir
