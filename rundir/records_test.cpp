// Tests of the records reader (rundir/records_reader.h, and its read_records): CRLF
// files read as LF ones (audit once rejected what analyze accepted), the seal line of a shard file
// is skipped, a bad number names its column and line, every column survives a write and a read, and
// a row that straddles two 4 MiB blocks is read whole.
#include "metrics/records.h"

#include <gtest/gtest.h>

#include <cmath>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "rundir/records_reader.h"
#include "util/errors.h"

namespace ra::rundir {
namespace {

class RecordsReader : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (std::filesystem::temp_directory_path() /
             ("ra_records_" + std::to_string(::getpid()) + ".csv")).string();
    metrics::Record a, b;
    a.platform = b.platform = "reference";
    a.kind = b.kind = "point";
    a.index = 4;
    b.index = 5;
    a.pe = 0.25;
    std::ostringstream out;
    out << metrics::records_header() << '\n';
    metrics::write_record(out, a);
    metrics::write_record(out, b);
    text_ = out.str();
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::vector<metrics::Record> read(const std::string& text) {
    std::ofstream(path_, std::ios::binary) << text;
    std::vector<metrics::Record> rows;
    read_records(path_, [&](const metrics::Record& r) { rows.push_back(r); });
    return rows;
  }
  std::string path_, text_;
};

TEST_F(RecordsReader, CrlfAndTheSealLineReadAsThePlainFile) {
  const auto plain = read(text_);
  ASSERT_EQ(plain.size(), 2u);
  std::string crlf;
  for (char c : text_) crlf += c == '\n' ? std::string("\r\n") : std::string(1, c);
  const auto windows = read(crlf + "# complete rows=2 fnv1a64=0000000000000000\r\n");
  ASSERT_EQ(windows.size(), 2u);
  EXPECT_EQ(windows[0].index, 4u);
  EXPECT_EQ(windows[0].pe, 0.25);
  EXPECT_EQ(windows[1].index, 5u);
}

TEST_F(RecordsReader, ABadNumberNamesItsColumnAndLine) {
  std::string bad = text_;
  const auto row3 = bad.find("reference,", bad.find("reference,") + 1);  // the second record
  bad.replace(bad.find(",point,5,", row3), 9, ",point,x5,");
  try {
    read(bad);
    FAIL() << "a bad index was accepted";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()), path_ + ":3: column 'index': 'x5' is not an integer");
  }
}

TEST_F(RecordsReader, EveryColumnSurvivesAWriteAndARead) {
  metrics::Record r;
  r.platform = "osmesa-llvmpipe";
  r.view = 7;
  r.view_group = 3;
  r.orientation = 2;
  r.fov_deg = 150;
  r.width = 907;
  r.height = 907;
  r.near = 0.1;
  r.far = 1e6;
  r.kind = "triangle";
  r.index = 123456789012ull;
  r.status = metrics::CaseStatus::kTimeout;
  r.visibility = metrics::Visibility::kMultipleVisible;
  r.pixels = 42;
  r.pe = 0.1, r.pe_norm = 0.2, r.lse_s = 0.3, r.lse_u = 0.4, r.extent_error = 0.5;
  r.lse_s_norm = 1.0 / 3, r.lse_u_norm = 2e-300;
  r.chain_8connected = 1;
  r.gaps = 0;
  r.te_s = 5, r.te_u = 6, r.te_s_norm = 7, r.te_u_norm = 8, r.te_u_edge_norm = 9.5;
  r.full_window = 0;
  r.simply_connected = 1;
  r.ref_diff = 3;
  r.pixel_hash = 18446744073709551615ull;
  r.render_us = 12.75;
  r.batch_size = 64;
  r.conformance = metrics::Conformance::kViolation;
  r.violating_pixels = 7;
  r.violated_rules = "line-deviation+line-count";
  r.host_us = 0.5;
  r.clock = "device";
  std::ostringstream out;
  out << metrics::records_header() << '\n';
  metrics::write_record(out, r);
  const auto rows = read(out.str());
  ASSERT_EQ(rows.size(), 1u);
  std::ostringstream again;
  metrics::write_record(again, rows[0]);
  std::ostringstream first;
  metrics::write_record(first, r);
  EXPECT_EQ(again.str(), first.str());
  EXPECT_EQ(rows[0].pixel_hash, r.pixel_hash);
  EXPECT_EQ(rows[0].lse_u_norm, 2e-300);
  EXPECT_EQ(rows[0].status, metrics::CaseStatus::kTimeout);
  EXPECT_EQ(rows[0].conformance, metrics::Conformance::kViolation);
  EXPECT_EQ(rows[0].violating_pixels, 7);
  EXPECT_EQ(rows[0].violated_rules, "line-deviation+line-count");
  EXPECT_EQ(rows[0].host_us, 0.5);
  EXPECT_EQ(rows[0].clock, "device");
}

