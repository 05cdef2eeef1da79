// How the window pixels of one primitive become a picture that a person reads at page size
// (`renderaudit show`, and through it the driver upgrade report): what the platform lit, what the
// reference rasterizer lights, what GL forbids or requires, and the ideal projection. Pure: pixel
// sets in, RGB out, no driver and no file.
//
// Coordinates: window pixels in GL window coordinates (pixel (x, y) covers [x, x+1) x [y, y+1),
// y up); image pixels as columns to the right and rows down from the top of the picture. A
// picture shows window pixels `shown` at `scale` image pixels each, rows flipped.
//
// The picture:
// - each window pixel a scale x scale block: white = unlit, mid grey = lit by both the platform
//   and the reference, orange = by the platform only, blue = by the reference only (differences GL
//   allows), black = lit where no conforming implementation lights it (forbidden: ink where there
//   must be none), green hatching on white = dark where every conforming implementation lights it
//   (missing: a hole where ink must be) (metrics/conformance.h); blocks of scale >= 8 have a darker
//   1-px border, a pixel grid. Forbidden and missing differ in colour and in texture, so that a
//   line not drawn never looks like a line drawn;
// - a magenta ring with a white halo around the forbidden and missing pixels, so that one of them
//   among forty thousand lit pixels is found at page size: the outline at a fixed distance from
//   the convex hull of a cluster of them (a circle around one pixel, a capsule along a missing
//   line), so that it lies on the picture wherever they do. Marked pixels closer than kMarkerJoin
//   image pixels form a cluster (over longer distances when there would be more than
//   kMarkerMaxRings); a cluster with as much black as a kMarkerLargeCluster square, and on average
//   kMarkerThick image pixels thick, is seen without a ring (a crack one pixel wide is ringed
//   however long). A ring leaves the centre of each block it crosses, hiding no pixel's colour;
// - the ideal projection as a 1-px red line on top: the clipped polygon's outline, the clipped
//   segment, or a cross at a projected point;
// - an inset, where pixels differ and a window pixel is too small to see at page size (scale below
//   kInsetBelowScale): the window pixels around the largest cluster of differing pixels, enlarged
//   to about kInsetSide image pixels, drawn as the picture is, and framed where it lies in the
//   picture. Differing pixels are those another platform draws otherwise where its drawing is
//   given (`show --against`: then two pictures of one scale, each given the other's drawing, inset
//   the same window pixels), else the forbidden and missing ones, else those lit by one
//   rasterizer only;
// - where another platform's drawing is given, a magenta dot on each pixel it draws otherwise, in
//   the inset (in the picture where there is none), where those are few: at most an eighth of the
//   pixels there (a change of many pixels is seen without them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "geometry/pixel_set.h"
#include "geometry/vector_math.h"

