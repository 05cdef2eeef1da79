// A shard's records file is trusted only when it is sealed: its last line is the trailer
//   # complete rows=N fnv1a64=HHHHHHHHHHHHHHHH
// where N counts the record rows (the header excluded) and the hash covers every byte before the
// trailer. A file cut short, concatenated, interleaved by two writers or edited by hand fails the
// check, and `run` redoes its shard instead of counting it. Readers of records skip lines that
// start with '#', so readers that skip comment lines read sealed files unchanged.
//
// A compressed shard file (<id>.csv.zst, util/zstd_stream.h) holds the very same bytes once
// decompressed: the header and the rows in frames of kRowsPerFrame rows each, then the trailer in
// a last frame of its own; the hash covers the decompressed bytes before the trailer. A cut file
// ends inside a frame or lacks the trailer's frame; a changed byte fails its frame's checksum or
// the hash.
#pragma once

#include <cstdint>
#include <fstream>
#include <memory>
#include <string>
#include <string_view>

#include "metrics/records.h"
#include "rundir/records_format.h"
#include "rundir/shard.h"
#include "util/fnv1a.h"
#include "util/zstd_stream.h"

namespace ra::rundir {

// Rows per zstd frame: about 1.3 MB of text, 0.2 MB compressed; a 5,000-primitive shard is one
// frame, so a reader splits work by file first and by frame within a large file.
constexpr uint64_t kRowsPerFrame = 8192;

// Writes a sealed records file at `path` (normally a temporary, committed by the caller) in
// `format`: the header, then write() for each row, then finish() for the seal.
class RecordsFileWriter {
 public:
  RecordsFileWriter(const std::string& path,
                    rundir::RecordsFormat format);  // throws std::runtime_error
  void write(const metrics::Record& r);
  // Writes the trailer and closes the file; returns the number of rows. Throws std::runtime_error
  // on I/O failure (the file is then incomplete: the caller removes it).
  uint64_t finish();

 private:
  void put(std::string_view bytes);
  std::string path_;
  std::ofstream out_;
  std::unique_ptr<util::ZstdFrameWriter> zstd_;  // null for plain CSV
  util::Fnv1a64 hash_;
  uint64_t rows_ = 0;
  std::string line_;
};

// The trailer line (with its '\n') for `body`, the file's bytes before it, holding `rows` rows.
// Used by tests to write sealed files by hand, as an independent check of RecordsFileWriter.
std::string shard_trailer(std::string_view body, uint64_t rows);

// Appends the trailer to the finished plain CSV file at `path` (a temporary, before it is committed);
// returns the number of rows. Throws std::runtime_error on I/O failure.
// Used by tests to seal hand-made shard files; run seals through RecordsFileWriter.
uint64_t seal_shard_file(const std::string& path);

// Empty when the file at `path` is sealed, its trailer matches its contents and it holds
// `expected_rows` rows; otherwise why not ("no trailer (cut short?)", "rows=... but ... expected",
// "hash mismatch", ...).
std::string check_shard_file(const std::string& path, uint64_t expected_rows);
// The same for the records of shard `s`, and the seal bound to the file's name: its first row
// records the shard's first primitive and its last row its last one (platform, view, kind and
// index). The writer writes a shard's rows in index order and the hash covers them all, so a
// sealed file of another shard (copied or renamed to this one's name) fails here.
std::string check_shard_file(const std::string& path, const Shard& s);

// What the seal check needs of a shard file's text: the hash and row count of everything before
// its last line, and that line (the trailer, when the file is sealed).
struct ShardSeal {
  uint64_t hash = util::Fnv1a64::kOffsetBasis;
  uint64_t rows = 0;
  std::string last_line;  // with its '\n'; without one when the text ends mid-line
  // the first and last rows before it (the header excluded), without '\n'; empty when none
  std::string first_row, last_row;
};

// The seal of a file's text read piece by piece (decompressed), for a reader that reads the whole
// file anyway (analyze checks the seals in the pass that loads the records): add() every piece in
// order, then finish().
class ShardSealReader {
 public:
  ShardSealReader();
  ~ShardSealReader();
  void add(std::string_view piece);
  ShardSeal finish();

 private:
  struct Digest;
  std::unique_ptr<Digest> digest_;
};

// check_shard_file's verdict on a seal read with ShardSealReader: empty when the trailer matches
// and counts `expected_rows` rows; otherwise why not, in check_shard_file's words. `compressed`:
// the file is a .csv.zst one.
std::string seal_verdict(const ShardSeal& seal, uint64_t expected_rows, bool compressed);
// The verdict of check_shard_file(path, s): the seal counts shard `s`'s rows and its first and last
// rows are the shard's first and last primitives.
std::string seal_verdict(const ShardSeal& seal, const Shard& s, bool compressed);

}  // namespace ra::rundir