// Schema version 2 files (34 columns, before the conformance verdict) stay readable: the verdict
// reads as not compared. A version 3 row in a version 2 file is still an error.
TEST_F(RecordsReader, SchemaVersion2FilesReadWithoutAVerdict) {
  metrics::Record r;
  r.platform = "osmesa-softpipe";
  r.kind = "line";
  r.index = 9;
  r.ref_diff = 4;
  r.batch_size = 1;
  std::ostringstream row;
  metrics::write_record(row, r);
  std::string v2 = row.str();
  v2.erase(v2.size() - 1);                 // newline
  for (int k = 0; k < 5; ++k) v2.erase(v2.rfind(','));  // the version 3 and 4 cells
  const auto rows = read(metrics::records_header_v2() + "\n" + v2 + "\n");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].index, 9u);
  EXPECT_EQ(rows[0].ref_diff, 4);
  EXPECT_EQ(rows[0].batch_size, 1);
  EXPECT_EQ(rows[0].conformance, metrics::Conformance::kNotCompared);
  EXPECT_EQ(rows[0].violating_pixels, -1);
  EXPECT_THROW(read(metrics::records_header_v2() + "\n" + row.str()), util::UserError);
  EXPECT_EQ(metrics::records_header().rfind(metrics::records_header_v2() + ",conformance,", 0), 0u);
}

// Schema version 3 files (37 columns, before the host's time and the clock) stay readable: no
// host time, no clock named. A version 4 row in a version 3 file is an error.
TEST_F(RecordsReader, SchemaVersion3FilesReadWithoutHostTimeOrClock) {
  metrics::Record r;
  r.platform = "vk-lavapipe";
  r.kind = "triangle";
  r.index = 11;
  r.render_us = 31.5;
  r.batch_size = 1;
  r.conformance = metrics::Conformance::kExact;
  r.violating_pixels = 0;
  r.host_us = 31.5;
  r.clock = "host";
  std::ostringstream row;
  metrics::write_record(row, r);
  std::string v3 = row.str();
  v3.erase(v3.size() - 1);
  for (int k = 0; k < 2; ++k) v3.erase(v3.rfind(','));  // host_us, clock
  const auto rows = read(metrics::records_header_v3() + "\n" + v3 + "\n");
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(rows[0].render_us, 31.5);
  EXPECT_EQ(rows[0].conformance, metrics::Conformance::kExact);
  EXPECT_TRUE(std::isnan(rows[0].host_us));
  EXPECT_EQ(rows[0].clock, "");
  EXPECT_THROW(read(metrics::records_header_v3() + "\n" + row.str()), util::UserError);
  EXPECT_EQ(metrics::records_header(), metrics::records_header_v3() + ",host_us,clock");
}

// Two measurements of one primitive that differ only in their clocks and batching have the same
// untimed line; any measured column tells them apart.
TEST(UntimedRecordLine, DropsTheTimingColumnsOnly) {
  metrics::Record a;
  a.platform = "vk-device";
  a.kind = "line";
  a.pixels = 12;
  a.pixel_hash = 99;
  a.render_us = 3.5, a.host_us = 40, a.batch_size = 40, a.clock = "device";
  metrics::Record b = a;
  b.render_us = 250, b.host_us = 250, b.batch_size = 1, b.clock = "host";
  EXPECT_EQ(metrics::untimed_record_line(a), metrics::untimed_record_line(b));
  EXPECT_EQ(metrics::untimed_record_line(a).find("3.5"), std::string::npos);
  b.pixel_hash = 98;
  EXPECT_NE(metrics::untimed_record_line(a), metrics::untimed_record_line(b));
}

TEST_F(RecordsReader, RowsStraddlingTheReadBlocksAreReadWhole) {
  // more than 4 MiB of rows, so that some row crosses the reader's block boundary
  std::ostringstream out;
  out << metrics::records_header() << '\n';
  metrics::Record r;
  r.platform = "reference";
  r.kind = "line";
  constexpr std::uint64_t kRows = 60000;
  for (std::uint64_t i = 0; i < kRows; ++i) {
    r.index = i;
    r.lse_s = double(i) / 7;
    metrics::write_record(out, r);
  }
  ASSERT_GT(out.str().size(), std::size_t{4} << 20);
  const auto rows = read(out.str());
  ASSERT_EQ(rows.size(), kRows);
  for (std::uint64_t i = 0; i < kRows; ++i) {
    ASSERT_EQ(rows[i].index, i);
    ASSERT_EQ(rows[i].lse_s, double(i) / 7);
  }
}

TEST_F(RecordsReader, AWrongHeaderAndAShortRowAreErrorsWithTheirLine) {
  try {
    read("platform,view\n");
    FAIL() << "a wrong header was accepted";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find(path_ + ":1: unexpected records header"),
              std::string::npos);
  }
  try {
    read(text_ + "reference,1,0\n");
    FAIL() << "a short row was accepted";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()), path_ + ":4: expected 39 fields, found 3");
  }
}

}  // namespace
}  // namespace ra::rundir
