// The shard servers' protocol: commands and replies survive any path, and garbage is refused.
#include "rundir/shard_command.h"

#include <gtest/gtest.h>

#include <string>

namespace ra::rundir {
namespace {

TEST(ShardServerProtocol, ACommandSurvivesPathsWithSpacesTabsNewlinesAndQuotes) {
  ShardCommand c;
  c.shard = {"osmesa-softpipe", geometry::Kind::kTriangle, 7, 90000, 100000};
  c.records_dir = "/runs/a b\t\"c\"\nd/records";
  c.log = "/runs/a b\t\"c\"\nd/logs/x.log";
  const std::string line = shard_command_line(c);
  EXPECT_EQ(line.find('\n'), std::string::npos);  // one line on the pipe
  const ShardCommand back = parse_shard_command(line, "osmesa-softpipe");
  EXPECT_EQ(back.shard.id(), "osmesa-softpipe.triangle.v7.90000-100000");
  EXPECT_EQ(back.records_dir, c.records_dir);
  EXPECT_EQ(back.log, c.log);
}

TEST(ShardServerProtocol, GarbageIsRefusedWithTheLine) {
  for (const std::string bad :
       {"", "kind triangle", "{\"kind\":\"square\",\"view\":1,\"begin\":0,\"end\":1,"
                             "\"records_dir\":\"r\",\"log\":\"l\"}",
        "{\"kind\":\"point\",\"view\":1,\"begin\":5,\"end\":1,\"records_dir\":\"r\",\"log\":\"l\"}",
        "{\"kind\":\"point\",\"view\":1,\"begin\":0,\"end\":1}"}) {
    try {
      parse_shard_command(bad, "reference");
      ADD_FAILURE() << "accepted: " << bad;
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("not a shard command: '" + bad + "'"),
                std::string::npos)
          << e.what();
    }
  }
}

TEST(ShardServerProtocol, RepliesNameTheirShardAndNothingElseIsAReply) {
  const Shard s{"reference", geometry::Kind::kLine, 3, 0, 10};
  std::string id;
  ASSERT_TRUE(parse_shard_done(shard_done_line(s), &id));
  EXPECT_EQ(id, "reference.line.v3.0-10");
  EXPECT_FALSE(parse_shard_done("cannot write /runs/x: No space left on device", &id));
  EXPECT_FALSE(parse_shard_done("shard-okay", &id));
}

}  // namespace
}  // namespace ra::rundir
