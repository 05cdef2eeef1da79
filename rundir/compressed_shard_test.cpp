// Tests of compressed shard files (rundir/shard_file.h's RecordsFileWriter, util/zstd_stream.h,
// rundir/records_reader.h): every column comes back bit for bit in both formats, the file is made
// of independent frames, and a cut, edited or interleaved compressed file fails its seal.
#include <gtest/gtest.h>
#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "metrics/records.h"
#include "rundir/records_reader.h"
#include "rundir/shard_file.h"
#include "util/errors.h"
#include "util/zstd_stream.h"

namespace ra::rundir {
namespace {

uint64_t bits(double v) {
  uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  return b;
}

// Doubles whose text is easy to get wrong: signed zero, the smallest and largest subnormals, the
// smallest normal, the largest finite, values with 17 significant digits, and exact integers.
const double kHardValues[] = {-0.0,
                              0.0,
                              std::numeric_limits<double>::denorm_min(),
                              -std::numeric_limits<double>::denorm_min(),
                              2.2250738585072009e-308,  // largest subnormal
                              std::numeric_limits<double>::min(),
                              std::numeric_limits<double>::max(),
                              -std::numeric_limits<double>::max(),
                              0.1,
                              1.0 / 3.0,
                              2.0 / 3.0 * 1e-300,
                              9007199254740993.0,  // 2^53 + 1 rounds to 2^53
                              123456.78901234567,
                              5e-324 * 3,
                              1e22,
                              -1.7976931348623155e308};

// Records that put each hard value into each double column, and extreme integers into each
// integer column.
std::vector<metrics::Record> hard_records() {
  std::vector<metrics::Record> out;
  const size_t n = sizeof kHardValues / sizeof kHardValues[0];
  for (size_t i = 0; i < n; ++i) {
    metrics::Record r;
    r.platform = "osmesa-llvmpipe";
    r.kind = "triangle";
    r.index = i == 0 ? std::numeric_limits<uint64_t>::max() : i;
    auto v = [&](size_t k) { return kHardValues[(i + k) % n]; };
    r.view = int(i) - 3;
    r.view_group = std::numeric_limits<int>::max();
    r.orientation = std::numeric_limits<int>::min();
    r.fov_deg = v(0);
    r.width = 907;
    r.height = -1;
    r.near = v(1);
    r.far = v(2);
    r.status = metrics::CaseStatus(i % 4);
    r.visibility = metrics::Visibility(i % 5);
    r.pixels = std::numeric_limits<int64_t>::min();
    r.pe = v(3), r.pe_norm = v(4), r.lse_s = v(5), r.lse_u = v(6), r.extent_error = v(7);
    r.lse_s_norm = v(8), r.lse_u_norm = v(9);
    r.chain_8connected = i % 2 ? -1 : 1;
    r.gaps = std::numeric_limits<int64_t>::max();
    r.te_s = v(10), r.te_u = v(11), r.te_s_norm = v(12), r.te_u_norm = v(13);
    r.te_u_edge_norm = i % 3 ? v(14) : metrics::kNA;  // an empty cell too
    r.full_window = 0, r.simply_connected = 1;
    r.ref_diff = int64_t(i);
    r.pixel_hash = std::numeric_limits<uint64_t>::max() - i;
    r.render_us = v(15);
    r.batch_size = int64_t(i);
    r.conformance = metrics::Conformance(i % 5);
    r.violating_pixels = int64_t(i) - 1;
    r.violated_rules = i % 2 ? "gl-polygon-rule+gl-line-diamond" : "";
    out.push_back(r);
  }
  return out;
}

void expect_same(const metrics::Record& a, const metrics::Record& b) {
  const double da[] = {a.fov_deg, a.near, a.far, a.pe, a.pe_norm, a.lse_s, a.lse_u, a.extent_error,
                       a.lse_s_norm, a.lse_u_norm, a.te_s, a.te_u, a.te_s_norm, a.te_u_norm,
                       a.te_u_edge_norm, a.render_us};
  const double db[] = {b.fov_deg, b.near, b.far, b.pe, b.pe_norm, b.lse_s, b.lse_u, b.extent_error,
                       b.lse_s_norm, b.lse_u_norm, b.te_s, b.te_u, b.te_s_norm, b.te_u_norm,
                       b.te_u_edge_norm, b.render_us};
  for (size_t k = 0; k < sizeof da / sizeof da[0]; ++k) {
    if (std::isnan(da[k])) {
      EXPECT_TRUE(std::isnan(db[k])) << "double column " << k;
    } else {
      EXPECT_EQ(bits(da[k]), bits(db[k])) << "double column " << k << ": " << da[k];
    }
  }
  EXPECT_EQ(a.platform, b.platform);
  EXPECT_EQ(a.view, b.view);
  EXPECT_EQ(a.view_group, b.view_group);
  EXPECT_EQ(a.orientation, b.orientation);
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.index, b.index);
  EXPECT_EQ(a.status, b.status);
  EXPECT_EQ(a.visibility, b.visibility);
  EXPECT_EQ(a.pixels, b.pixels);
  EXPECT_EQ(a.chain_8connected, b.chain_8connected);
  EXPECT_EQ(a.gaps, b.gaps);
  EXPECT_EQ(a.full_window, b.full_window);
  EXPECT_EQ(a.simply_connected, b.simply_connected);
  EXPECT_EQ(a.ref_diff, b.ref_diff);
  EXPECT_EQ(a.pixel_hash, b.pixel_hash);
  EXPECT_EQ(a.batch_size, b.batch_size);
  EXPECT_EQ(a.conformance, b.conformance);
  EXPECT_EQ(a.violating_pixels, b.violating_pixels);
  EXPECT_EQ(a.violated_rules, b.violated_rules);
}

class CompressedShard : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string stem = (std::filesystem::temp_directory_path() /
                              ("ra_cshard_" + std::to_string(::getpid()))).string();
    zst_ = stem + ".csv.zst";
    csv_ = stem + ".csv";
  }
  void TearDown() override {
    std::filesystem::remove(zst_);
    std::filesystem::remove(csv_);
  }
  static uint64_t write(const std::string& path, const std::vector<metrics::Record>& rs,
                        rundir::RecordsFormat f) {
    RecordsFileWriter w(path, f);
    for (const metrics::Record& r : rs) w.write(r);
    return w.finish();
  }
  static std::vector<metrics::Record> read(const std::string& path) {
    std::vector<metrics::Record> rs;
    rundir::read_records(path, [&](const metrics::Record& r) { rs.push_back(r); });
    return rs;
  }
  static std::string bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
  }
  static void put(const std::string& path, const std::string& b) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << b;
  }
  // Many ordinary rows: enough for several frames.
  static std::vector<metrics::Record> many(size_t n) {
    std::vector<metrics::Record> rs(n);
    for (size_t i = 0; i < n; ++i) {
      rs[i].platform = "reference";
      rs[i].kind = "point";
      rs[i].index = i;
      rs[i].pe = double(i) / 7.0;
      rs[i].pixel_hash = i * 0x9e3779b97f4a7c15ull;
    }
    return rs;
  }
  std::string zst_, csv_;
};

