// Primitive generation: deterministic, uniform in the unit sphere, independent of order.
#include "geometry/primitive.h"

#include <gtest/gtest.h>

#include <cmath>

#include "util/counter_rng.h"

namespace ra::geometry {
namespace {

// The generator is a pure function of (seed, kind, index): asking in any order gives the same bytes.
TEST(Primitive, SameBytesWhateverTheOrder) {
  const Primitive a = make_primitive(7, Kind::kTriangle, 12345);
  for (uint64_t i = 0; i < 100; ++i) make_primitive(7, Kind::kTriangle, i);
  const Primitive b = make_primitive(7, Kind::kTriangle, 12345);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(a.v[k].x, b.v[k].x);
    EXPECT_EQ(a.v[k].y, b.v[k].y);
    EXPECT_EQ(a.v[k].z, b.v[k].z);
  }
}

// Portability: SplitMix64 is integer-only, so its values are fixed forever. Reference values from
// the published algorithm (state 0 -> first output), computed independently with Python's ints.
TEST(Primitive, SplitMixIsTheStandardFunction) {
  EXPECT_EQ(util::splitmix64(0), 0xE220A8397B1DCDAFull);
  EXPECT_EQ(util::splitmix64(0x9E3779B97F4A7C15ull), 0x6E789E6AA1B965F4ull);
}

TEST(Primitive, KindsAndSeedsAreIndependentStreams) {
  EXPECT_NE(make_primitive(1, Kind::kPoint, 0).v[0].x, make_primitive(1, Kind::kLine, 0).v[0].x);
  EXPECT_NE(make_primitive(1, Kind::kPoint, 0).v[0].x, make_primitive(2, Kind::kPoint, 0).v[0].x);
}

// Uniform in the ball: P(|p| < r) = r^3, and the mean of each coordinate is 0.
TEST(Primitive, UniformInTheUnitSphere) {
  const int n = 200000;
  int inside_half = 0;
  double sum_x = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 p = make_primitive(3, Kind::kPoint, i).v[0];
    ASSERT_LE(dot(p, p), 1.0);
    inside_half += std::sqrt(dot(p, p)) < 0.5;
    sum_x += p.x;
  }
  const double frac = double(inside_half) / n, expected = 0.125;
  EXPECT_NEAR(frac, expected, 4 * std::sqrt(expected * (1 - expected) / n));
  EXPECT_NEAR(sum_x / n, 0.0, 4 * std::sqrt(0.2 / n));  // var of x in the ball = 1/5
}

// Records hold the name only (a plural there is a broken file); people may write either.
TEST(Primitive, ParseKindBySpelling) {
  EXPECT_EQ(parse_kind("line", KindSpelling::kName), Kind::kLine);
  EXPECT_EQ(parse_kind("lines", KindSpelling::kName), std::nullopt);
  EXPECT_EQ(parse_kind("triangles", KindSpelling::kNameOrPlural), Kind::kTriangle);
  EXPECT_EQ(parse_kind("Point", KindSpelling::kNameOrPlural), std::nullopt);  // case counts
  Kind k = Kind::kLine;
  EXPECT_TRUE(parse_kind(std::string("points"), &k));
  EXPECT_EQ(k, Kind::kPoint);
  EXPECT_FALSE(parse_kind(std::string("quad"), &k));
  EXPECT_EQ(k, Kind::kPoint);  // left as it was
}

}  // namespace
}  // namespace ra::geometry
