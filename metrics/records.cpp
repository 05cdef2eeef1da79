#include "metrics/records.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>
#include <ostream>
#include <sstream>
#include <vector>

#include "util/errors.h"

namespace ra {

namespace {
const char* const kVisibilityNames[] = {"true-visible", "true-invisible", "false-visible",
                                        "false-invisible", "multiple-visible"};
const char* const kStatusNames[] = {"ok", "invalid", "crash", "timeout"};

const char* const kColumns[] = {
    "platform",  "view",       "view_group",       "orientation", "fov_deg",    "width",
    "height",    "near",       "far",              "kind",        "index",      "status",
    "visibility", "pixels",    "pe",               "pe_norm",     "lse_s",      "lse_u",
    "extent_error", "lse_s_norm", "lse_u_norm",    "chain_8connected", "gaps",  "te_s",
    "te_u",      "te_s_norm",  "te_u_norm",        "te_u_edge_norm", "full_window",
    "simply_connected", "ref_diff", "pixel_hash",  "render_us", "batch_size"};
constexpr int kColumnCount = sizeof(kColumns) / sizeof(kColumns[0]);

void put_double(std::ostream& out, double v) {
  if (std::isnan(v)) return;  // empty cell = not applicable
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  out << buf;
}
void put_optional(std::ostream& out, int64_t v) {
  if (v >= 0) out << v;
}

double get_double(const std::string& s) { return s.empty() ? kNA : std::stod(s); }
int64_t get_optional(const std::string& s) { return s.empty() ? -1 : std::stoll(s); }
}  // namespace

const char* visibility_name(Visibility v) { return kVisibilityNames[int(v)]; }
bool parse_visibility(const std::string& s, Visibility* out) {
  for (int i = 0; i < 5; ++i)
    if (s == kVisibilityNames[i]) return *out = Visibility(i), true;
  return false;
}
const char* status_name(CaseStatus s) { return kStatusNames[int(s)]; }
bool parse_status(const std::string& s, CaseStatus* out) {
  for (int i = 0; i < 4; ++i)
    if (s == kStatusNames[i]) return *out = CaseStatus(i), true;
  return false;
}

std::string records_header() {
  std::string h;
  for (int i = 0; i < kColumnCount; ++i) h += (i ? "," : "") + std::string(kColumns[i]);
  return h;
}

void write_record(std::ostream& out, const Record& r) {
  out << r.platform << ',' << r.view << ',' << r.view_group << ',' << r.orientation << ',';
  put_double(out, r.fov_deg);
  out << ',' << r.width << ',' << r.height << ',';
  put_double(out, r.near);
  out << ',';
  put_double(out, r.far);
  out << ',' << r.kind << ',' << r.index << ',' << status_name(r.status) << ','
      << visibility_name(r.visibility) << ',' << r.pixels;
  for (double v : {r.pe, r.pe_norm, r.lse_s, r.lse_u, r.extent_error, r.lse_s_norm, r.lse_u_norm}) {
    out << ',';
    put_double(out, v);
  }
  out << ',';
  put_optional(out, r.chain_8connected);
  out << ',';
  put_optional(out, r.gaps);
  for (double v : {r.te_s, r.te_u, r.te_s_norm, r.te_u_norm, r.te_u_edge_norm}) {
    out << ',';
    put_double(out, v);
  }
  out << ',';
  put_optional(out, r.full_window);
  out << ',';
  put_optional(out, r.simply_connected);
  out << ',';
  put_optional(out, r.ref_diff);
  out << ',' << r.pixel_hash << ',';
  put_double(out, r.render_us);
  out << ',';
  if (r.batch_size > 0) out << r.batch_size;
  out << '\n';
}

void read_records(const std::string& path, const std::function<void(const Record&)>& row) {
  std::ifstream in(path);
  if (!in) throw UserError(path + ": cannot read records file");
  std::string line;
  const bool has_header = bool(std::getline(in, line));
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (!has_header || line != records_header())
    throw UserError(path + ":1: unexpected records header (schema version " +
                    std::to_string(kRecordsSchemaVersion) + " expects: " + records_header() + ")");
  std::vector<std::string> f;
  f.reserve(kColumnCount);
  std::vector<std::string> names;  // column names, for messages
  {
    std::stringstream header(records_header());
    for (std::string n; std::getline(header, n, ',');) names.push_back(n);
  }
  for (int64_t line_no = 2; std::getline(in, line); ++line_no) {
    if (!line.empty() && line.back() == '\r') line.pop_back();  // CRLF files read as LF ones
    if (!line.empty() && line[0] == '#') continue;  // the seal of a shard file (shard_file.h)
    f.clear();
    size_t start = 0;
    for (;;) {
      const size_t comma = line.find(',', start);
      f.push_back(line.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
      if (comma == std::string::npos) break;
      start = comma + 1;
    }
    auto bad = [&](const std::string& why) {
      throw UserError(path + ":" + std::to_string(line_no) + ": " + why);
    };
    if (int(f.size()) != kColumnCount)
      bad("expected " + std::to_string(kColumnCount) + " fields, found " + std::to_string(f.size()));
    Record r;
    int i = 0;  // after each field is taken, the index of the next one
    try {
      r.platform = f[i++];
      r.view = std::stoi(f[i++]);
      r.view_group = std::stoi(f[i++]);
      r.orientation = std::stoi(f[i++]);
      r.fov_deg = get_double(f[i++]);
      r.width = std::stoi(f[i++]);
      r.height = std::stoi(f[i++]);
      r.near = get_double(f[i++]);
      r.far = get_double(f[i++]);
      r.kind = f[i++];
      r.index = std::stoull(f[i++]);
      if (!parse_status(f[i++], &r.status)) bad("unknown status '" + f[i - 1] + "'");
      if (!parse_visibility(f[i++], &r.visibility)) bad("unknown visibility '" + f[i - 1] + "'");
      r.pixels = std::stoll(f[i++]);
      for (double* d : {&r.pe, &r.pe_norm, &r.lse_s, &r.lse_u, &r.extent_error, &r.lse_s_norm,
                        &r.lse_u_norm})
        *d = get_double(f[i++]);
      r.chain_8connected = int(get_optional(f[i++]));
      r.gaps = get_optional(f[i++]);
      for (double* d : {&r.te_s, &r.te_u, &r.te_s_norm, &r.te_u_norm, &r.te_u_edge_norm})
        *d = get_double(f[i++]);
      r.full_window = int(get_optional(f[i++]));
      r.simply_connected = int(get_optional(f[i++]));
      r.ref_diff = get_optional(f[i++]);
      r.pixel_hash = std::stoull(f[i++]);
      r.render_us = get_double(f[i++]);
      const std::string& batch = f[i++];
      r.batch_size = batch.empty() ? 0 : std::stoll(batch);
    } catch (const std::logic_error&) {  // stoi and friends: the field just taken is not a number
      const int column = std::max(0, i - 1);
      bad("column '" + (column < int(names.size()) ? names[column] : std::to_string(column + 1)) +
          "': '" + f[column] + "' is not a number");
    }
    row(r);
  }
}

}  // namespace ra
