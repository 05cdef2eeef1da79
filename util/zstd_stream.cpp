#include "util/zstd_stream.h"

#include <zstd.h>

#include <fstream>
#include <memory>
#include <stdexcept>
#include <vector>

namespace ra::util {

bool has_zstd_extension(std::string_view path) {
  return path.size() >= 4 && path.substr(path.size() - 4) == ".zst";
}

ZstdFrameWriter::ZstdFrameWriter(std::ostream& out, int level) : out_(out), cctx_(ZSTD_createCCtx()) {
  if (!cctx_) throw std::runtime_error("zstd: cannot create a compression context");
  auto* c = static_cast<ZSTD_CCtx*>(cctx_);
  ZSTD_CCtx_setParameter(c, ZSTD_c_compressionLevel, level);
  ZSTD_CCtx_setParameter(c, ZSTD_c_checksumFlag, 1);
  ZSTD_CCtx_setParameter(c, ZSTD_c_contentSizeFlag, 1);
}

ZstdFrameWriter::~ZstdFrameWriter() { ZSTD_freeCCtx(static_cast<ZSTD_CCtx*>(cctx_)); }

void ZstdFrameWriter::end_frame() {
  if (pending_.empty()) return;
  compressed_.resize(ZSTD_compressBound(pending_.size()));
  const size_t n = ZSTD_compress2(static_cast<ZSTD_CCtx*>(cctx_), compressed_.data(),
                                  compressed_.size(), pending_.data(), pending_.size());
  if (ZSTD_isError(n)) throw std::runtime_error(std::string("zstd: ") + ZSTD_getErrorName(n));
  out_.write(compressed_.data(), std::streamsize(n));
  pending_.clear();
}

namespace {
struct DecompressionState {
  std::unique_ptr<ZSTD_DCtx, size_t (*)(ZSTD_DCtx*)> dctx{ZSTD_createDCtx(), ZSTD_freeDCtx};
  std::vector<char> src = std::vector<char>(std::size_t{1} << 20);
  std::vector<char> dst = std::vector<char>(std::size_t{1} << 20);
};
}  // namespace

void for_each_zstd_chunk(const std::string& path,
                         const std::function<void(std::string_view)>& chunk) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot read it");
  // One context and one pair of buffers per thread, kept: a run's hundreds of files would
  // otherwise map and fault in fresh megabytes each. A callback that reads another file meanwhile
  // gets fresh ones.
  thread_local DecompressionState cached;
  thread_local bool cached_in_use = false;
  std::unique_ptr<DecompressionState> fresh;
  DecompressionState* state = &cached;
  if (cached_in_use) {
    fresh = std::make_unique<DecompressionState>();
    state = fresh.get();
  }
  struct InUse {
    bool* flag;
    bool was;
    ~InUse() { *flag = was; }
  } in_use{&cached_in_use, cached_in_use};
  cached_in_use = true;
  if (!state->dctx) throw std::runtime_error("zstd: cannot create a decompression context");
  ZSTD_DCtx_reset(state->dctx.get(), ZSTD_reset_session_only);
  ZSTD_DCtx* const dctx = state->dctx.get();
  std::vector<char>& src = state->src;
  std::vector<char>& dst = state->dst;
  size_t last = 0;  // 0 once a frame is complete: a file may end there and only there
  bool any = false;
  while (in) {
    in.read(src.data(), std::streamsize(src.size()));
    const size_t got = size_t(in.gcount());
    if (got == 0) break;
    any = true;
    ZSTD_inBuffer input{src.data(), got, 0};
    while (input.pos < input.size) {
      ZSTD_outBuffer output{dst.data(), dst.size(), 0};
      last = ZSTD_decompressStream(dctx, &output, &input);
      if (ZSTD_isError(last))
        throw std::runtime_error(path + ": not a valid zstd file (" +
                                 ZSTD_getErrorName(last) + ")");
      if (output.pos > 0) chunk(std::string_view(dst.data(), output.pos));
    }
    // Flush what the context still holds for the input it has consumed.
    for (;;) {
      ZSTD_outBuffer output{dst.data(), dst.size(), 0};
      ZSTD_inBuffer none{nullptr, 0, 0};
      if (last == 0) break;
      last = ZSTD_decompressStream(dctx, &output, &none);
      if (ZSTD_isError(last))
        throw std::runtime_error(path + ": not a valid zstd file (" +
                                 ZSTD_getErrorName(last) + ")");
      if (output.pos > 0) chunk(std::string_view(dst.data(), output.pos));
      if (output.pos < output.size) break;  // it needs more input
    }
  }
  if (in.bad()) throw std::runtime_error(path + ": read error");
  if (!any) throw std::runtime_error(path + ": empty file (not a zstd file)");
  if (last != 0) throw std::runtime_error(path + ": the file ends inside a zstd frame (cut short)");
}

std::string read_zstd_file(const std::string& path) {
  std::string out;
  for_each_zstd_chunk(path, [&](std::string_view c) { out.append(c); });
  return out;
}

}  // namespace ra::util
