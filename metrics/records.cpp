#include "metrics/records.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <limits>
#include <ostream>
#include <sstream>
#include <vector>

#include "util/errors.h"

namespace ra::metrics {

namespace {
const char* const kVisibilityNames[] = {"true-visible", "true-invisible", "false-visible",
                                        "false-invisible", "multiple-visible"};
const char* const kStatusNames[] = {"ok", "invalid", "crash", "timeout"};
const char* const kConformanceNames[] = {"", "exact", "snapped", "within-spec", "violation"};

const char* const kColumns[] = {
    "platform",  "view",       "view_group",       "orientation", "fov_deg",    "width",
    "height",    "near",       "far",              "kind",        "index",      "status",
    "visibility", "pixels",    "pe",               "pe_norm",     "lse_s",      "lse_u",
    "extent_error", "lse_s_norm", "lse_u_norm",    "chain_8connected", "gaps",  "te_s",
    "te_u",      "te_s_norm",  "te_u_norm",        "te_u_edge_norm", "full_window",
    "simply_connected", "ref_diff", "pixel_hash",  "render_us", "batch_size",
    "conformance", "violating_pixels", "violated_rules", "host_us", "clock"};
constexpr int kColumnCount = sizeof(kColumns) / sizeof(kColumns[0]);
static_assert(kColumnCount == int(kRecordColumnCount), "RecordColumn and kColumns must agree");

// Shortest text that reads back as the same double (std::to_chars without a precision): every
// value round-trips bit for bit, -0.0 and subnormals included, in fewer bytes than "%.17g".
void put_double(std::string& out, double v) {
  if (std::isnan(v)) return;  // empty cell = not applicable
  char buf[32];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}
template <typename Int>
void put_integer(std::string& out, Int v) {
  char buf[24];
  const auto res = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, res.ptr);
}
void put_optional(std::string& out, int64_t v) {
  if (v >= 0) put_integer(out, v);
}

}  // namespace

const char* visibility_name(Visibility v) { return kVisibilityNames[int(v)]; }
const char* status_name(CaseStatus s) { return kStatusNames[int(s)]; }

const char* conformance_name(Conformance c) { return kConformanceNames[int(c)]; }

bool parse_conformance(std::string_view s, Conformance* out) {
  for (int i = 0; i < 5; ++i)
    if (s == kConformanceNames[i]) return *out = Conformance(i), true;
  return false;
}

const char* record_column_name(RecordColumn c) { return kColumns[static_cast<std::size_t>(c)]; }

std::optional<RecordColumn> find_record_column(std::string_view name) {
  for (int i = 0; i < kColumnCount; ++i)
    if (name == kColumns[i]) return static_cast<RecordColumn>(i);
  return std::nullopt;
}

std::string records_header() {
  std::string h;
  for (int i = 0; i < kColumnCount; ++i) h += (i ? "," : "") + std::string(kColumns[i]);
  return h;
}

std::string records_header_v3() {
  std::string h;
  for (int i = 0; i < int(kRecordColumnCountV3); ++i) h += (i ? "," : "") + std::string(kColumns[i]);
  return h;
}

std::string records_header_v2() {
  std::string h;
  for (int i = 0; i < int(kRecordColumnCountV2); ++i) h += (i ? "," : "") + std::string(kColumns[i]);
  return h;
}

void append_record(std::string& out, const Record& r) {
  const auto sep = [&] { out += ','; };
  out += r.platform;
  sep();
  put_integer(out, r.view);
  sep();
  put_integer(out, r.view_group);
  sep();
  put_integer(out, r.orientation);
  sep();
  put_double(out, r.fov_deg);
  sep();
  put_integer(out, r.width);
  sep();
  put_integer(out, r.height);
  sep();
  put_double(out, r.near);
  sep();
  put_double(out, r.far);
  sep();
  out += r.kind;
  sep();
  put_integer(out, r.index);
  sep();
  out += status_name(r.status);
  sep();
  out += visibility_name(r.visibility);
  sep();
  put_integer(out, r.pixels);
  for (double v : {r.pe, r.pe_norm, r.lse_s, r.lse_u, r.extent_error, r.lse_s_norm, r.lse_u_norm}) {
    sep();
    put_double(out, v);
  }
  sep();
  put_optional(out, r.chain_8connected);
  sep();
  put_optional(out, r.gaps);
  for (double v : {r.te_s, r.te_u, r.te_s_norm, r.te_u_norm, r.te_u_edge_norm}) {
    sep();
    put_double(out, v);
  }
  sep();
  put_optional(out, r.full_window);
  sep();
  put_optional(out, r.simply_connected);
  sep();
  put_optional(out, r.ref_diff);
  sep();
  put_integer(out, r.pixel_hash);
  sep();
  put_double(out, r.render_us);
  sep();
  if (r.batch_size > 0) put_integer(out, r.batch_size);
  sep();
  out += conformance_name(r.conformance);
  sep();
  put_optional(out, r.violating_pixels);
  sep();
  out += r.violated_rules;
  sep();
  put_double(out, r.host_us);
  sep();
  out += r.clock;
  out += '\n';
}

std::string untimed_record_line(Record r) {
  r.render_us = r.host_us = kNA;
  r.batch_size = 0;
  r.clock.clear();
  std::string line;
  append_record(line, r);
  return line;
}

void write_record(std::ostream& out, const Record& r) {
  std::string line;
  append_record(line, r);
  out << line;
}

}  // namespace ra::metrics
