#include "runner/shard_file.h"

#include <algorithm>
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "util/atomic_file.h"
#include "util/fnv1a.h"

namespace ra {
namespace {

constexpr std::string_view kTrailerPrefix = "# complete rows=";

std::string hex64(uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016" PRIx64, v);
  return buf;
}

// Hash and row count of the first `length` bytes of `in` (the header line excluded from rows),
// read in blocks: memory does not depend on the file's size.
struct BodyDigest {
  uint64_t hash = Fnv1a64::kOffsetBasis, rows = 0;
  bool ends_with_newline = true;
};
BodyDigest digest(std::istream& in, uint64_t length) {
  Fnv1a64 h;
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
  return std::string(kTrailerPrefix) + std::to_string(d.rows) + " fnv1a64=" + hex64(d.hash) + "\n";
}

}  // namespace

std::string shard_trailer(std::string_view body, uint64_t rows) {
  Fnv1a64 h;
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
  if (!out) throw std::runtime_error(io_error_message("cannot write", path));
  return d.rows;
}

std::string check_shard_file(const std::string& path, uint64_t expected_rows) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) return "cannot read it";
  const uint64_t size = uint64_t(in.tellg());
  // The trailer is the last line: find where it starts in the last few hundred bytes.
  const uint64_t tail_len = std::min<uint64_t>(size, 256);
  std::string tail(tail_len, '\0');
  in.seekg(std::streamoff(size - tail_len));
  in.read(tail.data(), std::streamsize(tail_len));
  if (tail.empty() || tail.back() != '\n') return "no trailer (the file was cut short)";
  const size_t nl = tail.rfind('\n', tail.size() - 2);
  if (nl == std::string::npos && tail_len == size) return "no trailer (the file was cut short)";
  const size_t trailer_in_tail = nl == std::string::npos ? 0 : nl + 1;
  const std::string trailer = tail.substr(trailer_in_tail);
  if (trailer.compare(0, kTrailerPrefix.size(), kTrailerPrefix) != 0)
    return "no trailer (the file was cut short, or written before records were sealed)";
  in.clear();
  in.seekg(0);
  const BodyDigest d = digest(in, size - tail_len + trailer_in_tail);
  if (trailer != trailer_of(d))
    return "its trailer does not match its contents (" + std::to_string(d.rows) +
           " rows: damaged, or written by two processes at once)";
  if (d.rows != expected_rows)
    return "it holds " + std::to_string(d.rows) + " rows where the shard has " +
           std::to_string(expected_rows) + " primitives";
  return "";
}

}  // namespace ra
