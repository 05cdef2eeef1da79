// Audit records: one CSV row per (platform, view, primitive), the interface between the runner and
// every later stage. The schema (columns, units, empty cells) is documented in docs/records.md.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace ra::metrics {

// 2: batch_size after render_us; 3: conformance, violating_pixels, violated_rules at the end;
// 4: host_us and clock at the end. Files of versions 2 and 3 are still read: the cells they lack
// are empty ("not compared"; no host time, clock unsaid: the host's).
constexpr int kRecordsSchemaVersion = 4;

enum class Visibility {
  kTrueVisible,
  kTrueInvisible,
  kFalseVisible,
  kFalseInvisible,
  kMultipleVisible,
};
const char* visibility_name(Visibility v);  // "true-visible", ...

// Case status: the metrics are meaningful only for `ok`.
enum class CaseStatus { kOk, kInvalid, kCrash, kTimeout };
const char* status_name(CaseStatus s);  // "ok", "invalid", "crash", "timeout"

// How a primitive's lit pixels relate to what the GL spec allows (metrics/conformance.h).
enum class Conformance {
  kNotCompared,  // the reference platform itself, a case not drawn, or a version 2 record
  kExact,        // equal to the exact reference rasterizer's pixels
  kSnapped,      // equal to the reference with vertices snapped to the platform's effective grid
  kWithinSpec,   // neither, but every differing pixel is one GL allows
  kViolation,    // at least one pixel no conforming implementation could light or leave dark
};
const char* conformance_name(Conformance c);  // "", "exact", "snapped", "within-spec", "violation"
bool parse_conformance(std::string_view s, Conformance* out);

// Missing values (not applicable to the kind, or not true-visible) are NaN and written empty.
constexpr double kNA = std::numeric_limits<double>::quiet_NaN();

struct Record {
  std::string platform;
  int view = 0, view_group = 0, orientation = 0;
  double fov_deg = 0;
  int width = 0, height = 0;
  double near = 0, far = 0;
  std::string kind;  // "point", "line", "triangle"
  uint64_t index = 0;
  CaseStatus status = CaseStatus::kOk;
  Visibility visibility = Visibility::kTrueInvisible;
  int64_t pixels = 0;  // lit pixels found
  // Points (paper 3.4): pixels, and / sqrt(W*H).
  double pe = kNA, pe_norm = kNA;
  // Lines (paper 3.5): pixels, and / sqrt(W*H); gaps count; chain: 1 if one 8-connected chain.
  double lse_s = kNA, lse_u = kNA, extent_error = kNA, lse_s_norm = kNA, lse_u_norm = kNA;
  int chain_8connected = -1;  // -1 = not applicable
  int64_t gaps = -1;
  // Triangles (paper 3.6): px^2; / (W*H); TEu / visible edge length (pixels).
  double te_s = kNA, te_u = kNA, te_s_norm = kNA, te_u_norm = kNA, te_u_edge_norm = kNA;
  int full_window = -1, simply_connected = -1;
  // Pixels in the symmetric difference with the reference rasterizer (0 = conformant).
  int64_t ref_diff = -1;
  uint64_t pixel_hash = 0;  // FNV-1a of the sorted lit pixels (exact comparison across runs)
  double render_us = kNA;   // the drawing's time on `clock`, microseconds (a batch's share)
  int64_t batch_size = 0;   // primitives drawn under that one wait (1: alone; 0: not drawn)
  Conformance conformance = Conformance::kNotCompared;
  int64_t violating_pixels = -1;  // pixels of the verdict kViolation (0 otherwise; -1 not compared)
  std::string violated_rules;     // the rules broken, '+'-joined (conformance.h); empty if none
  // The host's CPU time of draw and wait, microseconds, this primitive's share of its batch;
  // equal to render_us where `clock` is "host".
  double host_us = kNA;
  std::string clock;  // "host" or "device" (render_us from the device's timestamps); "" not drawn
};

// The columns of a records row, in file order (records_header() spells them).
enum class RecordColumn : std::size_t {
  kPlatform, kView, kViewGroup, kOrientation, kFovDeg, kWidth, kHeight, kNear, kFar, kKind,
  kIndex, kStatus, kVisibility, kPixels, kPe, kPeNorm, kLseS, kLseU, kExtentError, kLseSNorm,
  kLseUNorm, kChain8Connected, kGaps, kTeS, kTeU, kTeSNorm, kTeUNorm, kTeUEdgeNorm, kFullWindow,
  kSimplyConnected, kRefDiff, kPixelHash, kRenderUs, kBatchSize, kConformance, kViolatingPixels,
  kViolatedRules, kHostUs, kClock,
};
constexpr std::size_t kRecordColumnCount = 39;
// Version 2 files have the first 34 columns only, version 3 files the first 37.
constexpr std::size_t kRecordColumnCountV2 = 34;
constexpr std::size_t kRecordColumnCountV3 = 37;
const char* record_column_name(RecordColumn c);  // "platform", "view", ...
// The column called `name`, or nullopt.
std::optional<RecordColumn> find_record_column(std::string_view name);

std::string records_header();  // the header line, without newline
std::string records_header_v2();  // the header line of schema version 2 files
std::string records_header_v3();  // the header line of schema version 3 files
// One line, with newline. Numbers are written shortest round-trip (std::to_chars): each reads back
// as the very same double.
void write_record(std::ostream& out, const Record& r);
void append_record(std::string& out, const Record& r);  // the same line, appended to `out`
// The record's line with its timing columns (render_us, batch_size, host_us, clock) emptied:
// what two measurements of the same primitive on a deterministic driver agree on.
std::string untimed_record_line(Record r);

}  // namespace ra::metrics