TEST_F(CompressedShard, EveryColumnReadsBackBitIdenticalInBothFormats) {
  const std::vector<metrics::Record> rs = hard_records();
  for (const auto& [path, format] : {std::pair{zst_, rundir::RecordsFormat::kCsvZst},
                                     std::pair{csv_, rundir::RecordsFormat::kCsv}}) {
    SCOPED_TRACE(path);
    EXPECT_EQ(write(path, rs, format), rs.size());
    EXPECT_EQ(check_shard_file(path, rs.size()), "");
    const std::vector<metrics::Record> back = read(path);
    ASSERT_EQ(back.size(), rs.size());
    for (size_t i = 0; i < rs.size(); ++i) expect_same(rs[i], back[i]);
  }
  // The compressed file decompresses to the plain file's bytes exactly (seal included).
  EXPECT_EQ(util::read_zstd_file(zst_), bytes(csv_));
}

TEST_F(CompressedShard, NumbersAreWrittenShortestRoundTrip) {
  metrics::Record r;
  r.platform = "reference";
  r.kind = "point";
  r.pe = 0.1;          // "%.17g" would write 0.10000000000000001
  r.pe_norm = -0.0;    // the sign survives
  r.render_us = 5e-324;
  std::string line;
  metrics::append_record(line, r);
  EXPECT_NE(line.find(",0.1,-0,"), std::string::npos) << line;
  EXPECT_NE(line.find(",5e-324,"), std::string::npos) << line;
}

