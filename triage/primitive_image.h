// One primitive of a run, re-rendered and drawn as a PNG for a person to look at (`renderaudit
// show`): which pixels the platform lit, which the reference rasterizer lights, and the ideal
// projection on top, so a changed or suspicious record can be seen rather than inferred.
//
// The image (OpenImageIO):
// - shows a rectangle of window pixels: the primitive's clipped bounding box, grown to hold every
//   pixel either rasterizer lit, plus kImageMargin pixels, clamped to the window; the whole window
//   when it is small (both sides <= kWholeWindowMax) or nothing is visible;
// - draws each window pixel as a scale x scale block, rows flipped (GL window y is up, image rows
//   go down): white = unlit, light grey = lit by both, orange = platform only, blue = reference
//   only (both differences GL allows), black = a pixel no conforming implementation could light
//   (forbidden) or leave dark (missing) (metrics/conformance.h); blocks of scale >= 8 have a
//   darker 1-px border, a pixel grid;
// - rings each forbidden or missing pixel in magenta with a white halo, so that one black pixel
//   among forty thousand lit ones is found at page size: nearby ones share a ring (pixels closer
//   than kMarkerJoin image pixels form a cluster, ringed as one), a cluster with as much black as
//   a square of kMarkerLargeCluster image pixels is seen without one (a crack one pixel wide is
//   ringed however long); a ring leaves the centre of each block it crosses, so it hides no
//   pixel's colour;
// - draws the ideal projection (clipping.h, window coordinates) as a 1-px red line on top: the
//   clipped polygon's outline, the clipped segment, or a cross at a projected point.
// The primitive is rendered once; the record printed with the image is measure_case()'s record of
// that very rendering (it equals the run's record for a deterministic platform).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/pixel_set.h"
#include "metrics/records.h"
#include "geometry/view.h"

namespace ra::triage {

constexpr int kImageMargin = 3;        // window pixels shown around the primitive
constexpr int kWholeWindowMax = 64;    // windows up to this size are shown whole
constexpr int kTargetImageSize = 512;  // the default scale makes the longer side about this
constexpr int kMaxImageScale = 256;
constexpr int kMaxImageSide = 16384;  // image pixels

// Colours, RGB.
struct Rgb8 {
  uint8_t r = 0, g = 0, b = 0;
  friend bool operator==(Rgb8 a, Rgb8 b) { return a.r == b.r && a.g == b.g && a.b == b.b; }
};
constexpr Rgb8 kUnlitColor{255, 255, 255};
constexpr Rgb8 kBothColor{150, 150, 150};  // mid grey: apart from white, the grid and black
constexpr Rgb8 kPlatformOnlyColor{230, 159, 0};   // Okabe-Ito orange
constexpr Rgb8 kReferenceOnlyColor{0, 114, 178};  // Okabe-Ito blue
constexpr Rgb8 kIdealColor{220, 0, 0};
constexpr Rgb8 kViolationColor{0, 0, 0};
constexpr Rgb8 kMarkerColor{210, 0, 210};  // magenta: the rings around forbidden and missing pixels

constexpr int kMarkerMinRadius = 10;      // image pixels: a ring around one pixel at scale 1
constexpr int kMarkerJoin = 24;           // image pixels: marked pixels this close share a ring
constexpr int kMarkerLargeCluster = 48;   // image pixels: a cluster this black all over needs no ring
constexpr std::size_t kMarkerMaxRings = 60;  // more clusters: joined over a longer distance

// A ring around a forbidden or missing pixel or a cluster of them: centre and radius in image
// pixels (columns to the right, rows down from the top of the picture); kMarkerColor within
// half_width of the radius, a 1-px white halo inside and outside. The radius is at least
// kMarkerMinRadius and 1/40 of the picture's longer side, the ring thicker in a picture of 600 px
// or more, so that it reads at page size.
struct MarkerRing {
  int cx = 0, cy = 0, radius = 0;
  int half_width = 1;
};

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
  int64_t missing = 0;    // black: dark although every conforming implementation lights them
};
// `violating`: the pixels a rule names (judge_primitive); those of `lit` are forbidden, the others
// missing. `shown` must hold every pixel of the three sets that should be drawn; `scale` >= 1.
PixelPicture draw_pixel_picture(const geometry::PixelSet& lit, const geometry::PixelSet& reference,
                                const geometry::PixelSet& violating,
                                const geometry::PixelRect& shown, int scale);

struct ShowRequest {
  std::string run_dir;   // holds experiment.toml
  std::string platform;  // any known platform (platform_names()), not only the run's
  std::string kind;      // "point", "line", "triangle" (or plural)
  int view = 1;          // 1-based, Table 1 order
  uint64_t index = 0;    // primitive index under the run's seed
  std::string out_path;  // .png; empty: RUN/show/PLATFORM.KIND.vVIEW.INDEX.png
  int scale = 0;         // image pixels per window pixel; 0: about kTargetImageSize px in all
};

struct PrimitiveImage {
  std::string path;           // PNG written
  int width = 0, height = 0;  // the picture of the window pixels, image pixels (top left of the PNG)
  int image_width = 0, image_height = 0;  // the PNG: the picture, the legend under it
  std::string legend_note;    // why the legend lacks its text, or ""
  int scale = 0;              // image pixels per window pixel
  geometry::PixelRect shown;  // window pixels shown, GL coordinates
  geometry::View view;
  metrics::Record record;                                   // measure_case() of this rendering
  int64_t both = 0, platform_only = 0, reference_only = 0;  // lit pixels, whole window
  int64_t violating = 0;  // pixels of platform_only + reference_only that GL forbids
  PixelPicture picture;   // the colours' counts (forbidden, missing) and the rings (no rgb)
};

// Loads RUN/experiment.toml, renders primitive `index` of `kind` in `view` on `platform` in this
// process, compares it with the reference rasterizer and writes the PNG. Throws ra::util::UserError
// saying what is wrong and what is allowed: no run directory, unknown platform or kind, view or
// index out of range, a scale out of range, a file that cannot be written.
PrimitiveImage show_primitive(const ShowRequest& request);

}  // namespace ra::triage
