// The `faulty` test platform (faulty_platform.cpp): each fault of a [faults] plan does exactly what
// it says to the reference rasterizer's pixels (a shift by one pixel, a wild pixel in the opposite
// quadrant, a dropped line end, a flaky shift on the first attempt only, a crash), and with an
// OSMesa base it draws what that platform draws.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <csignal>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "geometry/pixel_region.h"
#include "geometry/pixel_set.h"
#include "platforms/platform.h"
#include "platforms/window_view_testing.h"

namespace ra::platforms {
namespace {

using geometry::Pixel;
using geometry::PixelSet;
using geometry::Vec2;

constexpr int kSize = 16;

geometry::View window_view() { return testing::window_view(kSize); }

geometry::Primitive primitive(geometry::Kind kind, std::vector<Vec2> window_points,
                              uint64_t index = 0) {
  return testing::window_primitive(kind, window_points, index);
}

const geometry::PixelRegion& whole() {
  static const geometry::PixelRegion r(geometry::PixelRect{0, 0, kSize, kSize});
  return r;
}

PixelSet draw(const rundir::FaultPlan& plan, const geometry::Primitive& prim) {
  auto platform = create_faulty_platform(plan);
  platform->set_view(window_view());
  return platform->render(prim, whole()).lit;
}

PixelSet reference(const geometry::Primitive& prim) {
  auto platform = create_reference_platform();
  platform->set_view(window_view());
  return platform->render(prim, whole()).lit;
}

// Sets an environment variable for the life of the object, then puts back what was there.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    if (value)
      ::setenv(name, value, 1);
    else
      ::unsetenv(name);
  }
  ~ScopedEnv() {
    if (old_)
      ::setenv(name_.c_str(), old_->c_str(), 1);
    else
      ::unsetenv(name_.c_str());
  }

 private:
  std::string name_;
  std::optional<std::string> old_;
};

const geometry::Primitive kTriangle =
    primitive(geometry::Kind::kTriangle, {{1.5, 1.5}, {12.5, 3.5}, {5.5, 13.5}}, 3);

// An empty plan is the reference rasterizer, primitive for primitive, and says it is the test
// platform.
TEST(FaultyPlatform, WithNoFaultsDrawsWhatTheReferenceDraws) {
  auto platform = create_faulty_platform(rundir::FaultPlan{});
  EXPECT_EQ(platform->driver_info().renderer, "renderaudit faulty test platform");
  EXPECT_EQ(platform->driver_info().subpixel_bits, 0);
  const geometry::View view = geometry::make_view(90, 64, 64);
  platform->set_view(view);
  auto ref = create_reference_platform();
  ref->set_view(view);
  const geometry::PixelRegion region(geometry::PixelRect{0, 0, 64, 64});
  int lit = 0;
  for (geometry::Kind kind :
       {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle})
    for (uint64_t i = 0; i < 40; ++i) {
      const geometry::Primitive prim = geometry::make_primitive(11, kind, i);
      const RenderResult got = platform->render(prim, region);
      EXPECT_EQ(got.lit, ref->render(prim, region).lit) << geometry::kind_name(kind) << " " << i;
      EXPECT_TRUE(got.full_scan);
      lit += !got.lit.empty();
    }
  EXPECT_GT(lit, 30);  // the comparison saw real pixels
}

// shift_fraction 1: every primitive one pixel to the right; what leaves the window is dropped.
TEST(FaultyPlatform, AShiftMovesEveryPixelOneToTheRightInsideTheWindow) {
  rundir::FaultPlan plan;
  plan.shift_fraction = 1;
  PixelSet want = reference(kTriangle);
  want.translate(1, 0);
  EXPECT_EQ(draw(plan, kTriangle), want);
  // At the right border: the reference's column 15 goes out of the window. By hand, the triangle
  // lights x = 13-15 of row 3, 14-15 of row 4, 15 of row 5 (its left edge, x = 12.5 + 0.8125 (y -
  // 2.5), keeps centres on it; its bottom edge y = 2.5 drops row 2).
  const geometry::Primitive edge =
      primitive(geometry::Kind::kTriangle, {{12.5, 2.5}, {15.75, 2.5}, {15.75, 6.5}});
  const PixelSet ref = reference(edge);
  ASSERT_EQ(ref, (PixelSet{{13, 3}, {14, 3}, {15, 3}, {14, 4}, {15, 4}, {15, 5}}));
  PixelSet shifted = ref;
  shifted.translate(1, 0);
  shifted.clip_to({0, 0, kSize, kSize});
  const PixelSet got = draw(plan, edge);
  EXPECT_EQ(got, shifted);
  EXPECT_FALSE(got.contains({16, 3}));
  EXPECT_EQ(got.size(), ref.size() - 3);  // rows 3, 4 and 5 each lose their pixel at x = 15
}

// A wild pixel for a listed index only, half the window away from the lowest lit pixel in x and in
// y (the opposite quadrant), on top of the reference's pixels.
TEST(FaultyPlatform, AWildPixelLightsOnePixelInTheOppositeQuadrantForListedIndicesOnly) {
  rundir::FaultPlan plan;
  plan.wild_pixel = {3, 9};
  const PixelSet ref = reference(kTriangle);
  const Pixel anchor = ref.front();
  const Pixel wild{(anchor.x + kSize / 2) % kSize, (anchor.y + kSize / 2) % kSize};
  ASSERT_FALSE(ref.contains(wild));
  PixelSet want = ref;
  want.insert(wild);
  EXPECT_EQ(draw(plan, kTriangle), want);
  geometry::Primitive unlisted = kTriangle;
  unlisted.index = 4;
  EXPECT_EQ(draw(plan, unlisted), ref);
  // A primitive that lights nothing gets its wild pixel at the centre of the window.
  const geometry::Primitive none =
      primitive(geometry::Kind::kTriangle, {{1.5, 1.5}, {1.5, 1.5}, {6.5, 1.5}}, 9);
  EXPECT_EQ(draw(plan, none), (PixelSet{{kSize / 2, kSize / 2}}));
}