TEST_F(CompressedShard, AnInfinityIsRefusedOnRead) {
  // No records column allows an infinity: a written one must not read back as a number.
  metrics::Record r = hard_records()[1];
  r.pe = std::numeric_limits<double>::infinity();
  write(zst_, {r}, rundir::RecordsFormat::kCsvZst);
  try {
    read(zst_);
    FAIL() << "an infinite pe was accepted";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("column 'pe': 'inf' is not a finite number"),
              std::string::npos) << e.what();
  }
}

TEST_F(CompressedShard, RowsComeInIndependentFramesAndTheSealInALastOne) {
  const size_t n = 2 * kRowsPerFrame + 5;
  write(zst_, many(n), rundir::RecordsFormat::kCsvZst);
  const std::string b = bytes(zst_);
  std::vector<std::string> frames;
  for (size_t pos = 0; pos < b.size();) {
    const size_t len = ZSTD_findFrameCompressedSize(b.data() + pos, b.size() - pos);
    ASSERT_FALSE(ZSTD_isError(len));
    frames.push_back(b.substr(pos, len));
    pos += len;
  }
  ASSERT_EQ(frames.size(), 4u);  // 8192 rows (after the header), 8192, 5, the seal
  std::vector<std::string> text;
  for (const std::string& f : frames) {
    const unsigned long long size = ZSTD_getFrameContentSize(f.data(), f.size());
    ASSERT_NE(size, ZSTD_CONTENTSIZE_UNKNOWN);
    std::string out(size, '\0');
    ASSERT_EQ(ZSTD_decompress(out.data(), out.size(), f.data(), f.size()), size);
    EXPECT_EQ(out.back(), '\n');  // each frame ends at a line's end: rows never straddle frames
    text.push_back(out);
  }
  EXPECT_EQ(text[3].rfind("# complete rows=" + std::to_string(n) + " fnv1a64=", 0), 0u) << text[3];
  EXPECT_EQ(std::count(text[1].begin(), text[1].end(), '\n'), long(kRowsPerFrame));
  EXPECT_EQ(check_shard_file(zst_, n), "");
  EXPECT_EQ(read(zst_).size(), n);
}

TEST_F(CompressedShard, ACutFileFailsWhereverItIsCut) {
  write(zst_, many(kRowsPerFrame + 10), rundir::RecordsFormat::kCsvZst);
  const std::string b = bytes(zst_);
  // Cut inside a frame, and cut exactly where the seal's frame begins.
  size_t first = ZSTD_findFrameCompressedSize(b.data(), b.size());
  size_t second = ZSTD_findFrameCompressedSize(b.data() + first, b.size() - first);
  for (size_t keep : {b.size() - 3, first + second, first + 10, first, size_t{7}}) {
    SCOPED_TRACE(keep);
    put(zst_, b.substr(0, keep));
    EXPECT_NE(check_shard_file(zst_, kRowsPerFrame + 10).find("no trailer"), std::string::npos)
        << check_shard_file(zst_, kRowsPerFrame + 10);
  }
  // The reader refuses a file cut inside a frame, naming it.
  put(zst_, b.substr(0, first + 10));
  EXPECT_THROW(read(zst_), util::UserError);
}

