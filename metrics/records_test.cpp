// Tests of metrics/records.h's reader: CRLF files read as LF ones (audit once rejected what analyze
// accepted), the seal line of a shard file is skipped, a bad number names its column and line.
#include "metrics/records.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "util/errors.h"

namespace ra {
namespace {

class RecordsReader : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (std::filesystem::temp_directory_path() /
             ("ra_records_" + std::to_string(::getpid()) + ".csv")).string();
    Record a, b;
    a.platform = b.platform = "reference";
    a.kind = b.kind = "point";
    a.index = 4;
    b.index = 5;
    a.pe = 0.25;
    std::ostringstream out;
    out << records_header() << '\n';
    write_record(out, a);
    write_record(out, b);
    text_ = out.str();
  }
  void TearDown() override { std::filesystem::remove(path_); }
  std::vector<Record> read(const std::string& text) {
    std::ofstream(path_, std::ios::binary) << text;
    std::vector<Record> rows;
    read_records(path_, [&](const Record& r) { rows.push_back(r); });
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
  } catch (const UserError& e) {
    EXPECT_EQ(std::string(e.what()), path_ + ":3: column 'index': 'x5' is not a number");
  }
}

}  // namespace
}  // namespace ra
