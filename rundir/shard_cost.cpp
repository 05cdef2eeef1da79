// A rough cost model of shards (see the header).
#include "rundir/shard_cost.h"

#include <algorithm>
#include <array>
#include <optional>
#include <map>
#include <string>

#include "rundir/platform_spec.h"

namespace ra::rundir {
namespace {

struct KindCost {
  double fixed_us;      // per primitive, whatever its size
  double per_pixel_us;  // per pixel it lights
};

// [kind] for a driver: point, line, triangle
using DriverCost = std::array<KindCost, 3>;

const DriverCost& driver_cost(const std::string& platform) {
  static const DriverCost llvmpipe = {{{35, 0}, {30, 0.17}, {34, 0.025}}};
  static const DriverCost softpipe = {{{20, 0}, {20, 0.73}, {100, 0.31}}};
  static const DriverCost zink = {{{300, 0}, {250, 1.5}, {300, 0.2}}};  // ~8-12x llvmpipe
  // llvmpipe's core plus a queue submission and a fence wait per draw (docs/vulkan.md)
  static const DriverCost lavapipe = {{{40, 0}, {40, 0.2}, {50, 0.03}}};
  static const DriverCost reference = {{{1, 0}, {2, 0.04}, {6, 0.003}}};
  const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(platform);
  if (spec && spec->draws_with_vulkan()) return lavapipe;
  if (!spec || !spec->draws_with_gl()) return reference;
  if (spec->mesa_driver == "softpipe") return softpipe;
  if (spec->mesa_driver == "zink") return zink;
  return llvmpipe;
}

double mean_pixels(geometry::Kind kind, const geometry::View& v) {
  switch (kind) {
    case geometry::Kind::kPoint:
      return 1;
    case geometry::Kind::kLine:
      return 0.3 * std::max(v.width, v.height);
    case geometry::Kind::kTriangle:
      return 0.02 * double(v.width) * double(v.height);
  }
  return 1;
}

}  // namespace

double expected_shard_cost_us(const Shard& shard, const geometry::View& view) {
  const KindCost& c = driver_cost(shard.platform)[static_cast<std::size_t>(shard.kind)];
  double per_primitive = c.fixed_us + c.per_pixel_us * mean_pixels(shard.kind, view);
  // antialiased platforms draw and resolve 4 samples a pixel
  if (const std::optional<rundir::PlatformSpec> spec = rundir::find_platform(shard.platform);
      spec && spec->samples)
    per_primitive *= 4;
  return per_primitive * double(shard.size());
}

std::vector<Shard> largest_expected_cost_first(std::vector<Shard> shards, const Experiment& exp) {
  std::map<int, const geometry::View*> views;
  for (const geometry::View& v : exp.views) views[v.id] = &v;
  std::vector<std::pair<double, std::size_t>> keyed;
  for (std::size_t i = 0; i < shards.size(); ++i) {
    const auto it = views.find(shards[i].view);
    keyed.push_back({it == views.end() ? 0 : expected_shard_cost_us(shards[i], *it->second), i});
  }
  std::stable_sort(keyed.begin(), keyed.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  std::vector<Shard> out;
  out.reserve(shards.size());
  for (const auto& [cost, i] : keyed) out.push_back(std::move(shards[i]));
  return out;
}

}  // namespace ra::rundir