TEST_F(CompressedShard, AnEditedFileFails) {
  const std::vector<metrics::Record> rs = many(100);
  write(zst_, rs, rundir::RecordsFormat::kCsvZst);
  const std::string b = bytes(zst_);
  // A byte changed inside the compressed data: the frame's checksum (or its decoding) fails.
  std::string flipped = b;
  flipped[b.size() / 3] ^= 0x20;
  put(zst_, flipped);
  EXPECT_NE(check_shard_file(zst_, 100), "");
  // The text edited and compressed again as valid zstd: the seal's hash fails.
  put(zst_, b);
  std::string text = util::read_zstd_file(zst_);
  text[text.find(",5,") + 1] = '6';
  {
    std::ofstream out(zst_, std::ios::binary | std::ios::trunc);
    util::ZstdFrameWriter z(out);
    z.write(text);
    z.end_frame();
  }
  EXPECT_NE(check_shard_file(zst_, 100).find("does not match"), std::string::npos)
      << check_shard_file(zst_, 100);
}

TEST_F(CompressedShard, TwoWritersInterleavedFail) {
  // Two whole sealed files one after the other (two writers appending to one name): the last
  // trailer covers the first file's bytes and its own seal line too, so the hash fails.
  write(zst_, many(10), rundir::RecordsFormat::kCsvZst);
  const std::string b = bytes(zst_);
  put(zst_, b + b);
  EXPECT_NE(check_shard_file(zst_, 10).find("does not match"), std::string::npos)
      << check_shard_file(zst_, 10);
}

// pandas (Debian's /usr/bin/python3 with python3-pandas and python3-zstandard) reads a compressed
// shard and gets the very same doubles: each value is printed by Python as float.hex() and parsed
// back here, bit for bit. Skipped where those modules are missing (ctest: records_pandas, exit 77).
TEST_F(CompressedShard, PandasReadsTheSameValues) {
  if (std::system("/usr/bin/python3 -c 'import pandas, zstandard' >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "/usr/bin/python3 lacks pandas or zstandard";
  const std::vector<metrics::Record> rs = hard_records();
  write(zst_, rs, rundir::RecordsFormat::kCsvZst);
  const std::string cmd =
      "/usr/bin/python3 -c \"import pandas as pd, sys\n"
      "df = pd.read_csv(sys.argv[1], comment='#', float_precision='round_trip', "
      "dtype={'pixel_hash': 'uint64', 'index': 'uint64'})\n"
      "for c in ['pe', 'te_s', 'far', 'render_us']:\n"
      "    print(' '.join(float(v).hex() for v in df[c]))\n"
      "print(' '.join(str(v) for v in df['pixel_hash']))\n"
      "print(len(df))\" " + zst_;
  FILE* p = ::popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, p)) > 0;) out.append(buf, n);
  ASSERT_EQ(::pclose(p), 0) << out;
  std::istringstream lines(out);
  const auto column = [&](double metrics::Record::*field) {
    std::string line, word;
    std::getline(lines, line);
    std::istringstream words(line);
    for (const metrics::Record& r : rs) {
      ASSERT_TRUE(words >> word);
      const double v = std::strtod(word.c_str(), nullptr);  // C reads Python's hex form
      if (std::isnan(r.*field))
        EXPECT_TRUE(std::isnan(v)) << word;
      else
        EXPECT_EQ(bits(v), bits(r.*field)) << word << " vs " << r.*field;
    }
  };
  column(&metrics::Record::pe);
  column(&metrics::Record::te_s);
  column(&metrics::Record::far);
  column(&metrics::Record::render_us);
  std::string line, word;
  std::getline(lines, line);
  std::istringstream hashes(line);
  for (const metrics::Record& r : rs) {
    ASSERT_TRUE(hashes >> word);
    EXPECT_EQ(std::strtoull(word.c_str(), nullptr, 10), r.pixel_hash);
  }
  std::getline(lines, line);
  EXPECT_EQ(line, std::to_string(rs.size()));
}

}  // namespace
}  // namespace ra::rundir
