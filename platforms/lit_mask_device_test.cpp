// The lit-pixel scan on the device (lit_mask.h; gl_lit_mask.cpp, vulkan_lit_mask.cpp), on
// llvmpipe through GL, lavapipe through Vulkan and zink on lavapipe (GL over Vulkan; each skipped,
// with the reason, where it cannot be brought up): for rectangles anywhere in a layered window, of any size around the 32-pixel words,
// its masks hold exactly the pixels the host finds in the same rectangles read back, for a
// primitive's colour and for any colour, and its counts are their number.
#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

#include "platforms/gl_context.h"
#include "platforms/gl_lit_mask.h"
#include "platforms/lit_mask.h"
#include "platforms/mesa_drivers_testing.h"
#include "platforms/pixel_scan.h"
#include "platforms/raster_device.h"
#include "platforms/window_view_testing.h"
#include "util/errors.h"

namespace ra::platforms {
namespace {

std::unique_ptr<RasterDevice> make_device(const std::string& name, int layers) {
  const rundir::PlatformSpec spec = *rundir::find_platform(name);
  return spec.draws_with_vulkan() ? create_vulkan_device(spec, layers)
                                  : create_gl_device(spec, layers);
}

class ScanOnTheDevice : public ::testing::TestWithParam<const char*> {};

TEST_P(ScanOnTheDevice, FindsWhatTheHostFinds) {
  std::unique_ptr<RasterDevice> device;
  try {
    device = make_device(GetParam(), 3);
  } catch (const util::UserError& e) {
    GTEST_SKIP() << e.what();
  }
  ASSERT_TRUE(device->scans()) << GetParam();
  constexpr int kSize = 150;
  device->bind();
  device->set_view(testing::window_view(kSize));
  device->clear();
  ASSERT_EQ(device->layers(), 3);
  std::mt19937 rng(5);
  std::uniform_real_distribution<> coordinate(-5, kSize + 5);
  std::vector<geometry::Primitive> prims;
  std::vector<uint32_t> colours;
  std::vector<int> layers;
  for (int i = 0; i < 30; ++i) {
    std::vector<geometry::Vec2> points;
    for (int k = 0; k < 3; ++k) points.push_back({coordinate(rng), coordinate(rng)});
    const geometry::Kind kind = geometry::Kind(i % 3);
    points.resize(size_t(geometry::vertex_count(kind)));
    prims.push_back(testing::window_primitive(kind, points, uint64_t(i)));
    colours.push_back(uint32_t(1 + i) * 0x010203u);
    layers.push_back(i % 3);
  }
  device->draw_each(prims, colours, layers, false);
  std::vector<geometry::PixelRect> rects;
  std::vector<int> rect_layers;
  std::vector<uint32_t> rect_colours;
  for (int i = 0; i < 60; ++i) {
    const int x0 = int(rng() % kSize), y0 = int(rng() % kSize);
    const int x1 = x0 + 1 + int(rng() % uint32_t(kSize - x0));
    const int y1 = y0 + 1 + int(rng() % uint32_t(kSize - y0));
    rects.push_back({x0, y0, x1, y1});
    rect_layers.push_back(i % 3);
    rect_colours.push_back(i % 4 == 0 ? kAnyColour : colours[size_t(rng() % 30)]);
  }
  rects.push_back({0, 0, kSize, kSize});  // the whole window, for the colour of a triangle
  rect_layers.push_back(2);
  rect_colours.push_back(colours[29]);
  device->read(rects, rect_layers);
  std::vector<geometry::PixelSet> host(rects.size());
  for (size_t i = 0; i < rects.size(); ++i) {
    const geometry::PixelRect& r = rects[i];
    scan_rect(device->pixels(i), size_t(r.x1 - r.x0), device->rows_top_down(), r,
              rect_colours[i] == kAnyColour, rect_colours[i], host[i]);
  }
  device->scan(rects, rect_layers, rect_colours);
  int64_t lit = 0;
  for (size_t i = 0; i < rects.size(); ++i) {
    const geometry::PixelRect& r = rects[i];
    geometry::PixelSet on_device;
    append_mask_runs(device->mask(i), uint32_t(r.x1 - r.x0 + 31) / 32, device->rows_top_down(), r,
                     on_device);
    ASSERT_EQ(on_device, host[i]) << GetParam() << " rectangle " << i;
    EXPECT_EQ(device->lit_count(i), uint64_t(host[i].size())) << GetParam() << " rectangle " << i;
    lit += host[i].size();
  }
  EXPECT_GT(lit, 2000);  // the rectangles found something: the test compares real pixels
  // The drawing goes on after a scan (GL: the compute program is unbound): the same primitive
  // drawn again alone lights what it lit before.
  device->clear();
  device->draw_each({prims[29]}, {kWhite}, {0}, false);
  device->read({{0, 0, kSize, kSize}}, {});
  geometry::PixelSet again;
  scan_rect(device->pixels(0), kSize, device->rows_top_down(), {0, 0, kSize, kSize}, true, kWhite,
            again);
  EXPECT_EQ(again, host.back());
}

INSTANTIATE_TEST_SUITE_P(MesaDrivers, ScanOnTheDevice,
                         platforms::testing::mesa_drivers(),
                         platforms::testing::platform_test_name);

// The GLSL 4.30 text, which a context older than 4.5 gets, compiles and links as the 4.50 text does:
// every GL driver here is 4.5 or has no compute shaders, so this is the only place it is compiled.
TEST(GlLitMask, CompilesAsGlsl430And450) {
  std::unique_ptr<GlContext> context;
  try {
    context = create_gl_context(*rundir::find_platform("osmesa-llvmpipe"));
  } catch (const util::UserError& e) {
    GTEST_SKIP() << e.what();
  }
  for (int version : {430, 450})
    EXPECT_NO_THROW(GlLitMask(context->gl(), version, "osmesa-llvmpipe")) << "GLSL " << version;
}

}  // namespace
}  // namespace ra::platforms
