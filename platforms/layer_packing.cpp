#include "platforms/layer_packing.h"

namespace ra::platforms {

LayerPacker::LayerPacker(int layers, size_t max_primitives, int64_t max_shared_area)
    : layers_(layers < 1 ? 1 : layers),
      max_primitives_(max_primitives),
      max_shared_area_(max_shared_area) {}

int LayerPacker::place(const geometry::PixelRegion& region) {
  if (placed_ >= max_primitives_) return -1;
  const bool large = region.area() > max_shared_area_;
  int layer = -1;
  if (!large) {
    for (size_t k = 0; k < used_.size() && layer < 0; ++k) {
      if (used_[k].closed) continue;
      bool clash = false;
      for (const geometry::PixelRegion& r : used_[k].regions)
        if (r.overlaps(region)) {
          clash = true;
          break;
        }
      if (!clash) layer = int(k);
    }
  }
  if (layer < 0) {
    if (int(used_.size()) >= layers_) return -1;
    layer = int(used_.size());
    used_.emplace_back();
  }
  used_[size_t(layer)].regions.push_back(region);
  used_[size_t(layer)].closed = large;
  ++placed_;
  return layer;
}

void LayerPacker::clear() {
  used_.clear();
  placed_ = 0;
}

std::vector<int> pack_layers(const std::vector<geometry::PixelRegion>& regions, int layers,
                             size_t max_primitives, int64_t max_shared_area) {
  LayerPacker packer(layers, max_primitives, max_shared_area);
  std::vector<int> out;
  out.reserve(regions.size());
  for (const geometry::PixelRegion& r : regions) {
    const int layer = packer.place(r);
    if (layer < 0) return {};
    out.push_back(layer);
  }
  return out;
}

}  // namespace ra::platforms
