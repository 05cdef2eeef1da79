// The paper's published values as data: the file reads, its cells agree with each other where the
// paper's tables are tied (Table 4 = Table 3 / window x 10^3), and every number appears, as
// printed, in the extracted paper when it is at hand (shared/seeds beside the repository); and the
// comparison table's z = (ours - paper) / SE, computed by hand.
#include "analysis/paper_values.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/paper_tables.h"
#include "analysis/records_testing.h"
#include "util/errors.h"

namespace ra::analysis {
namespace {

const std::string kFile = std::string(RA_SOURCE_DIR) + "/experiments/papers/nist2008-tables.toml";

const PaperTableValues& table(const std::vector<PaperTableValues>& all, const std::string& n) {
  for (const auto& t : all)
    if (t.number == n) return t;
  throw std::runtime_error("no table " + n);
}

TEST(PaperValues, ReadAndTiedTogetherAsThePaperTiesThem) {
  const std::vector<PaperTableValues> all = load_paper_values(kFile).tables;
  ASSERT_EQ(all.size(), 6u);
  const PaperTableValues &t3 = table(all, "3"), &t4 = table(all, "4");
  EXPECT_EQ(t3.page, 229);
  for (int platform = 0; platform < 2; ++platform) {
    for (int g = 0; g < 4; ++g) {
      // PEnorm = PE / window: Table 4 (x10^3, 3 decimals) from Table 3 (5 decimals)
      EXPECT_NEAR(t4.median[platform][g], t3.median[platform][g] / t3.window[g] * 1e3, 0.0006);
      EXPECT_NEAR(t4.iqr[platform][g], t3.iqr[platform][g] / t3.window[g] * 1e3, 0.0006);
    }
  }
  EXPECT_TRUE(std::isnan(table(all, "10").iqr[1][3]));  // lost in the extraction
  EXPECT_TRUE(std::isnan(table(all, "9").median[1][0]));
  EXPECT_EQ(table(all, "10").iqr[0][1], 0.680);  // the TEu IQR of group B (Platform I)
  EXPECT_EQ(table(all, "7").median[0], (std::array<double, 4>{1.906, 1.920, 0.257, 0.258}));
}

TEST(PaperValues, EveryNumberIsPrintedInTheExtractedPaper) {
  const std::string seed = std::string(RA_SOURCE_DIR) + "/../shared/seeds/000_fcd947f0656c8c36.txt";
  if (!std::filesystem::exists(seed)) GTEST_SKIP() << seed << " is not beside this checkout";
  std::ifstream in(seed);
  std::stringstream text;
  text << in.rdbuf();
  std::string paper = text.str();
  // the extraction prints minus signs as en dashes
  for (std::size_t at; (at = paper.find("\xe2\x80\x93")) != std::string::npos;)
    paper.replace(at, 3, "-");
  for (const PaperTableValues& t : load_paper_values(kFile).tables) {
    const int decimals = t.number == "3" ? 5 : (t.number == "6" || t.number == "9") ? 2 : 3;
    for (const auto* block : {&t.median, &t.iqr})
      for (const auto& four : *block)
        for (double v : four) {
          if (std::isnan(v)) continue;
          char printed[32];
          std::snprintf(printed, sizeof printed, "%.*f", decimals, v);
          EXPECT_NE(paper.find(printed), std::string::npos)
              << "Table " << t.number << ": " << printed;
        }
  }
}

TEST(PaperValues, BadFilesAreRefusedWithTheirLine) {
  const std::string path = ::testing::TempDir() + "/paper_bad.toml";
  std::ofstream(path) << "[[table]]\nnumber = \"3\"\ncolumn = \"pe\"\nscale_exponent = 0\n"
                         "reading = \"x\"\nfov_deg = [30, 150, 30]\n";
  try {
    load_paper_values(path);
    FAIL() << "accepted";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("table.fov_deg: four numbers, groups A-D"),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find(path + ":6:"), std::string::npos) << e.what();
  }
}

// A value no printed table holds (inf, -inf, 1e308) stops at its line and column: it used to reach
// the table formatter and abort analyze there, naming no file. A missing file says what it was for.
TEST(PaperValues, NonFiniteOrHugeValuesAreRefusedAtTheirLine) {
  std::ifstream in(kFile);
  std::stringstream whole;
  whole << in.rdbuf();
  const std::string good = whole.str();
  const std::string cell = "platform_1_median = [0.39555,";
  const std::size_t at = good.find(cell);
  ASSERT_NE(at, std::string::npos);
  const std::size_t line = std::size_t(std::count(good.begin(), good.begin() + at, '\n')) + 1;
  const std::string path = ::testing::TempDir() + "/paper_huge.toml";
  for (const std::string value : {"inf", "-inf", "+inf", "1e308", "-2e15"}) {
    std::string text = good;
    text.replace(at, cell.size(), "platform_1_median = [" + value + ",");
    std::ofstream(path, std::ios::trunc) << text;
    try {
      load_paper_values(path);
      ADD_FAILURE() << value << " accepted";
    } catch (const util::UserError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(path + ":" + std::to_string(line) + ":22: table.platform_1_median: "
                          "value 1 of 4 is not a table value (allowed: -1e15 to 1e15, or nan "
                          "for a lost cell)"),
                std::string::npos)
          << value << ": " << what;
    }
  }
  std::string lost = good;  // nan still marks a lost cell
  lost.replace(at, cell.size(), "platform_1_median = [nan,");
  std::ofstream(path, std::ios::trunc) << lost;
  EXPECT_TRUE(std::isnan(table(load_paper_values(path).tables, "3").median[0][0]));
  const std::string missing = ::testing::TempDir() + "/no_such_paper.toml";
  try {
    load_paper_values(missing);
    ADD_FAILURE() << "a missing file accepted";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()),
              missing + ": cannot read the paper's values (--paper) (No such file or directory)");
  }
}

