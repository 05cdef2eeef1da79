// Tests of rundir/manifest.h's document_header and the check its readers share.
#include "rundir/manifest.h"

#include <gtest/gtest.h>

#include "util/errors.h"

namespace ra::rundir {
namespace {

std::string error_of(const nlohmann::json& doc, const std::string& remedy = "") {
  try {
    require_document_header(doc, "tally", 1, "run/analysis/tally.json", remedy);
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

TEST(DocumentHeader, WhatItWritesPassesItsCheck) {
  EXPECT_TRUE(has_document_header(document_header("tally", 1, false), "tally", 1));
  EXPECT_TRUE(has_document_header(document_header("bisection", 2), "bisection", 2));
  EXPECT_EQ(error_of(document_header("tally", 1, false)), "");
}

TEST(DocumentHeader, AnotherNameVersionOrShapeFailsNamingFileSchemaAndVersion) {
  const std::string expected =
      "run/analysis/tally.json: expected schema renderaudit-tally version 1";
  EXPECT_EQ(error_of(document_header("figures", 1, false)), expected);
  EXPECT_EQ(error_of(document_header("tally", 2, false)), expected);
  EXPECT_EQ(error_of({{"schema", "renderaudit-tally"}}), expected);
  EXPECT_EQ(error_of({{"schema", "renderaudit-tally"}, {"schema_version", "1"}}), expected);
  EXPECT_EQ(error_of({{"schema", 7}, {"schema_version", 1}}), expected);
  EXPECT_EQ(error_of(nlohmann::json::array({1, 2})), expected);
  EXPECT_EQ(error_of(nullptr), expected);
  EXPECT_EQ(error_of(nlohmann::json::object(), "run `renderaudit analyze run` again"),
            expected + " (run `renderaudit analyze run` again)");
}

}  // namespace
}  // namespace ra::rundir
