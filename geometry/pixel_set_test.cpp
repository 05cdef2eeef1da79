// Run-length pixel sets against a plain sorted vector of pixels (the obvious representation).
#include "geometry/pixel_set.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

namespace ra::geometry {
namespace {

std::set<Pixel> random_pixels(std::mt19937_64& rng, int w, int h, double density) {
  std::set<Pixel> s;
  std::uniform_real_distribution<double> u(0, 1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (u(rng) < density) s.insert({x, y});
  return s;
}

// Runs are maximal and sorted; size, iteration, membership and pixels() agree with the set.
TEST(PixelSet, RunsAreCanonical) {
  const PixelSet s = {{3, 1}, {1, 0}, {2, 0}, {0, 0}, {4, 0}, {2, 0}, {4, 1}, {-2, 1}};
  const std::vector<PixelRun> expect = {{0, 0, 3}, {0, 4, 5}, {1, -2, -1}, {1, 3, 5}};
  EXPECT_EQ(s.runs(), expect);
  EXPECT_EQ(s.size(), 7);
  EXPECT_EQ(s.front(), (Pixel{0, 0}));
  EXPECT_TRUE(s.contains({2, 0}));
  EXPECT_FALSE(s.contains({3, 0}));
  EXPECT_TRUE(s.contains({-2, 1}));
  EXPECT_FALSE(s.contains({-1, 1}));
  const std::vector<Pixel> iterated(s.begin(), s.end());
  EXPECT_EQ(iterated, s.pixels());
  EXPECT_EQ(iterated.size(), 7u);
  EXPECT_TRUE(std::is_sorted(iterated.begin(), iterated.end()));
  EXPECT_TRUE(PixelSet{}.empty());
  EXPECT_EQ(PixelSet{}.begin(), PixelSet{}.end());
}

// Touching appended runs merge into one; out-of-order or overlapping ones are a programming error.
TEST(PixelSet, AppendRun) {
  PixelSet s;
  s.append_run(5, 0, 3);
  s.append_run(5, 3, 7);
  s.append_run(5, 9, 9);  // empty: ignored
  s.append_run(6, -4, -1);
  EXPECT_EQ(s.runs(), (std::vector<PixelRun>{{5, 0, 7}, {6, -4, -1}}));
  EXPECT_EQ(s.size(), 10);
  EXPECT_THROW(s.append_run(6, -2, 0), std::logic_error);  // overlaps [-4, -1)
  EXPECT_THROW(s.append_run(4, 0, 1), std::logic_error);   // row below
}

// Insert, erase, translate and clip keep the runs canonical (equal sets compare equal).
TEST(PixelSet, EditsStayCanonical) {
  PixelSet s = {{0, 0}, {2, 0}};
  s.insert({1, 0});
  EXPECT_EQ(s.runs(), (std::vector<PixelRun>{{0, 0, 3}}));
  s.erase({1, 0});
  EXPECT_EQ(s, (PixelSet{{0, 0}, {2, 0}}));
  s.translate(5, -1);
  EXPECT_EQ(s, (PixelSet{{5, -1}, {7, -1}}));
  PixelSet wide;
  wide.append_run(0, -10, 10);
  wide.append_run(3, 0, 2);
  wide.clip_to({0, 0, 4, 2});
  EXPECT_EQ(wide.runs(), (std::vector<PixelRun>{{0, 0, 4}}));
}

// Symmetric difference and equality against std::set on random sets of all densities.
TEST(PixelSet, SymmetricDifferenceMatchesBruteForce) {
  std::mt19937_64 rng(17);
  for (int t = 0; t < 200; ++t) {
    const double da = 0.05 + 0.9 * (t % 10) / 9.0, db = 0.05 + 0.9 * ((t / 10) % 10) / 9.0;
    const std::set<Pixel> a = random_pixels(rng, 17, 9, da), b = random_pixels(rng, 17, 9, db);
    int64_t brute = 0;
    for (const Pixel& p : a) brute += !b.count(p);
    for (const Pixel& p : b) brute += !a.count(p);
    const PixelSet sa = PixelSet::from_pixels({a.begin(), a.end()});
    const PixelSet sb = PixelSet::from_pixels({b.begin(), b.end()});
    ASSERT_EQ(symmetric_difference_size(sa, sb), brute);
    ASSERT_EQ(symmetric_difference_size(sa, sa), 0);
    ASSERT_EQ(sa.size(), int64_t(a.size()));
    ASSERT_EQ(sa == sb, a == b);
  }
}

// The hash depends on the set only, and tells neighbouring sets apart.
TEST(PixelSet, Hash) {
  const PixelSet a = {{1, 2}, {2, 2}, {3, 2}};
  PixelSet b;
  b.append_run(2, 1, 2);
  b.append_run(2, 2, 4);  // built differently, the same set
  EXPECT_EQ(pixel_set_hash(a), pixel_set_hash(b));
  PixelSet shifted = a;
  shifted.translate(1, 0);
  EXPECT_NE(pixel_set_hash(a), pixel_set_hash(shifted));
  EXPECT_NE(pixel_set_hash(a), pixel_set_hash(PixelSet{{1, 2}, {3, 2}}));
  EXPECT_EQ(pixel_set_hash(PixelSet{}), 0xcbf29ce484222325ull);  // FNV-1a offset basis
  // Byte by byte as FNV-1a is defined, over runs with coordinates of one to four bytes, negative
  // ones included (records of old runs compare by this hash: it must never change).
  std::mt19937 rng(4);
  for (int t = 0; t < 200; ++t) {
    PixelSet s;
    const int32_t scale = t % 4 == 0 ? 200 : t % 4 == 1 ? 60000 : t % 4 == 2 ? 1 << 24 : 1 << 30;
    int32_t y = int32_t(rng() % uint32_t(scale)) - (t % 3 == 0 ? scale / 2 : 0);
    for (int r = 0; r < 20; ++r, y += 1 + int32_t(rng() % 3)) {
      const int32_t x = int32_t(rng() % uint32_t(scale)) - (t % 5 == 0 ? scale / 2 : 0);
      s.append_run(y, x, x + 1 + int32_t(rng() % 7));
    }
    uint64_t h = 0xcbf29ce484222325ull;
    for (const PixelRun& run : s.runs())
      for (const int32_t v : {run.y, run.x_begin, run.x_end})
        for (int k = 0; k < 4; ++k) h = (h ^ ((uint32_t(v) >> (8 * k)) & 0xffu)) * 0x100000001b3ull;
    ASSERT_EQ(pixel_set_hash(s), h) << "set " << t;
  }
}

}  // namespace
}  // namespace ra::geometry

namespace ra::geometry {
namespace {

// set_difference against a brute-force difference of random sets (runs that touch, overlap,
// contain one another, rows present in one set only).
TEST(PixelSet, SetDifferenceEqualsTheBruteForceOne) {
  uint64_t state = 12345;
  auto next = [&state](int n) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return int32_t((state >> 33) % uint64_t(n));
  };
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Pixel> pa, pb;
    for (int k = next(60); k > 0; --k) pa.push_back({next(12) - 2, next(6) - 1});
    for (int k = next(60); k > 0; --k) pb.push_back({next(12) - 2, next(6) - 1});
    const PixelSet a = PixelSet::from_pixels(pa), b = PixelSet::from_pixels(pb);
    std::vector<Pixel> expected;
    for (const Pixel& p : a)
      if (!b.contains(p)) expected.push_back(p);
    EXPECT_EQ(set_difference(a, b), PixelSet::from_pixels(expected)) << "trial " << trial;
  }
  EXPECT_TRUE(set_difference(PixelSet{}, PixelSet{{1, 1}}).empty());
  EXPECT_EQ(set_difference(PixelSet{{1, 1}}, PixelSet{}), (PixelSet{{1, 1}}));
}

}  // namespace
}  // namespace ra::geometry
