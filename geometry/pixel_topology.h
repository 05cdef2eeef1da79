// Connectivity of a set of lit pixels (GL window pixels, PixelSet order): how many pieces, holes,
// and whether it is a one-pixel-wide chain. Used by the line audit (one chain? how many gaps?) and
// the triangle audit (simply connected?) of the NIST paper, sections 3.5-3.6.
//
// Definitions (digital topology needs a pair of adjacencies so that a closed curve separates):
// - Lit pixels are 8-connected: pixels (x, y) and (x', y') are adjacent when max(|dx|, |dy|) == 1.
//   A correct rasterization of a thin line or sliver is a diagonal staircase, which 8-adjacency
//   keeps in one piece.
// - Background (unlit) pixels are 4-connected (|dx| + |dy| == 1), the dual of 8 for lit pixels. A
//   hole is a 4-connected background component that cannot reach the outside of the set's
//   bounding box, i.e. background enclosed by lit pixels (a diagonal wall of lit pixels encloses).
// Cost: union-find over the set's horizontal runs, O(runs): a filled shape costs O(rows).
#pragma once

#include <cstdint>
#include <vector>

#include "geometry/pixel_set.h"

namespace ra::geometry {

struct PixelTopology {
  int64_t components = 0;  // 8-connected components of the lit pixels (0 for an empty set)
  int64_t holes = 0;       // enclosed 4-connected components of the unlit pixels
  // One piece without holes. An empty set is not simply connected.
  bool simply_connected() const { return components == 1 && holes == 0; }
};

PixelTopology pixel_topology(const PixelSet& s);

// Number of 8-connected components (0 for an empty set).
int64_t count_components8(const PixelSet& s);

// True when the lit pixels form one simple 8-connected chain: the graph with an edge between
// 8-adjacent lit pixels is a simple path (one pixel; or connected, exactly two pixels with one
// neighbour and every other pixel with exactly two). Excludes branches, loops, and "thick"
// corners such as (0,0), (1,0), (1,1), where three pixels are mutually adjacent. An ideal
// diamond-exit line is such a chain; an empty set is not.
bool is_simple_chain8(const PixelSet& s);

}  // namespace ra::geometry
