// The `faulty` test platform: the reference rasterizer plus the failures listed in the experiment's
// [faults] table. It exists so the pipeline's own handling of crashing and hanging drivers, wild
// pixels and changed primitives can be tested without a broken driver at hand.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <thread>

#include "util/counter_rng.h"
#include "platforms/platform.h"
#include "geometry/clipping.h"
#include "geometry/reference_rasterizer.h"

namespace ra::platforms {
namespace {

bool listed(const std::vector<uint64_t>& v, uint64_t i) {
  return std::find(v.begin(), v.end(), i) != v.end();
}

int render_attempt() {
  const char* a = std::getenv("RA_RENDER_ATTEMPT");
  return a ? std::atoi(a) : 1;
}

// A deterministic per-primitive draw in [0, 1), independent of shard and process.
double fault_draw(const geometry::Primitive& prim, uint64_t salt) {
  return double(util::splitmix64(util::splitmix64(prim.index * 3 + uint64_t(prim.kind)) ^ salt) >>
                11) *
         0x1.0p-53;
}

class FaultyPlatform : public Platform {
 public:
  explicit FaultyPlatform(rundir::FaultPlan plan) : plan_(std::move(plan)) {
    const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(plan_.base);
    if (spec && spec->draws_with_gl())  // wild pixels are then drawn by GL itself
      base_ = create_gl_platform(*spec, ReadbackMethod::kRegionWithProof, plan_.wild_pixel);
  }

  ~FaultyPlatform() override {
    if (plan_.hang_at_exit)  // what a driver that hangs in its teardown does
      for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
  }

  DriverInfo driver_info() const override {
    DriverInfo info{"renderaudit faulty test platform", "reference + injected faults",
                    "renderaudit", 0, false, 0, "none"};
    if (base_) info = base_->driver_info(), info.renderer += " + injected faults";
    return info;
  }
  double measure_timer_over_cpu() override {
    return base_ ? base_->measure_timer_over_cpu() : Platform::measure_timer_over_cpu();
  }
  void set_view(const geometry::View& view) override {
    view_ = view;
    if (base_) base_->set_view(view);
  }

  RenderResult render(const geometry::Primitive& prim,
                      const geometry::PixelRegion& expected) override {
    if (listed(plan_.crash, prim.index)) std::raise(SIGSEGV);  // what a crashing driver does
    if (listed(plan_.hang, prim.index))
      for (;;) std::this_thread::sleep_for(std::chrono::seconds(1));
    const auto t0 = Clock::now();
    RenderResult out = base_ ? base_->render(prim, expected) : draw_reference(prim);
    if (plan_.timed) {
      // The base's own measure of its drawing where it has one (a GL driver's), else the wall
      // time of the reference rasterization; the slowdown is spent here, inside the drawing.
      const double drawn_us = base_ ? out.render_us : microseconds_since(t0);
      const double extra_us = plan_.slows(prim.kind) ? plan_.slowdown * drawn_us : 0;
      const auto spin_from = Clock::now();
      while (microseconds_since(spin_from) < extra_us) {
      }
      const double spun_us = microseconds_since(spin_from);
      if (base_)
        out.render_us += spun_us, out.host_us += spun_us;
      else
        out.render_us = out.host_us = microseconds_since(t0);
    }
    return out;
  }

 private:
  using Clock = std::chrono::steady_clock;
  static double microseconds_since(Clock::time_point t) {
    return std::chrono::duration<double, std::micro>(Clock::now() - t).count();
  }

  RenderResult draw_reference(const geometry::Primitive& prim) {
    RenderResult out;
    const geometry::SubpixelGrid grid(plan_.snap_bits, plan_.snap_truncate
                                                           ? geometry::SnapRounding::kTruncate
                                                           : geometry::SnapRounding::kNearest);
    out.lit = geometry::rasterize_reference(view_, prim, grid);
    if (prim.kind == geometry::Kind::kLine && fault_draw(prim, 3) < plan_.drop_line_end_fraction)
      drop_last_pixel(prim, grid, out.lit);
    bool shift = fault_draw(prim, 1) < plan_.shift_fraction;
    if (fault_draw(prim, 2) < plan_.flaky_fraction && first_attempt_) shift = true;
    if (shift) out.lit.translate(1, 0);
    if (listed(plan_.wild_pixel, prim.index)) {
      // One pixel far from everything else: the opposite quadrant of the window.
      geometry::Pixel anchor = out.lit.empty() ? geometry::Pixel{0, 0} : out.lit.front();
      out.lit.insert({(anchor.x + view_.width / 2) % view_.width,
                      (anchor.y + view_.height / 2) % view_.height});
    }
    out.lit.clip_to({0, 0, view_.width, view_.height});
    out.render_us = out.host_us = 0;  // untimed unless the plan asks (FaultPlan::timed)
    out.full_scan = true;
    return out;
  }

  // Removes the pixel nearest the segment's second end along its major axis, as a Bresenham
  // loop that stops one step early does.
  void drop_last_pixel(const geometry::Primitive& prim, geometry::SubpixelGrid grid,
                       geometry::PixelSet& lit) const {
    if (lit.empty()) return;
    const geometry::ClippedSegment s = geometry::clip_segment(view_, prim.v[0], prim.v[1]);
    const geometry::Vec2 a{geometry::snap_to_subpixel(s.p0.x, grid),
                           geometry::snap_to_subpixel(s.p0.y, grid)};
    const geometry::Vec2 b{geometry::snap_to_subpixel(s.p1.x, grid),
                           geometry::snap_to_subpixel(s.p1.y, grid)};
    const bool x_major = std::fabs(b.x - a.x) >= std::fabs(b.y - a.y);
    const double dir = x_major ? b.x - a.x : b.y - a.y;
    geometry::Pixel last = lit.front();
    for (const geometry::Pixel& p : lit)
      if ((x_major ? p.x - last.x : p.y - last.y) * dir > 0) last = p;
    lit.erase(last);
  }

  rundir::FaultPlan plan_;
  std::unique_ptr<Platform> base_;  // an OSMesa platform when [faults] base names one
  geometry::View view_;
  // Flaky primitives are wrong on the first attempt only: a re-render (the coordinator's retry of
  // a failed shard, the audit's flake check) runs its worker with RA_RENDER_ATTEMPT=2.
  bool first_attempt_ = render_attempt() < 2;
};

}  // namespace

std::unique_ptr<Platform> create_faulty_platform(const rundir::FaultPlan& faults) {
  return std::make_unique<FaultyPlatform>(faults);
}

}  // namespace ra::platforms
