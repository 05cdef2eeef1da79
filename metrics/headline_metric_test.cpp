// The headline error of each kind, as it is and divided by the window: its column names and its
// values agree with records.h.
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

// Every headline column, as it is and divided by the window, is a column of the records file.
TEST(HeadlineMetric, ColumnsAreRecordsColumns) {
  const std::string header = "," + records_header() + ",";
  for (geometry::Kind k : {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle})
    for (const char* column : {headline_column(k), headline_norm_column(k)})
      EXPECT_NE(header.find("," + std::string(column) + ","), std::string::npos) << column;
}

// The divided form reads its own field, each kind's; the summary quotes points in pixels and
// lines and triangles divided, under the labels its table has always had.
TEST(HeadlineMetric, NormalisedAndSummaryFormsReadTheirColumns) {
  Record r;
  r.pe = 1.5;
  r.pe_norm = 0.5;
  r.lse_u = 2.5;
  r.lse_u_norm = 0.25;
  r.te_u = 3.5;
  r.te_u_norm = 0.125;
  EXPECT_STREQ(headline_norm_column(geometry::Kind::kPoint), "pe_norm");
  EXPECT_STREQ(headline_norm_column(geometry::Kind::kLine), "lse_u_norm");
  EXPECT_STREQ(headline_norm_column(geometry::Kind::kTriangle), "te_u_norm");
  EXPECT_EQ(headline_norm_value(r, geometry::Kind::kPoint), 0.5);
  EXPECT_EQ(headline_norm_value(r, geometry::Kind::kLine), 0.25);
  EXPECT_EQ(headline_norm_value(r, geometry::Kind::kTriangle), 0.125);
  EXPECT_EQ(summary_metric_value(r, geometry::Kind::kPoint), 1.5);
  EXPECT_EQ(summary_metric_value(r, geometry::Kind::kLine), 0.25);
  EXPECT_EQ(summary_metric_value(r, geometry::Kind::kTriangle), 0.125);
  EXPECT_STREQ(summary_metric_label(geometry::Kind::kPoint), "PE (px)");
  EXPECT_STREQ(summary_metric_label(geometry::Kind::kLine), "LSEu-norm");
  EXPECT_STREQ(summary_metric_label(geometry::Kind::kTriangle), "TEu-norm");
  EXPECT_TRUE(std::isnan(summary_metric_value(Record{}, geometry::Kind::kTriangle)));
}

}  // namespace
}  // namespace ra::metrics
