// Tests of the attention model (attention.h) against hand-computed values of equations 3-7.
#include "regulation/attention.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ra::regulation {
namespace {

TEST(Attention, BinaryModelEquation4) {
  // p = 0.9, alpha = 0.2: 0.9 + 0.1 * 0.2 = 0.92
  EXPECT_DOUBLE_EQ(binary_attention_weight(0.9, 0.2), 0.92);
  // alpha = 0 is equation 5: the weight is p
  EXPECT_DOUBLE_EQ(binary_attention_weight(0.3, 0.0), 0.3);
  // alpha = 1: attention does not matter
  EXPECT_DOUBLE_EQ(binary_attention_weight(0.3, 1.0), 1.0);
}

TEST(Attention, ObjectModelEquations6And7) {
  // p(A_S | A_O) = 0.5, p(A_O) = 0.8, alpha = 0.25: q = 0.4, 0.4 + 0.6 * 0.25 = 0.55
  EXPECT_DOUBLE_EQ(object_attention_weight(0.5, 0.8, 0.25), 0.55);
  EXPECT_DOUBLE_EQ(object_attention_weight(0.5, 0.8, 0.0), 0.4);  // equation 7
}

TEST(Attention, ContinuousModelEquation3ReducesToKnownIntegrals) {
  // uniform density, a(x) = alpha + (1 - alpha) x: alpha + (1 - alpha) / 2 = 0.6 for alpha 0.2
  const double w = continuous_attention_weight([](double) { return 1.0; },
                                               [](double x) { return 0.2 + 0.8 * x; });
  EXPECT_NEAR(w, 0.6, 1e-12);  // trapezoid is exact on linear integrands
  // density 2x (attention tends to be high), a(x) = x^2: integral 2x^3 = 0.5
  const double w2 = continuous_attention_weight([](double x) { return 2 * x; },
                                                [](double x) { return x * x; }, 2000);
  EXPECT_NEAR(w2, 0.5, 1e-6);
}

TEST(Attention, ExpectedPerceptualCostSumsWeightedCosts) {
  // three objects: primary (0.9), background (0.05), alpha 0.2: weights 0.92, 0.24
  AttentionModel m;
  m.alpha = 0.2;
  const double wp = attention_weight(m, Category::kPrimaryActor);
  const double wb = attention_weight(m, Category::kBackground);
  EXPECT_DOUBLE_EQ(wp, 0.92);
  EXPECT_DOUBLE_EQ(wb, 0.05 + 0.95 * 0.2);
  EXPECT_DOUBLE_EQ(expected_perceptual_cost({10.0, 10.0, 0.0}, {wp, wb, wp}), 9.2 + 2.4);
}

TEST(Attention, TaggingFollowsSharesDeclarationsAndSeed) {
  AttentionModel m;
  std::vector<std::string> names;
  for (int i = 0; i < 4000; ++i) names.push_back("tree " + std::to_string(i));
  m.tags["tree 7"] = Category::kPrimaryActor;
  const auto a = tag_objects(names, m, 3), b = tag_objects(names, m, 3), c = tag_objects(names, m, 4);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_EQ(a[7], Category::kPrimaryActor);
  int counts[kCategories] = {};
  for (Category x : a) ++counts[int(x)];
  for (int k = 0; k < kCategories; ++k)  // 4000 draws: within 4 standard deviations of the share
    EXPECT_NEAR(counts[k] / 4000.0, m.share[k], 4 * std::sqrt(m.share[k] * (1 - m.share[k]) / 4000) + 0.001)
        << category_name(Category(k));
}

}  // namespace
}  // namespace ra::regulation
