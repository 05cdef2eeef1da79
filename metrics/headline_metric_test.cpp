// The headline error of each kind: its column name and its value agree with records.h.
#include "metrics/headline_metric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace ra::metrics {
namespace {

TEST(HeadlineMetric, OneColumnPerKind) {
  EXPECT_STREQ(headline_column(geometry::Kind::kPoint), "pe");
  EXPECT_STREQ(headline_column(geometry::Kind::kLine), "lse_u");
  EXPECT_STREQ(headline_column(geometry::Kind::kTriangle), "te_u");
}

// The value is the named column's: each kind reads its own field, not a neighbour's.
TEST(HeadlineMetric, ValueIsTheNamedColumn) {
  Record r;
  r.pe = 1.5;
  r.lse_u = 2.5;
  r.lse_u_norm = 99;
  r.te_u = 3.5;
  r.te_u_norm = 98;
  EXPECT_EQ(headline_value(r, geometry::Kind::kPoint), 1.5);
  EXPECT_EQ(headline_value(r, geometry::Kind::kLine), 2.5);
  EXPECT_EQ(headline_value(r, geometry::Kind::kTriangle), 3.5);
  EXPECT_TRUE(std::isnan(headline_value(Record{}, geometry::Kind::kLine)));
}

// Every headline column is a column of the records file.
TEST(HeadlineMetric, ColumnsAreRecordsColumns) {
  const std::string header = "," + records_header() + ",";
  for (geometry::Kind k : {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle})
    EXPECT_NE(header.find("," + std::string(headline_column(k)) + ","), std::string::npos)
        << headline_column(k);
}

}  // namespace
}  // namespace ra::metrics
