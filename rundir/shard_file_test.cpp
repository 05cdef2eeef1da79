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

// The seal is bound to the file's name: a whole, sealed file of shard 0-3 is another shard's
// records under the name of shard 3-6 (or of another view, kind or platform), for check_shard_file
// and for the verdict on a seal read in a reader's own pass (ShardSealReader, as analyze reads it).
TEST_F(ShardFile, ASealedFileOfAnotherShardFailsUnderThisShardsName) {
  std::string text = "platform,view,g,o,f,w,h,n,r,kind,index,more\n";
  for (int i = 0; i < 3; ++i)
    text += "reference,2,0,0,30,64,64,0.01,10,line," + std::to_string(i) + ",x\n";
  write(text);
  seal_shard_file(path_);
  const Shard own{"reference", geometry::Kind::kLine, 2, 0, 3};
  EXPECT_EQ(check_shard_file(path_, own), "");
  EXPECT_EQ(check_shard_file(path_, 3), "");  // the seal alone holds
  ShardSealReader reader;
  reader.add(read());
  const ShardSeal seal = reader.finish();
  EXPECT_EQ(seal.first_row, "reference,2,0,0,30,64,64,0.01,10,line,0,x");
  EXPECT_EQ(seal.last_row, "reference,2,0,0,30,64,64,0.01,10,line,2,x");
  EXPECT_EQ(seal_verdict(seal, own, false), "");
  for (const Shard& other : {Shard{"reference", geometry::Kind::kLine, 2, 3, 6},
                             Shard{"reference", geometry::Kind::kLine, 1, 0, 3},
                             Shard{"reference", geometry::Kind::kPoint, 2, 0, 3},
                             Shard{"egl-llvmpipe", geometry::Kind::kLine, 2, 0, 3}}) {
    SCOPED_TRACE(other.id());
    const std::string why = check_shard_file(path_, other);
    EXPECT_NE(why.find("its first row records line 0 of view 2 on reference where shard " +
                       other.id() + "'s records"),
              std::string::npos) << why;
    EXPECT_NE(why.find("another shard's records under this shard's name"), std::string::npos);
    EXPECT_EQ(seal_verdict(seal, other, false), why);
  }
  // the first row right, the last one another primitive's
  std::string ends_elsewhere = "platform,view,g,o,f,w,h,n,r,kind,index\n";
  for (int i : {0, 1, 5})
    ends_elsewhere += "reference,2,0,0,30,64,64,0.01,10,line," + std::to_string(i) + "\n";
  write(ends_elsewhere);
  seal_shard_file(path_);
  EXPECT_NE(check_shard_file(path_, own).find("its last row records line 5 of view 2 on reference"),
            std::string::npos) << check_shard_file(path_, own);
}

}  // namespace
}  // namespace ra::rundir
