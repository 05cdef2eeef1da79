#include "runner/reference_platform.h"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "runner/platform.h"
#include "runner/point_metrics.h"

namespace ra {

PixelSet reference_render(const View& view, const Primitive& prim) {
  PixelSet out;
  switch (prim.kind) {
    case Kind::kPoint: {
      // A size-1 point lights the pixel that contains its window position.
      const IdealPoint p = project_point(view, prim.v[0]);
      if (p.visible) {
        const Pixel px{int32_t(std::floor(p.window.x)), int32_t(std::floor(p.window.y))};
        if (px.x >= 0 && px.x < view.width && px.y >= 0 && px.y < view.height) out.push_back(px);
      }
      break;
    }
    case Kind::kLine:
    case Kind::kTriangle:
      throw std::logic_error("reference rasterizer: lines and triangles are not supported yet");
  }
  return out;
}

namespace {

class ReferencePlatform : public Platform {
 public:
  DriverInfo driver_info() const override {
    return {"renderaudit reference rasterizer", "exact double precision", "renderaudit", 0, false};
  }
  void set_view(const View& view) override { view_ = view; }
  RenderResult render(const Primitive& prim, const PixelRect&) override {
    RenderResult out;
    const auto t0 = std::chrono::steady_clock::now();
    out.lit = reference_render(view_, prim);
    out.render_us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    out.full_scan = true;  // nothing is read back: the set is complete by construction
    return out;
  }

 private:
  View view_;
};

}  // namespace

std::unique_ptr<Platform> create_reference_platform() {
  return std::make_unique<ReferencePlatform>();
}

}  // namespace ra
