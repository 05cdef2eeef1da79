#include "rundir/shard_file.h"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "util/atomic_file.h"
#include "util/fnv1a.h"

namespace ra::rundir {
namespace {

constexpr std::string_view kTrailerPrefix = "# complete rows=";

// Hash and row count of the first `length` bytes of `in` (the header line excluded from rows),
// read in blocks: memory does not depend on the file's size.
struct BodyDigest {
  uint64_t hash = util::Fnv1a64::kOffsetBasis, rows = 0;
  bool ends_with_newline = true;
};
BodyDigest digest(std::istream& in, uint64_t length) {
  util::Fnv1a64 h;
  uint64_t lines = 0;
  char last = '\n';
  std::string block(1 << 20, '\0');
  while (length > 0) {
    const std::streamsize want = std::streamsize(std::min<uint64_t>(block.size(), length));
    in.read(block.data(), want);
    const std::streamsize got = in.gcount();
    if (got <= 0) break;
    h.add(block.data(), size_t(got));
    for (std::streamsize i = 0; i < got; ++i) lines += block[size_t(i)] == '\n';
    last = block[size_t(got) - 1];
    length -= uint64_t(got);
  }
  BodyDigest d;
  d.hash = h.value;
  d.ends_with_newline = last == '\n';
  if (!d.ends_with_newline) ++lines;
  d.rows = lines > 0 ? lines - 1 : 0;
  return d;
}

std::string trailer_of(const BodyDigest& d) {
  return std::string(kTrailerPrefix) + std::to_string(d.rows) + " fnv1a64=" + util::hex64(d.hash) +
         "\n";
}

// The digest of a decompressed stream whose last line is the trailer: every line but the most
// recent one is hashed as it arrives, so the trailer is known (and left out) at the end.
class HeldBackDigest {
 public:
  void add(std::string_view piece) {
    const size_t last = piece.rfind('\n');
    const size_t before = last == 0 || last == std::string_view::npos
                              ? std::string_view::npos
                              : piece.rfind('\n', last - 1);
    if (before == std::string_view::npos) {  // at most one line ends here: keep it all for now
      held_.append(piece);
      return;
    }
    // Everything up to the piece's second-to-last line end is known not to be the trailer.
    take(held_);
    take(piece.substr(0, before + 1));
    held_.assign(piece.substr(before + 1));
  }
  // The last line (with its '\n', or without one when the stream ends mid-line) and the digest of
  // everything before it; `first_row` and `last_row`: the first and last lines after the header
  // before it (without '\n'; empty when there are none).
  BodyDigest finish(std::string* last_line, std::string* first_row, std::string* last_row) {
    const size_t last = held_.rfind('\n', held_.size() >= 2 ? held_.size() - 2 : 0);
    const size_t cut = held_.size() >= 2 && last != std::string::npos ? last + 1 : 0;
    take(std::string_view(held_).substr(0, cut));
    *last_line = held_.substr(cut);
    const size_t header_end = head_.find('\n');
    const size_t row_end =
        header_end == std::string::npos ? header_end : head_.find('\n', header_end + 1);
    *first_row = row_end != std::string::npos
                     ? head_.substr(header_end + 1, row_end - header_end - 1)
                     : std::string();
    *last_row = lines_ >= 2 ? last_complete_ : "";
    BodyDigest d;
    d.hash = hash_.value;
    d.rows = lines_ > 0 ? lines_ - 1 : 0;
    return d;
  }

 private:
  static constexpr size_t kLongestRowKept = 1 << 16;  // a row is about 200 bytes