// Platform p1, group A (view 1 and 2: FOV 30, 128 x 128): PE {0.05 ... 0.60}, HF6 median 0.30.
TEST(PaperValues, TheComparisonSaysHowManyStandardErrorsApartWeAre) {
  testing::ScopedTempDir dir{"paper_comparison"};
  testing::write_nine_point_run(dir.path);
  const RunRecords run = load_run_records(dir.path.string());
  TableOptions o;
  const double nan = std::nan("");
  const PaperTableValues t3 = testing::table3_group_a(0.2, 0.3, nan, 0.325);
  o.paper = {t3};
  const std::vector<stats::Table> tables = paper_tables(run, o);
  const stats::Table* c = nullptr;
  for (const stats::Table& t : tables)
    if (t.file_stem == "paper_comparison") c = &t;
  ASSERT_NE(c, nullptr);
  ASSERT_EQ(c->rows.size(), 2u);  // median and IQR of group A
  const auto& median = c->rows[0];
  EXPECT_EQ(median[4].text, "0.300000");
  const double se = std::stod(median[5].csv.empty() ? median[5].text : median[5].csv);
  ASSERT_GT(se, 0);
  char z[16];
  std::snprintf(z, sizeof z, "%.1f", (0.3 - 0.2) / se);
  EXPECT_EQ(median[7].text, z);      // z I
  EXPECT_EQ(median[9].text, "0.0");  // z II: the paper says 0.3 too
  EXPECT_EQ(median[10].text, (0.3 - 0.2) / se > 3 ? "I" : "");
  const auto& iqr = c->rows[1];
  EXPECT_EQ(iqr[6].text, "lost");
  EXPECT_EQ(iqr[7].text, "n/a");
  EXPECT_EQ(iqr[9].text, "0.0");  // 0.325, as ours
  EXPECT_NE(c->notes.back().find("Paper Table 3: by hand."), std::string::npos);
}

}  // namespace
}  // namespace ra::analysis
