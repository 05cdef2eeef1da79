// The Vulkan device (vulkan_device.cpp, vulkan_context.cpp): the platforms' names, the device
// choice and its errors, and what lavapipe draws against the reference rasterizer and GL (skipped,
// with the reason, where no Vulkan loader or lavapipe is installed).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "geometry/reference_rasterizer.h"
#include "platforms/platform.h"
#include "platforms/vulkan_context.h"
#include "util/errors.h"

namespace ra::platforms {
namespace {

// A view whose clip coordinates are GL window coordinates scaled to [-1, 1]: object (x, y) in
// pixels lands at window (x, y), y up. Asymmetric primitives in it show a flipped y at once.
geometry::View window_view(int w, int h) {
  geometry::View v;
  v.width = w;
  v.height = h;
  v.view_matrix = geometry::Mat4::identity();
  v.projection = geometry::Mat4::identity();
  v.projection.at(0, 0) = 2.0 / w;
  v.projection.at(0, 3) = -1;
  v.projection.at(1, 1) = 2.0 / h;
  v.projection.at(1, 3) = -1;
  v.view_projection = v.projection;
  return v;
}

geometry::Primitive make(geometry::Kind kind, std::initializer_list<geometry::Vec3> vs,
                         uint64_t index = 0) {
  geometry::Primitive p;
  p.kind = kind;
  p.index = index;
  int i = 0;
  for (const geometry::Vec3& v : vs) p.v[i++] = v;
  return p;
}

geometry::PixelRegion whole(const geometry::View& v) {
  return geometry::PixelRegion(geometry::PixelRect{0, 0, v.width, v.height});
}

// Skips the calling test (with the reason) where lavapipe cannot be brought up.
#define REQUIRE_LAVAPIPE()                                                                \
  do {                                                                                    \
    try {                                                                                 \
      choose_vulkan_device(*rundir::find_platform("vk-lavapipe"), list_vulkan_devices()); \
    } catch (const util::UserError& e) {                                                  \
      GTEST_SKIP() << "no lavapipe here: " << e.what();                                   \
    }                                                                                     \
  } while (0)

TEST(VulkanPlatformNames, FixedNamesAndDeviceIndices) {
  const auto lvp = rundir::find_platform("vk-lavapipe");
  ASSERT_TRUE(lvp);
  EXPECT_EQ(lvp->backend, rundir::Backend::kVulkan);
  EXPECT_EQ(lvp->mesa_driver, "lavapipe");
  EXPECT_TRUE(lvp->draws_with_driver());
  EXPECT_FALSE(lvp->draws_with_gl());  // not for the GL-only studies
  EXPECT_FALSE(rundir::is_aliased_gl_platform("vk-lavapipe"));
  EXPECT_EQ(rundir::find_platform("vk-lavapipe-bresenham")->line_mode,
            rundir::PlatformSpec::LineMode::kBresenham);
  EXPECT_EQ(rundir::find_platform("vk-lavapipe-msaa4")->samples, 4);
  const auto d3 = rundir::find_platform("vk-device:3");
  ASSERT_TRUE(d3);
  EXPECT_EQ(d3->device, 3);
  EXPECT_EQ(d3->backend, rundir::Backend::kVulkan);
  EXPECT_EQ(rundir::find_platform("vk-device:3-bresenham")->line_mode,
            rundir::PlatformSpec::LineMode::kBresenham);
  EXPECT_EQ(rundir::find_platform("vk-device:3-msaa4")->samples, 4);
  EXPECT_EQ(rundir::find_platform("vk-device")->device, -1);
  for (const char* bad : {"vk-device:", "vk-device:x", "vk-device:-1", "vk-device:256",
                          "egl-device:3-bresenham", "vk-device:3-msaa4-bresenham", "vk-device@b"})
    EXPECT_FALSE(rundir::find_platform(bad)) << bad;
  const auto build = rundir::find_platform("vk-lavapipe@mesa-25.0.7");
  ASSERT_TRUE(build);
  EXPECT_EQ(build->build, "mesa-25.0.7");
}

VulkanDeviceInfo device(int index, const std::string& type, bool llvmpipe, bool bresenham) {
  VulkanDeviceInfo d;
  d.index = index;
  d.name = "device " + std::to_string(index);
  d.type = type;
  d.llvmpipe = llvmpipe;
  d.line_rasterization = true;
  d.rectangular_lines = true;
  d.bresenham_lines = bresenham;
  d.max_samples = 4;
  return d;
}

std::string error_of(const std::string& platform, const std::vector<VulkanDeviceInfo>& devices) {
  try {
    choose_vulkan_device(*rundir::find_platform(platform), devices);
  } catch (const util::UserError& e) {
    return e.what();
  }
  return "";
}

TEST(VulkanDeviceChoice, EachNameFindsItsDeviceOrSaysWhyNot) {
  const std::vector<VulkanDeviceInfo> devices = {device(0, "cpu", true, true),
                                                 device(1, "discrete GPU", false, false)};
  EXPECT_EQ(choose_vulkan_device(*rundir::find_platform("vk-lavapipe"), devices).index, 0);
  EXPECT_EQ(choose_vulkan_device(*rundir::find_platform("vk-device"), devices).index,
            1);  // not the CPU
  EXPECT_EQ(choose_vulkan_device(*rundir::find_platform("vk-device:0"), devices).index, 0);
  // an index beyond the list names the devices there are
  const std::string beyond = error_of("vk-device:7", devices);
  EXPECT_NE(beyond.find("there is no Vulkan device 7"), std::string::npos) << beyond;
  EXPECT_NE(beyond.find("1: device 1 (discrete GPU)"), std::string::npos) << beyond;
  // a line mode the driver lacks
  const std::string lines = error_of("vk-device:1-bresenham", devices);
  EXPECT_NE(lines.find("draws Bresenham lines, but Vulkan device 1 (device 1) offers only"),
            std::string::npos)
      << lines;
  EXPECT_NE(lines.find("rectangular"), std::string::npos) << lines;
  // no GPU, no lavapipe
  const std::string no_gpu = error_of("vk-device", {devices[0]});
  EXPECT_NE(no_gpu.find("no Vulkan device here is a GPU"), std::string::npos) << no_gpu;
  const std::string no_lvp = error_of("vk-lavapipe", {devices[1]});
  EXPECT_NE(no_lvp.find("mesa-vulkan-drivers"), std::string::npos) << no_lvp;
}

// Timestamps of a counter narrower than 64 bits wrap (timestampValidBits 36 on some Intel GPUs):
// the interval across one wrap, the bits above the valid ones ignored, and no counter at all.
TEST(VulkanTimestamps, IntervalsAcrossAWrap) {
  const uint64_t top36 = uint64_t(1) << 36;
  EXPECT_DOUBLE_EQ(timestamp_interval_us(1000, 3000, 64, 1.0), 2.0);
  EXPECT_DOUBLE_EQ(timestamp_interval_us(top36 - 10, 5, 36, 1.5), 15 * 1.5 / 1e3);
  EXPECT_DOUBLE_EQ(
      timestamp_interval_us((uint64_t(1) << 40) | 100, (uint64_t(1) << 41) | 150, 36, 2.0),
      50 * 2.0 / 1e3);
  EXPECT_DOUBLE_EQ(timestamp_interval_us(7, 7, 36, 1.0), 0.0);
  EXPECT_TRUE(
      std::isnan(timestamp_interval_us(3000, 1000, 64, 1.0)));  // a 64-bit counter never wraps
  EXPECT_TRUE(std::isnan(timestamp_interval_us(1000, 3000, 0, 1.0)));
}

TEST(VulkanLavapipe, ReportsItsLimits) {
  REQUIRE_LAVAPIPE();
  const auto p = create_vulkan_platform(*rundir::find_platform("vk-lavapipe"));
  const DriverInfo d = p->driver_info();
  EXPECT_NE(d.renderer.find("llvmpipe"), std::string::npos) << d.renderer;
  EXPECT_NE(d.version.find("Vulkan 1."), std::string::npos) << d.version;
  EXPECT_GE(d.subpixel_bits, 4);  // Vulkan's least subPixelPrecisionBits
  EXPECT_EQ(d.line_mode, "default");
}

// The window convention: an asymmetric triangle, a slanted segment and a point land on the
// reference rasterizer's GL window pixels (y up), not on their mirror images. The vertices lie on
// the 1/256 px grid lavapipe snaps to, and no pixel centre lies on an edge.
TEST(VulkanLavapipe, DrawsInGlWindowCoordinates) {
  REQUIRE_LAVAPIPE();
  const geometry::View view = window_view(128, 96);
  const auto p = create_vulkan_platform(*rundir::find_platform("vk-lavapipe"));
  p->set_view(view);
  const geometry::Primitive tri = make(geometry::Kind::kTriangle, {{10.26171875, 5.51171875, 0},
                                                                   {100.74609375, 20.12890625, 0},
                                                                   {30.50390625, 90.87109375, 0}});
  const geometry::PixelSet expected = geometry::rasterize_reference(view, tri);
  const RenderResult r = p->render(tri, whole(view));
  EXPECT_GT(expected.size(), 2000);
  EXPECT_EQ(r.lit, expected);
  // the mirror image (y -> 96 - y) is another set: a flipped y could not pass the check above
  geometry::Primitive mirrored = tri;
  for (geometry::Vec3& v : mirrored.v) v.y = 96 - v.y;
  EXPECT_NE(geometry::rasterize_reference(view, mirrored), expected);
  // a point lights the pixel holding it
  const geometry::Primitive point =
      make(geometry::Kind::kPoint, {{70.30078125, 12.69921875, 0}}, 1);
  geometry::PixelSet one;
  one.append_run(12, 70, 71);
  EXPECT_EQ(p->render(point, whole(view)).lit, one);
  EXPECT_GT(r.render_us, 0);
}

// A strict line is a rectangle: its pixels are the centres inside the segment's 1 px wide
// rectangle, counted here by brute force (every pixel centre against the rectangle).
TEST(VulkanLavapipe, DefaultLinesAreRectanglesUnderStrictLines) {
  REQUIRE_LAVAPIPE();
  const auto p = create_vulkan_platform(*rundir::find_platform("vk-lavapipe"));
  if (!p->driver_info().strict_lines) GTEST_SKIP() << "lavapipe without strictLines";
  const geometry::View view = window_view(64, 64);
  p->set_view(view);
  const geometry::Vec2 a{5.37109375, 7.12890625}, b{50.62890625, 30.26171875};
  const RenderResult r =
      p->render(make(geometry::Kind::kLine, {{a.x, a.y, 0}, {b.x, b.y, 0}}), whole(view));
  const geometry::Vec2 d = b - a;
  const double len = geometry::length(d);
  const geometry::Vec2 u = (1 / len) * d;
  geometry::PixelSet brute;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const geometry::Vec2 q = geometry::Vec2{x + 0.5, y + 0.5} - a;
      const double along = q.x * u.x + q.y * u.y, across = q.x * u.y - q.y * u.x;
      if (along > 0 && along < len && std::fabs(across) < 0.5) brute.append_run(y, x, x + 1);
    }
  EXPECT_GT(brute.size(), 45);
  EXPECT_EQ(r.lit, brute);
  EXPECT_EQ(geometry::rasterize_rectangle_segment(a, b, 64, 64), brute);
}

// The Bresenham mode is GL's diamond-exit.
TEST(VulkanLavapipe, BresenhamLinesAreDiamondExit) {
  REQUIRE_LAVAPIPE();
  const auto p = create_vulkan_platform(*rundir::find_platform("vk-lavapipe-bresenham"));
  const geometry::View view = window_view(64, 64);
  p->set_view(view);
  for (const auto& [a, b] : {std::pair<geometry::Vec2, geometry::Vec2>{{5.37109375, 7.12890625},
                                                                       {50.62890625, 30.26171875}},
                             {{40.12890625, 60.51171875}, {33.87109375, 2.26171875}}}) {
    const RenderResult r =
        p->render(make(geometry::Kind::kLine, {{a.x, a.y, 0}, {b.x, b.y, 0}}), whole(view));
    EXPECT_EQ(r.lit, geometry::rasterize_segment(a, b, 64, 64));
  }
}

// Polygons with a shared edge: every pixel whose centre is in the quad is lit by exactly one of
// the two triangles, and each triangle lights the reference's pixels.
TEST(VulkanLavapipe, TrianglesSharingAnEdgeLightEachPixelOnce) {
  REQUIRE_LAVAPIPE();
  const geometry::View view = window_view(64, 64);
  const auto p = create_vulkan_platform(*rundir::find_platform("vk-lavapipe"));
  p->set_view(view);
  const geometry::Vec3 a{3.12890625, 4.26171875, 0}, b{58.87109375, 9.51171875, 0},
      c{52.37109375, 60.12890625, 0}, d{6.62890625, 55.87109375, 0};
  const geometry::Primitive t1 = make(geometry::Kind::kTriangle, {a, b, c}, 1),
                            t2 = make(geometry::Kind::kTriangle, {a, c, d}, 2);
  const geometry::PixelSet p1 = p->render(t1, whole(view)).lit, p2 = p->render(t2, whole(view)).lit;
  EXPECT_EQ(p1, geometry::rasterize_reference(view, t1));
  EXPECT_EQ(p2, geometry::rasterize_reference(view, t2));
  // disjoint (no pixel of one in the other), and together the quad's pixels
  EXPECT_EQ(geometry::set_difference(p1, p2), p1);
  const geometry::PixelSet quad =
      geometry::rasterize_convex_polygon({{a.x, a.y}, {b.x, b.y}, {c.x, c.y}, {d.x, d.y}}, 64, 64);
  EXPECT_EQ(p1.size() + p2.size(), quad.size());
  EXPECT_TRUE(geometry::set_difference(quad, p1) == p2);
}

// A pixel lit far from the expected region (a driver bug) is found: the occlusion count exceeds
// what the region holds, and the whole window is read.
TEST(VulkanLavapipe, APixelOutsideTheRegionIsFound) {
  REQUIRE_LAVAPIPE();
  const geometry::View view = window_view(128, 128);
  const auto p = create_vulkan_platform(*rundir::find_platform("vk-lavapipe"),
                                        ReadbackMethod::kRegionWithProof, {5});
  p->set_view(view);
  const geometry::Primitive tri =
      make(geometry::Kind::kTriangle, {{10.25, 10.25, 0}, {20.75, 10.5, 0}, {12.5, 22.75, 0}}, 5);
  const geometry::PixelRegion region(geometry::PixelRect{8, 8, 24, 25});
  const RenderResult r = p->render(tri, region);
  EXPECT_TRUE(r.full_scan);
  EXPECT_EQ(r.lit.size(), geometry::rasterize_reference(view, tri).size() + 1);
  // a batch of small primitives shares one proof, and each gets its own pixels
  const auto clean = create_vulkan_platform(*rundir::find_platform("vk-lavapipe"));
  clean->set_view(view);
  std::vector<geometry::Primitive> prims;
  std::vector<geometry::PixelRegion> regions;
  for (int i = 0; i < 4; ++i) {
    const double x = 10 + 25 * i;
    prims.push_back(make(geometry::Kind::kTriangle,
                         {{x + 0.25, 40.25, 0}, {x + 12.75, 41.5, 0}, {x + 3.5, 55.75, 0}}, i));
    regions.push_back(geometry::PixelRegion(geometry::PixelRect{int(x) - 2, 38, int(x) + 16, 58}));
  }
  const std::vector<RenderResult> batch = clean->render_batch(prims, regions);
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(batch[i].lit, geometry::rasterize_reference(view, prims[i])) << i;
    EXPECT_EQ(batch[i].batch_size, 4);
    EXPECT_FALSE(batch[i].full_scan);
  }
}

