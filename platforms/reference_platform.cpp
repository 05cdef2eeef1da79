// The `reference` platform: the project's exact rasterizer (reference_rasterizer.h) behind the
// Platform interface, so an audit can run with no driver at all.
#include <chrono>

#include "platforms/platform.h"
#include "geometry/reference_rasterizer.h"

namespace ra::platforms {

namespace {

class ReferencePlatform : public Platform {
 public:
  DriverInfo driver_info() const override {
    return {"renderaudit reference rasterizer", "exact double precision", "renderaudit", 0, false,
            0, "none"};
  }
  void set_view(const geometry::View& view) override { view_ = view; }
  RenderResult render(const geometry::Primitive& prim, const geometry::PixelRegion&) override {
    RenderResult out;
    const auto t0 = std::chrono::steady_clock::now();
    out.lit = geometry::rasterize_reference(view_, prim);
    out.render_us = out.host_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    out.full_scan = true;  // nothing is read back: the set is complete by construction
    return out;
  }

 private:
  geometry::View view_;
};

}  // namespace

std::unique_ptr<Platform> create_reference_platform() {
  return std::make_unique<ReferencePlatform>();
}

}  // namespace ra::platforms
