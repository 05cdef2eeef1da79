// The layer packer (layer_packing.h): disjoint regions share a layer, overlapping ones never do, a
// large region takes a layer of its own, and with one layer it cuts batches exactly where the
// rule for windows without layers does (small, disjoint, at most the batch size; large alone),
// checked against that rule written out on random regions.
#include "platforms/layer_packing.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace ra::platforms {
namespace {

geometry::PixelRegion rect(int x0, int y0, int x1, int y1) {
  return geometry::PixelRegion(geometry::PixelRect{x0, y0, x1, y1});
}

TEST(LayerPacking, DisjointShareOverlappingSplitLargeAlone) {
  LayerPacker p(3, 64, 100);
  EXPECT_EQ(p.place(rect(0, 0, 5, 5)), 0);
  EXPECT_EQ(p.place(rect(10, 0, 15, 5)), 0);   // disjoint: same layer
  EXPECT_EQ(p.place(rect(3, 3, 8, 8)), 1);     // overlaps the first
  EXPECT_EQ(p.place(rect(4, 4, 6, 6)), 2);     // overlaps layers 0 and 1
  EXPECT_EQ(p.place(rect(50, 50, 52, 52)), 0); // first fit
  EXPECT_EQ(p.place(rect(3, 3, 5, 5)), -1);    // overlaps every layer: no room
  EXPECT_EQ(p.size(), 5u);
  p.clear();
  EXPECT_EQ(p.place(rect(0, 0, 20, 20)), 0);   // 400 px > 100: large, closes layer 0
  EXPECT_EQ(p.place(rect(30, 30, 31, 31)), 1); // disjoint, but layer 0 is closed
  EXPECT_EQ(p.place(rect(40, 40, 60, 60)), 2); // large: an empty layer of its own
  EXPECT_EQ(p.place(rect(70, 70, 71, 71)), 1);
  EXPECT_EQ(p.place(rect(80, 80, 99, 99)), -1);  // large, no empty layer left
}

TEST(LayerPacking, StopsAtTheBatchSize) {
  LayerPacker p(4, 3, 1000);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(p.place(rect(10 * i, 0, 10 * i + 5, 5)), 0);
  EXPECT_EQ(p.place(rect(100, 0, 105, 5)), -1);
  EXPECT_EQ(pack_layers({rect(0, 0, 5, 5), rect(2, 2, 6, 6)}, 1, 64, 1000), std::vector<int>{});
  EXPECT_EQ(pack_layers({rect(0, 0, 5, 5), rect(2, 2, 6, 6)}, 2, 64, 1000),
            (std::vector<int>{0, 1}));
}

// The batches of a window without layers, as the runner cut them before it had layers: flush
// before a primitive that is large, overlaps the batch or finds it full; flush after a large one.
std::vector<size_t> batch_sizes_by_rule(const std::vector<geometry::PixelRegion>& regions,
                                        size_t max_batch, int64_t max_area) {
  std::vector<size_t> sizes;
  std::vector<geometry::PixelRegion> batch;
  auto flush = [&] {
    if (!batch.empty()) sizes.push_back(batch.size());
    batch.clear();
  };
  for (const geometry::PixelRegion& r : regions) {
    const bool large = r.area() > max_area;
    bool clash = batch.size() >= max_batch || large;
    for (size_t k = 0; k < batch.size() && !clash; ++k) clash = batch[k].overlaps(r);
    if (clash) flush();
    batch.push_back(r);
    if (large) flush();
  }
  flush();
  return sizes;
}

TEST(LayerPacking, OneLayerCutsBatchesAsAWindowWithoutLayers) {
  std::mt19937 rng(2008);
  std::uniform_int_distribution<int> pos(0, 120), size(1, 24);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<geometry::PixelRegion> regions;
    for (int i = 0; i < 300; ++i) {
      const int x = pos(rng), y = pos(rng);
      regions.push_back(rect(x, y, x + size(rng), y + size(rng)));
    }
    LayerPacker packer(1, 8, 200);
    std::vector<size_t> sizes;
    for (const geometry::PixelRegion& r : regions) {
      if (packer.place(r) < 0) {
        sizes.push_back(packer.size());
        packer.clear();
        ASSERT_EQ(packer.place(r), 0);
      }
    }
    sizes.push_back(packer.size());
    ASSERT_EQ(sizes, batch_sizes_by_rule(regions, 8, 200)) << "trial " << trial;
  }
}

// Whatever the order, no two regions of one layer overlap and every layer is below the count.
TEST(LayerPacking, NoLayerHoldsOverlappingRegions) {
  std::mt19937 rng(7);
  std::uniform_int_distribution<int> pos(0, 60), size(1, 30);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<geometry::PixelRegion> regions;
    for (int i = 0; i < 40; ++i) {
      const int x = pos(rng), y = pos(rng);
      regions.push_back(rect(x, y, x + size(rng), y + size(rng)));
    }
    LayerPacker packer(6, 64, 400);
    std::vector<std::pair<geometry::PixelRegion, int>> placed;
    for (const geometry::PixelRegion& r : regions) {
      const int layer = packer.place(r);
      if (layer < 0) break;
      ASSERT_LT(layer, 6);
      for (const auto& [other, other_layer] : placed)
        if (other_layer == layer) ASSERT_FALSE(other.overlaps(r));
      placed.emplace_back(r, layer);
    }
    EXPECT_GE(placed.size(), 6u);  // at least one per layer fits
  }
}

}  // namespace
}  // namespace ra::platforms