// 4 samples: a pixel inside a large triangle has all 4 covered, one outside none; the total of
// samples lit equals the occlusion count (else the platform would have thrown).
TEST(VulkanLavapipe, MultisampleCoverage) {
  REQUIRE_LAVAPIPE();
  const geometry::View view = window_view(64, 64);
  const auto p = create_vulkan_platform(*rundir::find_platform("vk-lavapipe-msaa4"));
  p->set_view(view);
  const geometry::Primitive tri =
      make(geometry::Kind::kTriangle, {{4.1, 4.3, 0}, {60.2, 8.7, 0}, {20.9, 58.4, 0}});
  const RenderResult r = p->render(tri, whole(view));
  ASSERT_EQ(r.samples, 4);
  ASSERT_EQ(r.samples_lit.size(), size_t(r.lit.size()));
  size_t i = 0, full = 0;
  for (const geometry::Pixel& px : r.lit) {
    if (px.x == 25 && px.y == 25) {
      EXPECT_EQ(r.samples_lit[i], 4);
    }
    full += r.samples_lit[i] == 4;
    ++i;
  }
  // the area is 1480.5 px^2: the fully covered pixels are most of it, and fewer
  EXPECT_GT(full, 1300u);
  EXPECT_LT(full, 1481u);
  // drawn again, the erase left nothing behind: the same coverage
  const RenderResult again = p->render(tri, whole(view));
  EXPECT_EQ(again.lit, r.lit);
  EXPECT_EQ(again.samples_lit, r.samples_lit);
}

}  // namespace
}  // namespace ra::platforms