namespace ra::triage {

// Colours, RGB.
struct Rgb8 {
  uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(Rgb8 a, Rgb8 b) { return a.r == b.r && a.g == b.g && a.b == b.b; }
};
constexpr Rgb8 kUnlitColor{255, 255, 255};
constexpr Rgb8 kBothColor{150, 150, 150};         // mid grey: apart from white, the grid and black
constexpr Rgb8 kPlatformOnlyColor{230, 159, 0};   // Okabe-Ito orange
constexpr Rgb8 kReferenceOnlyColor{0, 114, 178};  // Okabe-Ito blue
constexpr Rgb8 kIdealColor{220, 0, 0};
constexpr Rgb8 kForbiddenColor{0, 0, 0};    // solid: lit where GL forbids it
constexpr Rgb8 kMissingColor{0, 158, 115};  // Okabe-Ito bluish green, hatched on white
constexpr Rgb8 kMarkerColor{210, 0, 210};   // magenta: rings; dots on pixels drawn otherwise
constexpr Rgb8 kFrameColor{40, 40, 40};     // the inset's frame, in the picture and around it

constexpr int kMarkerMinRadius = 10;         // image pixels: a ring around one pixel at scale 1
constexpr int kMarkerJoin = 24;              // image pixels: marked pixels this close share a ring
constexpr int kMarkerLargeCluster = 48;      // image pixels: a cluster this black all over ...
constexpr int kMarkerThick = 8;              // ... and this thick on average needs no ring
constexpr std::size_t kMarkerMaxRings = 60;  // more clusters: joined over a longer distance

constexpr int kInsetBelowScale =
    6;  // a picture at a smaller scale gets an inset of its differences
constexpr int kInsetMinWindow = 12;  // window pixels on a side of the inset, at least ...
constexpr int kInsetMaxWindow = 32;  // ... and at most
constexpr int kInsetSide = 400;      // image pixels on a side of the inset, about

// The hatching of a missing pixel's block: whether image pixel (x, y) of it is kMissingColor (the
// others white): diagonal stripes, each about a quarter of a block wide (one image pixel at
// scales up to 7), continuous across neighbouring blocks.
bool missing_hatch(int x, int y, int scale);

// A ring around a cluster of forbidden or missing pixels: kMarkerColor within half_width of
// `radius` image pixels from the convex hull of the cluster's block centres, a 1-px white halo
// inside and outside. The radius is at least kMarkerMinRadius and 1/40 of the picture's longer
// side, and clears the blocks themselves; the ring is thicker in a picture of 600 px or more, so
// that it reads at page size.
struct MarkerRing {
  int cx = 0, cy = 0;  // the centre of the box of the cluster's block centres
  int radius = 0;
  int half_width = 1;
  std::vector<std::pair<int, int>> hull;  // convex, counter-clockwise; 1 point: a circle
};
// How far a ring and its halo reach from the centre of a marked block, image pixels, in a picture
// whose longer side is `longer_side` at `scale`: a picture shows this much around what it marks.
int marker_ring_reach(int longer_side, int scale);

// The picture of window pixels `shown` at `scale` image pixels each, before the ideal projection
// is drawn on it: the blocks in their colours (above) and the rings. Counts: window pixels of each
// colour, whole window.
struct PixelPicture {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;  // width * height * 3, rows from the top
  std::vector<MarkerRing> rings;
  int64_t large_clusters = 0;  // clusters of marked pixels seen without a ring
  int64_t both = 0, platform_only = 0, reference_only = 0;  // grey, orange, blue
  int64_t forbidden = 0;  // black: lit although no conforming implementation lights them
  int64_t missing = 0;  // hatched green: dark although every conforming implementation lights them
};
// `violating`: the pixels a rule names (judge_primitive); those of `lit` are forbidden, the others
// missing. `shown` must hold every pixel of the three sets that should be drawn; `scale` >= 1.
PixelPicture draw_pixel_picture(const geometry::PixelSet& lit, const geometry::PixelSet& reference,
                                const geometry::PixelSet& violating,
                                const geometry::PixelRect& shown, int scale);

// What one primitive's picture is made of.
struct PictureLayers {
  geometry::PixelSet lit, reference, violating;  // as draw_pixel_picture takes them
  std::vector<geometry::Vec2> ideal;  // window coordinates: 1 point (a cross), 2 (a segment),
                                      // 3 or more (a closed polygon), none (not visible)
  bool has_other = false;             // another platform's drawing of the same primitive is given
  geometry::PixelSet other;           // its lit pixels
  int window_width = 0, window_height = 0;  // the view's window, pixels
};

// The inset: window pixels `window` at `scale` image pixels each; empty where there is none.
struct InsetChoice {
  geometry::PixelRect window;
  int scale = 0;
  int64_t differing = 0;  // differing pixels, whole window (of the kind it was chosen from)
};
// The inset of a picture at `scale` (see the header comment). Whether there is one depends on
// `scale`; which window pixels and at what scale on the layers alone, so that two platforms each
// given as the other's get the same.
InsetChoice choose_inset(const PictureLayers& layers, int scale);

// The whole picture: `main` the picture of `shown` with the ideal projection and the inset's
// frame on it; `inset`, where one was chosen, the inset drawn the same way (rgb empty where none);
// the pixels drawn otherwise dotted in the inset, or in `main` where there is none, where few.
struct ComposedPicture {
  PixelPicture main, inset;
  InsetChoice inset_choice;
  int frame_width = 0;           // image pixels of the frame's line, in both
  int64_t drawn_otherwise = -1;  // pixels the other platform draws otherwise; -1: none given
  bool dotted = false;           // they are dotted (in the inset, or in `main` where none)
};
ComposedPicture compose_picture(const PictureLayers& layers, const geometry::PixelRect& shown,
                                int scale);

}  // namespace ra::triage
