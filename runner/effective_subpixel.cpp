#include "runner/effective_subpixel.h"

#include <cmath>

#include "geometry/clipping.h"
#include "util/counter_rng.h"

namespace ra::runner {

namespace {

constexpr int kWindow = 128;
constexpr uint64_t kCalibrationSeed = 0x5ab9'1e1c'a11b'ca7eull;
constexpr uint64_t kCalibrationStream = 0xca1b;
// Far above any experiment's primitive indices, so that a test platform's faults listed by index
// (crash, hang) never hit a calibration triangle.
constexpr uint64_t kCalibrationIndexBase = uint64_t(1) << 62;

// A window coordinate in [8, 120] on the odd multiples of 2^-15 px: never a tie (a midpoint) of
// any candidate grid of 13 bits or fewer, and exact in float as the world coordinate below.
double calibration_coordinate(util::CounterRng& rng) {
  const int64_t k = rng.integer(8 << 14, 120 << 14);  // units of 2^-14 px
  return std::ldexp(double(2 * k + 1), -15);
}

}  // namespace

geometry::View calibration_view() {
  geometry::View v = geometry::make_view(90, kWindow, kWindow, 0.01, 10.0);
  v.id = 0;
  return v;
}

std::vector<geometry::Primitive> calibration_triangles() {
  std::vector<geometry::Primitive> out;
  for (int i = 0; i < kCalibrationTriangles; ++i) {
    util::CounterRng rng(kCalibrationSeed, kCalibrationStream, uint64_t(i));
    geometry::Primitive p;
    p.kind = geometry::Kind::kTriangle;
    p.index = kCalibrationIndexBase + uint64_t(i);
    for (int k = 0; k < 3; ++k) {
      // Window x = (X + 1) * 64 at depth 1 under a 90-degree camera (tan 45 = 1): X = x / 64 - 1.
      const double x = calibration_coordinate(rng), y = calibration_coordinate(rng);
      p.v[k] = {x / (kWindow / 2) - 1.0, y / (kWindow / 2) - 1.0, -1.0};
    }
    out.push_back(p);
  }
  return out;
}

EffectiveSubpixel measure_effective_subpixel(platforms::Platform& platform) {
  EffectiveSubpixel out;
  out.candidates.push_back({geometry::SubpixelGrid(0), 0});
  for (int bits = kMaxCandidateSubpixelBits; bits >= 1; --bits) {
    out.candidates.push_back({geometry::SubpixelGrid(bits, geometry::SnapRounding::kNearest), 0});
    out.candidates.push_back({geometry::SubpixelGrid(bits, geometry::SnapRounding::kTruncate), 0});
  }
  const geometry::View view = calibration_view();
  platform.set_view(view);
  for (const geometry::Primitive& prim : calibration_triangles()) {
    const geometry::ClippedPolygon poly =
        geometry::clip_triangle(view, prim.v[0], prim.v[1], prim.v[2]);
    const geometry::PixelSet lit =
        platform.render(prim, geometry::bounding_rect(poly, view.width, view.height, 2)).lit;
    ++out.triangles;
    for (SubpixelCandidate& c : out.candidates)
      if (geometry::rasterize_polygon(poly, view.width, view.height, c.grid) == lit) ++c.matches;
  }
  out.grid = out.candidates.front().grid;
  out.matches = out.candidates.front().matches;
  for (const SubpixelCandidate& c : out.candidates)
    if (c.matches > out.matches) out.grid = c.grid, out.matches = c.matches;
  return out;
}

nlohmann::json effective_subpixel_json(const EffectiveSubpixel& e) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const SubpixelCandidate& c : e.candidates)
    candidates.push_back({{"grid", geometry::subpixel_grid_text(c.grid)}, {"matches", c.matches}});
  return {{"bits", e.grid.exact() ? 0 : e.grid.bits},
          {"rounding", e.grid.exact() ? "none" : geometry::snap_rounding_name(e.grid.rounding)},
          {"text", geometry::subpixel_grid_text(e.grid)},
          {"matches", e.matches},
          {"triangles", e.triangles},
          {"candidates", candidates}};
}

}  // namespace ra::runner
