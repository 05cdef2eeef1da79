#include "platforms/raster_device.h"

#include <algorithm>

namespace ra::platforms {

int layers_for_window(int w, int h, int max_layers) {
  const size_t bytes = size_t(std::max(w, 1)) * size_t(std::max(h, 1)) * 4;
  int layers = int(std::min<size_t>(kLayerBudgetBytes / bytes, size_t(kMaxLayers)));
  if (max_layers > 0) layers = std::min(layers, max_layers);
  return std::max(layers, 1);
}

}  // namespace ra::platforms
