// Tests of the data `renderaudit stats` reads from CSV columns (column_samples.h): small files
// written here, each case with the reason it exists.
#include "stats/column_samples.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "stats/stats_testing.h"
#include "util/errors.h"

namespace ra::stats {
namespace {

// Selection keeps the rows whose cells read the condition's text exactly, and counts the empty
// cells of the rows it keeps, not of the others.
TEST(ColumnSamples, SelectedRowsAndTheirEmptyCells) {
  const auto dir = testing::temp_dir("samples");
  const std::string path = (dir / "r.csv").string();
  std::ofstream(path) << "platform,v\na,1\nb,10\na,\na,3\n";
  ColumnSample s{path, "v", {}, 0};
  add_selected_values(path, parse_row_conditions({"platform=a"}), s);
  EXPECT_EQ(s.values, (std::vector<double>{1, 3}));
  EXPECT_EQ(s.n_missing, 1u);
  EXPECT_NO_THROW(require_two_selected_values(s));
  EXPECT_THROW(parse_row_conditions({"=a"}), util::UserError);
  EXPECT_THROW(parse_row_conditions({"platform"}), util::UserError);
  ColumnSample none{path, "v", {}, 0};
  add_selected_values(path, parse_row_conditions({"platform=c"}), none);
  EXPECT_THROW(require_two_selected_values(none), util::UserError);
  EXPECT_THROW(read_column_sample(path, "w"), util::UserError);  // no such column
  EXPECT_EQ(read_column_sample(path, "v").values.size(), 3u);
  std::filesystem::remove_all(dir);
}

// Groups come in order of first appearance (the ANOVA table's order); a row without a label or a
// value is skipped and counted; one group is not an ANOVA.
TEST(ColumnSamples, GroupsInOrderOfFirstAppearance) {
  const auto dir = testing::temp_dir("groups");
  const std::string path = (dir / "g.csv").string();
  std::ofstream(path) << "g,v\nz,1\na,2\nz,3\n,4\na,\na,5\n";
  const GroupedValues g = read_grouped_values(path, "g", "v");
  EXPECT_EQ(g.names, (std::vector<std::string>{"z", "a"}));
  EXPECT_EQ(g.groups[0], (std::vector<double>{1, 3}));
  EXPECT_EQ(g.groups[1], (std::vector<double>{2, 5}));
  EXPECT_EQ(g.n, 4u);
  EXPECT_EQ(g.n_missing, 2u);
  std::ofstream(path) << "g,v\nz,1\nz,2\n";
  EXPECT_THROW(read_grouped_values(path, "g", "v"), util::UserError);
  std::filesystem::remove_all(dir);
}

// Regression rows are those complete in the response and every predictor; the polynomial spec and
// the predictor names are checked before any file is read.
TEST(ColumnSamples, RegressionRowsCompleteInEveryColumn) {
  const auto dir = testing::temp_dir("regress");
  const std::string path = (dir / "x.csv").string();
  std::ofstream(path) << "y,a,b\n1,2,3\n4,,6\n7,8,9\n";
  const RegressionData d = read_regression_data(path, "y", {"a", "b"});
  EXPECT_EQ(d.y, (std::vector<double>{1, 7}));
  EXPECT_EQ(d.x[1], (std::vector<double>{3, 9}));
  EXPECT_EQ(d.n_missing, 1u);
  EXPECT_EQ(parse_polynomial_spec(path, "a:3"), (std::pair<std::string, int>{"a", 3}));
  EXPECT_THROW(parse_polynomial_spec(path, "a:31"), util::UserError);
  EXPECT_THROW(parse_polynomial_spec(path, ":2"), util::UserError);
  EXPECT_THROW(parse_polynomial_spec(path, "a:2x"), util::UserError);
  EXPECT_THROW(check_predictor_names(path, {"a", "a"}, "y"), util::UserError);
  EXPECT_THROW(check_predictor_names(path, {"y"}, "y"), util::UserError);
  EXPECT_NO_THROW(check_predictor_names(path, {"a", "b"}, "y"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ra::stats
