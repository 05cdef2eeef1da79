// Zstandard files as this project writes and reads them: a sequence of independent frames (the
// zstd format's own concatenation rule), each compressed alone at level 1 with its content size
// and a content checksum, so that a reader may decompress frames on different threads, and a
// flipped byte anywhere fails the frame's checksum. Any .zst file (one frame or many, written by
// the `zstd` tool, by python-zstandard, by DuckDB) reads through for_each_zstd_chunk.
#pragma once

#include <cstddef>
#include <functional>
#include <ostream>
#include <string>
#include <string_view>

namespace ra::util {

// True when `path` ends with ".zst".
bool has_zstd_extension(std::string_view path);

// Buffers what is written and compresses it as one frame at each end_frame() (and on finish()).
// Writes to a stream the caller owns; throws std::runtime_error when compression fails.
class ZstdFrameWriter {
 public:
  explicit ZstdFrameWriter(std::ostream& out, int level = 1);
  ~ZstdFrameWriter();
  ZstdFrameWriter(const ZstdFrameWriter&) = delete;
  ZstdFrameWriter& operator=(const ZstdFrameWriter&) = delete;

  void write(std::string_view bytes) { pending_.append(bytes); }
  // Compresses what was written since the last frame into a frame of its own (nothing if empty).
  void end_frame();

 private:
  std::ostream& out_;
  void* cctx_;  // ZSTD_CCtx
  std::string pending_, compressed_;
};

// Decompresses the file at `path` (every frame, in order) and calls `chunk` with the decompressed
// bytes, a piece at a time (pieces end anywhere, not at line ends). Throws std::runtime_error
// "PATH: ..." when the file cannot be read, is not zstd, fails a checksum, or ends inside a frame
// ("cut short").
void for_each_zstd_chunk(const std::string& path,
                         const std::function<void(std::string_view)>& chunk);

// The whole decompressed content of the file at `path` (errors as for_each_zstd_chunk).
std::string read_zstd_file(const std::string& path);

}  // namespace ra::util
