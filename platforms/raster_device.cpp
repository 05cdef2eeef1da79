#include "platforms/raster_device.h"

#include <algorithm>
#include <stdexcept>

namespace ra::platforms {

int layers_for_window(int w, int h, int max_layers) {
  const size_t bytes = size_t(std::max(w, 1)) * size_t(std::max(h, 1)) * 4;
  int layers = int(std::min<size_t>(kLayerBudgetBytes / bytes, size_t(kMaxLayers)));
  if (max_layers > 0) layers = std::min(layers, max_layers);
  return std::max(layers, 1);
}

// A device without the scan on the device: callers ask scans() first.
void RasterDevice::scan(const std::vector<geometry::PixelRect>&, const std::vector<int>&,
                        const std::vector<uint32_t>&) {
  throw std::logic_error("RasterDevice::scan: this device does not scan");
}
const uint32_t* RasterDevice::mask(size_t) const {
  throw std::logic_error("RasterDevice::mask: this device does not scan");
}
uint64_t RasterDevice::lit_count(size_t) const {
  throw std::logic_error("RasterDevice::lit_count: this device does not scan");
}

}  // namespace ra::platforms