// drop_line_end_fraction 1: every line loses its last pixel along its major axis (a Bresenham loop
// stopping one step early), in either direction; triangles keep theirs. By hand: the segment along
// y = 2.3 from x = 0.7 to 8.3 lights columns 0-7 of row 2 (column 8 holds its end), from 8.3 to
// 0.7 columns 1-8.
TEST(FaultyPlatform, ADroppedLineEndRemovesTheLastPixelAlongTheMajorAxis) {
  rundir::FaultPlan plan;
  plan.drop_line_end_fraction = 1;
  const geometry::Primitive right = primitive(geometry::Kind::kLine, {{0.7, 2.3}, {8.3, 2.3}});
  const geometry::Primitive left = primitive(geometry::Kind::kLine, {{8.3, 2.3}, {0.7, 2.3}});
  auto row = [](int x0, int x1) {
    std::vector<Pixel> p;
    for (int x = x0; x <= x1; ++x) p.push_back({x, 2});
    return PixelSet::from_pixels(p);
  };
  ASSERT_EQ(reference(right), row(0, 7));
  ASSERT_EQ(reference(left), row(1, 8));
  EXPECT_EQ(draw(plan, right), row(0, 6));
  EXPECT_EQ(draw(plan, left), row(2, 8));
  // y-major, going down: the lowest pixel goes.
  const geometry::Primitive down = primitive(geometry::Kind::kLine, {{4.2, 13.3}, {5.1, 3.7}});
  PixelSet want = reference(down);
  ASSERT_GT(want.size(), 5);
  want.erase(want.front());
  EXPECT_EQ(draw(plan, down), want);
  EXPECT_EQ(draw(plan, kTriangle), reference(kTriangle));
}

// flaky_fraction 1: shifted on the first attempt, drawn right when the coordinator retries
// (RA_RENDER_ATTEMPT=2, read when the platform is made).
TEST(FaultyPlatform, AFlakyPrimitiveIsShiftedOnTheFirstAttemptOnly) {
  rundir::FaultPlan plan;
  plan.flaky_fraction = 1;
  PixelSet shifted = reference(kTriangle);
  shifted.translate(1, 0);
  {
    const ScopedEnv first("RA_RENDER_ATTEMPT", nullptr);
    EXPECT_EQ(draw(plan, kTriangle), shifted);
  }
  {
    const ScopedEnv retry("RA_RENDER_ATTEMPT", "2");
    EXPECT_EQ(draw(plan, kTriangle), reference(kTriangle));
  }
}

// A primitive on the crash list kills the process with SIGSEGV, as a crashing driver does; the
// others before it draw.
TEST(FaultyPlatformDeathTest, APrimitiveOnTheCrashListKillsTheProcessWithSegv) {
  ::testing::FLAGS_gtest_death_test_style = "threadsafe";
  rundir::FaultPlan plan;
  plan.crash = {3};
  auto platform = create_faulty_platform(plan);
  platform->set_view(window_view());
  geometry::Primitive fine = kTriangle;
  fine.index = 2;
  EXPECT_EQ(platform->render(fine, whole()).lit, reference(kTriangle));
  EXPECT_EXIT(
      {
        const rlimit no_core{};  // zero: the child's crash leaves no core file behind
        setrlimit(RLIMIT_CORE, &no_core);
        platform->render(kTriangle, whole());
      },
      ::testing::KilledBySignal(SIGSEGV), "");
}

// base = an OSMesa platform: GL draws, and the wild pixel is lit by GL inside the occlusion query
// (found by the readback's proof); the driver's name says faults are injected.
TEST(FaultyPlatform, OnAnOsmesaBaseDrawsWhatThatPlatformDraws) {
  rundir::FaultPlan plan;
  plan.base = "osmesa-llvmpipe";
  plan.wild_pixel = {3};
  auto faulty = create_faulty_platform(plan);
  auto gl = create_gl_platform(*rundir::find_platform("osmesa-llvmpipe"));
  const std::string renderer = faulty->driver_info().renderer;
  EXPECT_NE(renderer.find("llvmpipe"), std::string::npos) << renderer;
  EXPECT_EQ(renderer, gl->driver_info().renderer + " + injected faults");
  faulty->set_view(window_view());
  gl->set_view(window_view());
  const geometry::PixelRegion region(geometry::PixelRect{0, 0, 14, 15});
  geometry::Primitive clean = kTriangle;
  clean.index = 2;
  const PixelSet drawn = gl->render(clean, region).lit;
  EXPECT_GT(drawn.size(), 40);
  EXPECT_EQ(faulty->render(clean, region).lit, drawn);
  const RenderResult wild = faulty->render(kTriangle, region);
  EXPECT_EQ(wild.lit.size(), drawn.size() + 1);
  EXPECT_EQ(geometry::set_difference(drawn, wild.lit).size(), 0);
  EXPECT_TRUE(wild.full_scan);  // the extra fragment broke the region's proof
}

}  // namespace
}  // namespace ra::platforms