  void take(std::string_view bytes) {
    hash_.add(bytes);
    const uint64_t before = lines_;
    lines_ += uint64_t(std::count(bytes.begin(), bytes.end(), '\n'));
    // the header and the first row
    if (before < 2 && head_.size() < 2 * kLongestRowKept) {
      head_.append(bytes.substr(0, 2 * kLongestRowKept - head_.size()));
      const size_t header_end = head_.find('\n');
      const size_t row_end = header_end == std::string::npos ? header_end
                                                             : head_.find('\n', header_end + 1);
      if (row_end != std::string::npos) head_.resize(row_end + 1);
    }
    // the last complete line so far, and the line begun after it
    const size_t end = bytes.rfind('\n');
    if (end == std::string_view::npos) {
      if (partial_.size() < kLongestRowKept) partial_.append(bytes.substr(0, kLongestRowKept));
      return;
    }
    const size_t start = end == 0 ? std::string_view::npos : bytes.rfind('\n', end - 1);
    if (start == std::string_view::npos)
      last_complete_ = partial_ + std::string(bytes.substr(0, end));
    else
      last_complete_.assign(bytes.substr(start + 1, end - start - 1));
    partial_.assign(bytes.substr(end + 1, kLongestRowKept));
  }
  util::Fnv1a64 hash_;
  uint64_t lines_ = 0;
  std::string held_;  // the last line or two seen, not yet hashed
  std::string head_;  // the first two lines hashed (the header and the first row)
  std::string last_complete_, partial_;  // the last whole line hashed, and the one begun after it
};

// The seal of the file at `path` (decompressed when it is a .csv.zst one), or why it cannot be read.
std::string read_seal(const std::string& path, ShardSeal* out) {
  ShardSealReader seal;
  if (util::has_zstd_extension(path)) {
    try {
      util::for_each_zstd_chunk(path, [&](std::string_view c) { seal.add(c); });
    } catch (const std::runtime_error& e) {
      const std::string what = e.what();
      if (what.find("cut short") != std::string::npos) return "no trailer (the file was cut short)";
      return "damaged: " + what.substr(std::min(what.size(), path.size() + 2));
    }
  } else {
    std::ifstream in(path, std::ios::binary);
    if (!in) return "cannot read it";
    std::string block(1 << 20, '\0');
    while (in) {
      in.read(block.data(), std::streamsize(block.size()));
      if (in.gcount() <= 0) break;
      seal.add(std::string_view(block.data(), size_t(in.gcount())));
    }
    if (in.bad()) return "cannot read it";
  }
  *out = seal.finish();
  return "";
}

// The cells a row names its primitive by: platform, view, kind, index ("" for a row too short).
struct RowIdentity {
  std::string platform, view, kind, index;
};
RowIdentity row_identity(std::string_view row) {
  std::vector<std::string_view> cells;
  for (size_t start = 0; cells.size() <= size_t(metrics::RecordColumn::kIndex);) {
    const size_t comma = row.find(',', start);
    cells.push_back(row.substr(start, comma == std::string_view::npos ? row.npos : comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  if (cells.size() <= size_t(metrics::RecordColumn::kIndex)) return {};
  const auto cell = [&](metrics::RecordColumn c) { return std::string(cells[size_t(c)]); };
  return {cell(metrics::RecordColumn::kPlatform), cell(metrics::RecordColumn::kView),
          cell(metrics::RecordColumn::kKind), cell(metrics::RecordColumn::kIndex)};
}

std::string primitive_words(const RowIdentity& r) {
  return r.kind + " " + r.index + " of view " + r.view + " on " + r.platform;
}

// Empty when `row` records primitive `index` of shard `s`; otherwise what it records instead.
std::string row_mismatch(std::string_view row, const Shard& s, uint64_t index, const char* which) {
  const RowIdentity got = row_identity(row);
  const RowIdentity want{s.platform, std::to_string(s.view), geometry::kind_name(s.kind),
                         std::to_string(index)};
  if (got.platform == want.platform && got.view == want.view && got.kind == want.kind &&
      got.index == want.index)
    return "";
  return std::string("its ") + which + " row records " +
         (got.index.empty() ? std::string("no primitive") : primitive_words(got)) + " where shard " +
         s.id() + "'s records " + primitive_words(want);
}

}  // namespace

RecordsFileWriter::RecordsFileWriter(const std::string& path, rundir::RecordsFormat format)
    : path_(path), out_(path, std::ios::binary | std::ios::trunc) {
  if (!out_) throw std::runtime_error(util::io_error_message("cannot open", path));
  if (format == rundir::RecordsFormat::kCsvZst)
    zstd_ = std::make_unique<util::ZstdFrameWriter>(out_);
  put(metrics::records_header() + "\n");
}

void RecordsFileWriter::put(std::string_view bytes) {
  hash_.add(bytes);
  if (zstd_)
    zstd_->write(bytes);
  else
    out_.write(bytes.data(), std::streamsize(bytes.size()));
}

void RecordsFileWriter::write(const metrics::Record& r) {
  line_.clear();
  metrics::append_record(line_, r);
  put(line_);
  if (++rows_ % kRowsPerFrame == 0 && zstd_) zstd_->end_frame();
}

uint64_t RecordsFileWriter::finish() {
  BodyDigest d;
  d.hash = hash_.value;
  d.rows = rows_;
  const std::string trailer = trailer_of(d);
  if (zstd_) {
    zstd_->end_frame();
    zstd_->write(trailer);
    zstd_->end_frame();
  } else {
    out_ << trailer;
  }
  out_.close();
  if (!out_) throw std::runtime_error(util::io_error_message("cannot write", path_));
  return rows_;
}

std::string shard_trailer(std::string_view body, uint64_t rows) {
  util::Fnv1a64 h;
  h.add(body);
  BodyDigest d;
  d.hash = h.value;
  d.rows = rows;
  return trailer_of(d);
}

uint64_t seal_shard_file(const std::string& path) {
  BodyDigest d;
  {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    d = digest(in, UINT64_MAX);
    if (in.bad()) throw std::runtime_error("cannot read " + path);
  }
  std::ofstream out(path, std::ios::binary | std::ios::app);
  if (!d.ends_with_newline) out << '\n';  // never: records end their lines; kept exact anyway
  out << trailer_of(d);
  out.close();
  if (!out) throw std::runtime_error(util::io_error_message("cannot write", path));
  return d.rows;
}

std::string check_shard_file(const std::string& path, uint64_t expected_rows) {
  ShardSeal seal;
  if (std::string why = read_seal(path, &seal); !why.empty()) return why;
  return seal_verdict(seal, expected_rows, util::has_zstd_extension(path));
}

std::string check_shard_file(const std::string& path, const Shard& s) {
  ShardSeal seal;
  if (std::string why = read_seal(path, &seal); !why.empty()) return why;
  return seal_verdict(seal, s, util::has_zstd_extension(path));
}

struct ShardSealReader::Digest {
  HeldBackDigest held;
};

ShardSealReader::ShardSealReader() : digest_(std::make_unique<Digest>()) {}
ShardSealReader::~ShardSealReader() = default;

void ShardSealReader::add(std::string_view piece) { digest_->held.add(piece); }

ShardSeal ShardSealReader::finish() {
  ShardSeal seal;
  const BodyDigest d = digest_->held.finish(&seal.last_line, &seal.first_row, &seal.last_row);
  seal.hash = d.hash;
  seal.rows = d.rows;
  return seal;
}

std::string seal_verdict(const ShardSeal& seal, uint64_t expected_rows, bool compressed) {
  const std::string& trailer = seal.last_line;
  if (trailer.empty() || trailer.back() != '\n') return "no trailer (the file was cut short)";
  // a plain file of one short line (the header alone) was cut short; a longer unsealed one may
  // predate the seal
  const bool one_short_line =
      seal.rows == 0 && seal.hash == util::Fnv1a64::kOffsetBasis && trailer.size() <= 256;
  if (trailer.compare(0, kTrailerPrefix.size(), kTrailerPrefix) != 0)
    return compressed || one_short_line
               ? "no trailer (the file was cut short)"
               : "no trailer (the file was cut short, or written before records were sealed)";
  BodyDigest d;
  d.hash = seal.hash;
  d.rows = seal.rows;
  if (trailer != trailer_of(d))
    return "its trailer does not match its contents (" + std::to_string(d.rows) +
           " rows: damaged, or written by two processes at once)";
  if (d.rows != expected_rows)
    return "it holds " + std::to_string(d.rows) + " rows where the shard has " +
           std::to_string(expected_rows) + " primitives";
  return "";
}

std::string seal_verdict(const ShardSeal& seal, const Shard& s, bool compressed) {
  if (std::string why = seal_verdict(seal, s.size(), compressed); !why.empty()) return why;
  if (s.size() == 0) return "";
  // The hash proves the rows are those the writer wrote, in its order (by index); the first and
  // last prove which shard it wrote them for.
  std::string why = row_mismatch(seal.first_row, s, s.begin, "first");
  if (why.empty()) why = row_mismatch(seal.last_row, s, s.end - 1, "last");
  if (why.empty()) return "";
  return why + ": these are another shard's records under this shard's name (copied or renamed)";
}

}  // namespace ra::rundir
