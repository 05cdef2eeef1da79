// Block reading and in-place splitting of records files (see the header).
#include "rundir/records_reader.h"

#include <cmath>
#include <cstring>
#include <fstream>
#include <vector>

#include "util/errors.h"
#include "util/zstd_stream.h"

namespace ra::rundir {

std::optional<double> RecordRow::number(metrics::RecordColumn c) const {
  const std::string_view f = cell(c);
  if (f.empty()) return std::nullopt;
  double v = 0;
  const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
  if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v)) {
    fail("column '" + std::string(metrics::record_column_name(c)) + "': '" + std::string(f) +
         "' is not a finite number");
  }
  return v;
}

double RecordRow::required_number(metrics::RecordColumn c) const {
  const std::optional<double> v = number(c);
  if (!v) fail("column '" + std::string(metrics::record_column_name(c)) + "' is empty");
  return *v;
}

metrics::CaseStatus RecordRow::status() const {
  const std::string_view s = cell(metrics::RecordColumn::kStatus);
  for (int i = 0; i < 4; ++i)
    if (s == metrics::status_name(static_cast<metrics::CaseStatus>(i))) return static_cast<metrics::CaseStatus>(i);
  fail("unknown status '" + std::string(s) + "' (allowed: ok, invalid, crash, timeout)");
}

metrics::Visibility RecordRow::visibility() const {
  const std::string_view s = cell(metrics::RecordColumn::kVisibility);
  for (int i = 0; i < 5; ++i)
    if (s == metrics::visibility_name(static_cast<metrics::Visibility>(i))) return static_cast<metrics::Visibility>(i);
  fail("unknown visibility '" + std::string(s) +
       "' (allowed: true-visible, true-invisible, false-visible, false-invisible, "
       "multiple-visible)");
}

metrics::Conformance RecordRow::conformance() const {
  metrics::Conformance c = metrics::Conformance::kNotCompared;
  const std::string_view s = cell(metrics::RecordColumn::kConformance);
  if (!metrics::parse_conformance(s, &c))
    fail("unknown conformance '" + std::string(s) +
         "' (allowed: exact, snapped, within-spec, violation, or empty)");
  return c;
}

void RecordRow::fail(const std::string& why) const {
  throw util::UserError(*file_ + ":" + std::to_string(line_) + ": " + why);
}

void RecordRow::not_an_integer(metrics::RecordColumn c) const {
  fail("column '" + std::string(metrics::record_column_name(c)) + "': '" + std::string(cell(c)) +
       "' is not an integer");
}

// Feeds lines to a RecordRow and the caller's callback.
class RecordsFileReader {
 public:
  RecordsFileReader(const std::string& path, const std::function<void(const RecordRow&)>& row,
                    const std::function<void(std::string_view)>* text = nullptr)
      : path_(path),
        callback_(row),
        text_(text),
        header_(metrics::records_header()),
        header_v2_(metrics::records_header_v2()),
        header_v3_(metrics::records_header_v3()) {
    row_.file_ = &path_;
  }

  void read() {
    if (util::has_zstd_extension(path_)) {
      try {
        util::for_each_zstd_chunk(path_, [this](std::string_view c) { feed(c); });
      } catch (const std::runtime_error& e) {
        if (dynamic_cast<const util::UserError*>(&e)) throw;
        throw util::UserError(e.what());
      }
    } else {
      std::ifstream in(path_, std::ios::binary);
      if (!in) throw util::UserError(path_ + ": cannot read records file");
      std::vector<char> block(std::size_t{4} << 20);
      while (in) {
        in.read(block.data(), static_cast<std::streamsize>(block.size()));
        const std::size_t n = static_cast<std::size_t>(in.gcount());
        if (n == 0) break;
        feed(std::string_view(block.data(), n));
      }
      if (in.bad()) throw util::UserError(path_ + ": read error");
    }
    if (!carry_.empty()) line(carry_);
    if (row_.line_ == 0) bad_header();
  }

 private:
  // Splits a piece of the file's text into lines; a line cut by the piece's end waits in carry_.
  void feed(std::string_view block) {
    if (text_ != nullptr) (*text_)(block);
    std::size_t start = 0;
    const std::size_t n = block.size();
    for (;;) {
      const void* found = std::memchr(block.data() + start, '\n', n - start);
      if (!found) break;
      const std::size_t end =
          static_cast<std::size_t>(static_cast<const char*>(found) - block.data());
      if (carry_.empty()) {
        line(block.substr(start, end - start));
      } else {
        carry_.append(block.data() + start, end - start);
        line(carry_);
        carry_.clear();
      }
      start = end + 1;
    }
    carry_.append(block.data() + start, n - start);
  }

  [[noreturn]] void bad_header() const {
    throw util::UserError(path_ + ":1: unexpected records header (schema version " +
                          std::to_string(metrics::kRecordsSchemaVersion) + " expects: " + header_ + ")");
  }

