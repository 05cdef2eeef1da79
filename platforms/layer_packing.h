// Which layer of a layered window (platforms/raster_device.h) each primitive of a batch is drawn
// into. Primitives whose expected regions are disjoint may share a layer: each is told apart by
// its colour, and its occlusion count proves that none of its pixels fell outside its region. A
// primitive whose region overlaps one already in a layer goes to another, so that it cannot
// overwrite it. Regions are in GL window pixels (geometry/pixel_region.h).
//
// First fit, in the order the primitives come: the runner packs as it forms a batch and the
// measurement packs the same batch again, and both get the same layers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "geometry/pixel_region.h"

namespace ra::platforms {

class LayerPacker {
 public:
  // `layers` >= 1 layers, at most `max_primitives` primitives in all. A region larger than
  // `max_shared_area` pixels takes a layer of its own (nothing joins it): its readback is not
  // small, and a batch of one large primitive is what a window without layers draws.
  LayerPacker(int layers, size_t max_primitives, int64_t max_shared_area);

  // The layer the region goes into, or -1 when the batch has no room for it (then nothing changed).
  int place(const geometry::PixelRegion& region);
  size_t size() const { return placed_; }
  void clear();

 private:
  struct Layer {
    std::vector<geometry::PixelRegion> regions;
    bool closed = false;  // holds a large region
  };
  int layers_;
  size_t max_primitives_;
  int64_t max_shared_area_;
  size_t placed_ = 0;
  std::vector<Layer> used_;
};

// The layers of a whole batch, or an empty vector when it does not fit.
std::vector<int> pack_layers(const std::vector<geometry::PixelRegion>& regions, int layers,
                             size_t max_primitives, int64_t max_shared_area);

}  // namespace ra::platforms
