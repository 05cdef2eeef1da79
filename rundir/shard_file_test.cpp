// Tests of rundir/shard_file.h: only a whole, untouched shard file passes.
#include "rundir/shard_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

namespace ra::rundir {
namespace {

class ShardFile : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (std::filesystem::temp_directory_path() /
             ("ra_shard_" + std::to_string(::getpid()) + ".csv")).string();
    write("a,b\n1,x\n2,y\n3,z\n");
  }
  void TearDown() override { std::filesystem::remove(path_); }
  void write(const std::string& text) { std::ofstream(path_, std::ios::binary) << text; }
  std::string read() {
    std::ifstream in(path_, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), {});
  }
  std::string path_;
};

TEST_F(ShardFile, ASealedFileChecksOutAndCountsItsRows) {
  EXPECT_EQ(seal_shard_file(path_), 3u);
  const std::string text = read();
  // FNV-1a 64 of the four lines before it, computed independently in Python:
  //   h = 0xcbf29ce484222325; for b in data: h = ((h ^ b) * 0x100000001b3) % 2**64
  EXPECT_EQ(text, "a,b\n1,x\n2,y\n3,z\n# complete rows=3 fnv1a64=68b586b4b20d2725\n");
  EXPECT_EQ(check_shard_file(path_, 3), "");
}

TEST_F(ShardFile, TheHashIsFnv1a64) {
  // Reference value from the FNV specification's test vectors: FNV-1a 64 of "a" = af63dc4c8601ec8c.
  EXPECT_EQ(shard_trailer("a", 0), "# complete rows=0 fnv1a64=af63dc4c8601ec8c\n");
  EXPECT_EQ(shard_trailer("", 0), "# complete rows=0 fnv1a64=cbf29ce484222325\n");
}

TEST_F(ShardFile, AnUnsealedFileIsNotTrusted) {
  EXPECT_NE(check_shard_file(path_, 3).find("no trailer"), std::string::npos);
}

TEST_F(ShardFile, ACutShortFileFails) {
  seal_shard_file(path_);
  const std::string text = read();
  write(text.substr(0, text.size() - 5));
  EXPECT_NE(check_shard_file(path_, 3).find("no trailer"), std::string::npos);
}

TEST_F(ShardFile, ALineDroppedOrDoubledFails) {
  seal_shard_file(path_);
  std::string text = read();
  std::string dropped = text;
  dropped.erase(dropped.find("2,y\n"), 4);
  write(dropped);
  EXPECT_NE(check_shard_file(path_, 3).find("does not match"), std::string::npos);
  std::string doubled = text;
  doubled.insert(doubled.find("2,y\n"), "2,y\n");
  write(doubled);
  EXPECT_NE(check_shard_file(path_, 3).find("does not match"), std::string::npos);
}

TEST_F(ShardFile, OneChangedByteFails) {
  seal_shard_file(path_);
  std::string text = read();
  text[text.find("x")] = 'w';
  write(text);
  EXPECT_NE(check_shard_file(path_, 3).find("does not match"), std::string::npos);
}

TEST_F(ShardFile, AWholeFileOfTheWrongShardSizeFails) {
  seal_shard_file(path_);
  EXPECT_EQ(check_shard_file(path_, 4), "it holds 3 rows where the shard has 4 primitives");
}

TEST_F(ShardFile, AMissingFileSaysSo) {
  std::filesystem::remove(path_);
  EXPECT_EQ(check_shard_file(path_, 3), "cannot read it");
}

}  // namespace
}  // namespace ra::rundir