  void line(std::string_view text) {
    ++row_.line_;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (row_.line_ == 1) {
      if (text == header_v2_)
        columns_ = metrics::kRecordColumnCountV2;  // the later cells stay empty: "not compared"
      else if (text == header_v3_)
        columns_ = metrics::kRecordColumnCountV3;
      else if (text != header_)
        bad_header();
      return;
    }
    if (!text.empty() && text.front() == '#') return;  // the seal of a shard file
    std::size_t n = 0;
    std::size_t start = 0;
    for (;;) {
      const std::size_t comma = text.find(',', start);
      if (n < metrics::kRecordColumnCount) {
        row_.cells_[n] =
            text.substr(start, comma == std::string_view::npos ? comma : comma - start);
      }
      ++n;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (n != columns_) {
      row_.fail("expected " + std::to_string(columns_) + " fields, found " +
                std::to_string(n));
    }
    callback_(row_);
  }

  const std::string path_;
  const std::function<void(const RecordRow&)>& callback_;
  const std::function<void(std::string_view)>* text_;  // may be null
  const std::string header_, header_v2_, header_v3_;
  std::size_t columns_ = metrics::kRecordColumnCount;
  std::string carry_;  // an incomplete line from the previous piece
  RecordRow row_;
};

int records_schema_version(const std::string& path) {
  std::string first;
  bool done = false;
  const auto take = [&](std::string_view c) {
    if (done) return;
    const std::size_t nl = c.find('\n');
    first.append(c.substr(0, nl));
    done = nl != std::string_view::npos;
  };
  if (util::has_zstd_extension(path)) {
    struct HeaderRead {};  // stops decompressing once the first line is in
    try {
      util::for_each_zstd_chunk(path, [&](std::string_view c) {
        take(c);
        if (done) throw HeaderRead{};
      });
    } catch (const HeaderRead&) {
    } catch (const std::runtime_error&) {
      if (!done) return 0;
    }
  } else {
    std::ifstream in(path, std::ios::binary);
    std::getline(in, first);
  }
  if (!first.empty() && first.back() == '\r') first.pop_back();
  if (first == metrics::records_header()) return metrics::kRecordsSchemaVersion;
  if (first == metrics::records_header_v3()) return 3;
  if (first == metrics::records_header_v2()) return 2;
  return 0;
}

void for_each_record_row(const std::string& path,
                         const std::function<void(const RecordRow&)>& row) {
  RecordsFileReader(path, row).read();
}

void for_each_record_row(const std::string& path, const std::function<void(const RecordRow&)>& row,
                         const std::function<void(std::string_view)>& text) {
  RecordsFileReader(path, row, &text).read();
}

metrics::Record parse_record(const RecordRow& row) {
  using C = metrics::RecordColumn;
  const auto number = [&](C c) { return row.number(c).value_or(metrics::kNA); };
  metrics::Record r;
  r.platform = std::string(row.cell(C::kPlatform));
  r.view = row.integer<int>(C::kView);
  r.view_group = row.integer<int>(C::kViewGroup);
  r.orientation = row.integer<int>(C::kOrientation);
  r.fov_deg = number(C::kFovDeg);
  r.width = row.integer<int>(C::kWidth);
  r.height = row.integer<int>(C::kHeight);
  r.near = number(C::kNear);
  r.far = number(C::kFar);
  r.kind = std::string(row.cell(C::kKind));
  r.index = row.integer<uint64_t>(C::kIndex);
  r.status = row.status();
  r.visibility = row.visibility();
  r.pixels = row.integer<int64_t>(C::kPixels);
  r.pe = number(C::kPe);
  r.pe_norm = number(C::kPeNorm);
  r.lse_s = number(C::kLseS);
  r.lse_u = number(C::kLseU);
  r.extent_error = number(C::kExtentError);
  r.lse_s_norm = number(C::kLseSNorm);
  r.lse_u_norm = number(C::kLseUNorm);
  r.chain_8connected = row.optional_integer<int>(C::kChain8Connected, -1);
  r.gaps = row.optional_integer<int64_t>(C::kGaps, -1);
  r.te_s = number(C::kTeS);
  r.te_u = number(C::kTeU);
  r.te_s_norm = number(C::kTeSNorm);
  r.te_u_norm = number(C::kTeUNorm);
  r.te_u_edge_norm = number(C::kTeUEdgeNorm);
  r.full_window = row.optional_integer<int>(C::kFullWindow, -1);
  r.simply_connected = row.optional_integer<int>(C::kSimplyConnected, -1);
  r.ref_diff = row.optional_integer<int64_t>(C::kRefDiff, -1);
  r.pixel_hash = row.integer<uint64_t>(C::kPixelHash);
  r.render_us = number(C::kRenderUs);
  r.batch_size = row.optional_integer<int64_t>(C::kBatchSize, 0);
  r.conformance = row.conformance();
  r.violating_pixels = row.optional_integer<int64_t>(C::kViolatingPixels, -1);
  r.violated_rules = std::string(row.cell(C::kViolatedRules));
  r.host_us = number(C::kHostUs);
  r.clock = std::string(row.cell(C::kClock));
  return r;
}

void read_records(const std::string& path, const std::function<void(const metrics::Record&)>& row) {
  for_each_record_row(path, [&](const RecordRow& cells) { row(parse_record(cells)); });
}

}  // namespace ra::rundir
