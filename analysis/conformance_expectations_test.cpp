// The expectations file's reader: comments and blank lines skipped, every malformed line said with
// its place, all at once (a reviewer fixes them in one go).
#include "analysis/conformance_expectations.h"

#include <gtest/gtest.h>

#include "util/errors.h"

namespace ra::analysis {
namespace {

std::string parse_error(const std::string& text) {
  try {
    parse_expectations(text, "known.txt");
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

// The writer's own form reads back: fields, comments after them, comment lines, blank lines.
TEST(ConformanceExpectations, TheWrittenFormReadsBack) {
  const Expectations e = parse_expectations(
      "# header\n\nosmesa-softpipe line 5 721  # 3 px: line-column\n"
      "  faulty\ttriangle 1 0\r\n",
      "known.txt");
  ASSERT_EQ(e.entries.size(), 2u);
  EXPECT_EQ(e.entries[0].name(), "osmesa-softpipe line 5 721");
  EXPECT_EQ(e.entries[0].line, 3);
  EXPECT_EQ(e.entries[1].name(), "faulty triangle 1 0");
  EXPECT_EQ(e.entries[1].line, 4);
}

// Each kind of mistake, each with FILE:LINE and what to do; the good lines between them do not
// stop the reading.
TEST(ConformanceExpectations, EveryMalformedLineIsSaidWithItsPlace) {
  const std::string err = parse_error(
      "faulty line 1\n"            // 1: three fields
      "faulty line 1 2 3\n"        // 2: five
      "faulty lines 1 2\n"         // 3: not a kind
      "faulty line 0 2\n"          // 4: views count from 1
      "faulty line 1 -2\n"         // 5: not an index
      "faulty line 1 2\n"          // 6: fine
      "faulty line 1 2 # again\n"  // 7: listed twice
  );
  EXPECT_NE(err.find("known.txt:1: expected four fields, PLATFORM KIND VIEW INDEX (e.g. "
                     "'osmesa-softpipe line 5 721'), found 3: 'faulty line 1'"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("known.txt:2: expected four fields"), std::string::npos) << err;
  EXPECT_NE(err.find("known.txt:3: kind 'lines' is not one of point, line, triangle"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("known.txt:4: view '0' is not a view id"), std::string::npos) << err;
  EXPECT_NE(err.find("known.txt:5: index '-2' is not a primitive index"), std::string::npos) << err;
  EXPECT_NE(err.find("known.txt:7: faulty line 1 2 is listed already on line 6; remove one"),
            std::string::npos)
      << err;
  EXPECT_EQ(err.find("known.txt:6:"), std::string::npos) << err;
}

}  // namespace
}  // namespace ra::analysis
