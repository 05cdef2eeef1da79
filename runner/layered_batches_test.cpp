// Layered batches (platforms/layer_packing.h, RasterDevice::draw_each): overlapping lines and
// triangles drawn many per wait, each in its own layer with its own proof, give records equal in
// every column but the timing ones to those of primitives drawn one at a time, on llvmpipe (GL),
// lavapipe (Vulkan) and zink on lavapipe (GL whose commands become Vulkan submissions, as on a
// GPU's Vulkan driver; each skipped where it is missing); and the device's clock, where asked for,
// fills render_us from timestamps with the host's share of the wait beside it. The scan on the
// device gives the host scan's records.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "platforms/platform.h"
#include "platforms/mesa_drivers_testing.h"
#include "platforms/vulkan_context.h"
#include "runner/case_measurement.h"
#include "util/errors.h"

namespace ra::runner {
namespace {

std::unique_ptr<platforms::Platform> make_platform(const std::string& name,
                                                   const platforms::BatchOptions& batching) {
  const rundir::PlatformSpec spec = *rundir::find_platform(name);
  if (spec.draws_with_vulkan())
    return platforms::create_vulkan_platform(spec, platforms::ReadbackMethod::kRegionWithProof, {},
                                             batching);
  return platforms::create_gl_platform(spec, platforms::ReadbackMethod::kRegionWithProof, {},
                                       batching);
}

bool available(const std::string& name, std::string* why) {
  try {
    make_platform(name, {});
    return true;
  } catch (const util::UserError& e) {
    *why = e.what();
    return false;
  }
}

std::vector<geometry::Primitive> primitives(geometry::Kind kind, uint64_t n) {
  std::vector<geometry::Primitive> prims;
  for (uint64_t i = 0; i < n; ++i) prims.push_back(geometry::make_primitive(2008, kind, i));
  return prims;
}

class LayeredBatches : public ::testing::TestWithParam<const char*> {};

// Every kind at both FOVs and both window sizes of the NIST views: the layered measurement equals
// the one without layers record for record, and really drew overlapping primitives together.
TEST_P(LayeredBatches, EqualOneAtATimeRecords) {
  std::string why;
  if (!available(GetParam(), &why)) GTEST_SKIP() << why;
  platforms::BatchOptions one_layer, layered;
  one_layer.max_layers = 1;
  layered.max_layers = 16;
  auto single = make_platform(GetParam(), one_layer);
  auto batched = make_platform(GetParam(), layered);
  for (int size : {128, 907}) {
    for (double fov : {30.0, 150.0}) {
      const geometry::View view =
          geometry::make_view(fov, size, size, 0.01, 10.0, geometry::random_rotation(2008, 3));
      single->set_view(view);
      batched->set_view(view);
      EXPECT_EQ(single->batch_layers(), 1);
      EXPECT_EQ(batched->batch_layers(), 16);
      for (geometry::Kind kind :
           {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
        const std::vector<geometry::Primitive> prims = primitives(kind, size == 907 ? 96 : 160);
        const auto a = measure_cases(GetParam(), *single, view, prims, true);
        const auto b = measure_cases(GetParam(), *batched, view, prims, true);
        ASSERT_EQ(a.size(), b.size());
        int64_t drawn_together = 0, lit = 0;
        for (size_t i = 0; i < a.size(); ++i) {
          ASSERT_EQ(metrics::untimed_record_line(a[i]), metrics::untimed_record_line(b[i]))
              << GetParam() << " " << geometry::kind_name(kind) << " " << size << " FOV " << fov;
          EXPECT_EQ(b[i].clock, "host");
          EXPECT_EQ(b[i].render_us, b[i].host_us);
          if (b[i].batch_size > a[i].batch_size) ++drawn_together;
          lit += b[i].pixels;
        }
        EXPECT_GT(lit, 0);
        // Lines and triangles overlap in these views: without layers most go alone.
        if (kind != geometry::Kind::kPoint) EXPECT_GT(drawn_together, int64_t(a.size()) / 2);
      }
    }
  }
}

// Forced onto the device's timer (these CPU drivers have one, though run does not use it there):
// every primitive of a batch gets its own device time and its share of the host's wait.
TEST_P(LayeredBatches, TheDeviceClockTimesEachPrimitive) {
  std::string why;
  if (!available(GetParam(), &why)) GTEST_SKIP() << why;
  platforms::BatchOptions device;
  device.max_layers = 8;
  device.clock = platforms::BatchOptions::Clock::kDevice;
  platforms::BatchOptions host_only;
  host_only.max_layers = 1;
  auto timed = make_platform(GetParam(), device);
  auto plain = make_platform(GetParam(), host_only);
  const geometry::View view =
      geometry::make_view(30, 128, 128, 0.01, 10.0, geometry::random_rotation(2008, 5));
  timed->set_view(view);
  plain->set_view(view);
  for (geometry::Kind kind :
       {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
    const std::vector<geometry::Primitive> prims = primitives(kind, 100);
    const auto t = measure_cases(GetParam(), *timed, view, prims, true);
    const auto p = measure_cases(GetParam(), *plain, view, prims, true);
    for (size_t i = 0; i < t.size(); ++i) {
      ASSERT_EQ(metrics::untimed_record_line(t[i]), metrics::untimed_record_line(p[i]))
          << geometry::kind_name(kind) << i;
      if (t[i].status != metrics::CaseStatus::kOk) continue;
      EXPECT_EQ(t[i].clock, "device");
      EXPECT_EQ(p[i].clock, "host");
      EXPECT_TRUE(std::isfinite(t[i].render_us) && t[i].render_us >= 0) << t[i].render_us;
      EXPECT_GT(t[i].host_us, 0);
      EXPECT_GE(t[i].batch_size, 1);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(MesaDrivers, LayeredBatches,
                         platforms::testing::mesa_drivers(),
                         platforms::testing::platform_test_name);

// Two overlapping triangles forced into one layer: the second overwrites part of the first, whose
// count then exceeds its pixels; it is found whole by its redraw alone, as if drawn alone.
void expect_overwritten_primitive_drawn_again_alone(const std::string& platform,
                                                    platforms::BatchOptions::Scan scan) {
  platforms::BatchOptions device;
  device.max_layers = 4;
  device.clock = platforms::BatchOptions::Clock::kDevice;  // each primitive its own proof
  device.scan = scan;
  auto timed = make_platform(platform, device);
  auto plain = make_platform(platform, {});
  const geometry::View view = geometry::make_view(90, 64, 64);
  timed->set_view(view);
  plain->set_view(view);
  geometry::Primitive a, b;
  a.kind = b.kind = geometry::Kind::kTriangle;
  a.v = {geometry::Vec3{-0.5, -0.5, -1}, geometry::Vec3{0.5, -0.5, -1}, geometry::Vec3{0, 0.5, -1}};
  b.v = {geometry::Vec3{-0.5, 0.5, -1}, geometry::Vec3{0.5, 0.5, -1}, geometry::Vec3{0, -0.5, -1}};
  b.index = 1;
  const geometry::PixelRegion whole(geometry::PixelRect{0, 0, 64, 64});
  const auto together = timed->render_batch({a, b}, {whole, whole}, {0, 0});
  const auto alone_a = plain->render(a, whole), alone_b = plain->render(b, whole);
  ASSERT_EQ(together.size(), 2u);
  EXPECT_EQ(together[0].lit, alone_a.lit) << platform;
  EXPECT_EQ(together[1].lit, alone_b.lit) << platform;
  EXPECT_TRUE(together[0].full_scan);   // a's proof failed in the batch
  EXPECT_EQ(together[0].batch_size, 1); // and it was drawn again alone
  EXPECT_FALSE(together[1].full_scan);
  EXPECT_EQ(together[1].batch_size, 2);
  EXPECT_GT(alone_a.lit.size(), 100u);
}

TEST(LayeredBatchesProof, AnOverwrittenPrimitiveIsDrawnAgainAlone) {
  expect_overwritten_primitive_drawn_again_alone("osmesa-llvmpipe",
                                                 platforms::BatchOptions::Scan::kHost);
}

// The scan on the device (platforms/lit_mask.h), forced, with layers and without:
// every record equal to the host scan's in every column but timing, and the proofs' fallbacks
// (a primitive searched in its whole layer, then drawn again alone) take the same path.
class DeviceScan : public ::testing::TestWithParam<const char*> {};

TEST_P(DeviceScan, EqualsTheHostScanRecordForRecord) {
  std::string why;
  if (!available(GetParam(), &why)) GTEST_SKIP() << why;
  platforms::BatchOptions host, device_one_layer, device_layered;
  host.max_layers = device_one_layer.max_layers = 1;
  device_layered.max_layers = 16;
  device_one_layer.scan = device_layered.scan = platforms::BatchOptions::Scan::kDevice;
  auto reference = make_platform(GetParam(), host);
  auto one_layer = make_platform(GetParam(), device_one_layer);
  auto layered = make_platform(GetParam(), device_layered);
  for (int size : {128, 907}) {
    const geometry::View view =
        geometry::make_view(size == 128 ? 150.0 : 30.0, size, size, 0.01, 10.0,
                            geometry::random_rotation(2008, 3));
    for (auto* p : {reference.get(), one_layer.get(), layered.get()}) p->set_view(view);
    for (geometry::Kind kind :
         {geometry::Kind::kPoint, geometry::Kind::kLine, geometry::Kind::kTriangle}) {
      const std::vector<geometry::Primitive> prims = primitives(kind, 80);
      const auto a = measure_cases(GetParam(), *reference, view, prims, true);
      for (auto* p : {one_layer.get(), layered.get()}) {
        const auto b = measure_cases(GetParam(), *p, view, prims, true);
        ASSERT_EQ(a.size(), b.size());
        int64_t lit = 0;
        for (size_t i = 0; i < a.size(); ++i) {
          ASSERT_EQ(metrics::untimed_record_line(a[i]), metrics::untimed_record_line(b[i]))
              << geometry::kind_name(kind) << " " << size << " layers " << p->batch_layers();
          lit += b[i].pixels;
        }
        EXPECT_GT(lit, 0) << geometry::kind_name(kind) << " " << size;
      }
    }
  }
}

TEST_P(DeviceScan, AnOverwrittenPrimitiveIsFoundByItsRedrawAlone) {
  std::string why;
  if (!available(GetParam(), &why)) GTEST_SKIP() << why;
  expect_overwritten_primitive_drawn_again_alone(GetParam(), platforms::BatchOptions::Scan::kDevice);
}

INSTANTIATE_TEST_SUITE_P(MesaDrivers, DeviceScan,
                         platforms::testing::mesa_drivers(),
                         platforms::testing::platform_test_name);

}  // namespace
}  // namespace ra::runner
