// One primitive of a run, re-rendered and drawn as a PNG for a person to look at (`renderaudit
// show`): which pixels the platform lit, which the reference rasterizer lights, and the ideal
// projection on top, so a changed or suspicious record can be seen rather than inferred.
//
// The image (OpenImageIO) is the picture of triage/pixel_picture.h with its legend
// (triage/image_legend.h) under it. It shows a rectangle of window pixels: the primitive's clipped
// bounding box, grown to hold every pixel either rasterizer lit (and the other platform's, where
// one is given), plus kImageMargin pixels or the reach of a ring (marker_ring_reach) where that is
// more, clamped to the window; the whole window when it is small (both sides <= kWholeWindowMax)
// or nothing is visible. Each window pixel is a block of `scale` image pixels, by default so that
// the longer side is about kTargetImageSize (before the rings' room).
//
// Given another platform (`show --against`), the same primitive is also drawn there, in a child
// process (one Mesa per process), before this process makes its own context: both pictures of a
// pair show the same window pixels at the same scale and the same inset, around the pixels the two
// draw otherwise. The primitive is rendered once on `platform`; the record printed with the image
// is measure_case()'s record of that very rendering (it equals the run's record for a deterministic
// platform).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "geometry/pixel_set.h"
#include "geometry/view.h"
#include "metrics/records.h"
#include "triage/pixel_picture.h"

namespace ra::triage {

constexpr int kImageMargin = 3;        // window pixels shown around the primitive
constexpr int kWholeWindowMax = 64;    // windows up to this size are shown whole
constexpr int kTargetImageSize = 512;  // the default scale makes the longer side about this
constexpr int kMaxImageScale = 256;
constexpr int kMaxImageSide = 16384;  // image pixels

struct ShowRequest {
  std::string run_dir;   // holds experiment.toml
  std::string platform;  // any known platform (platform_names()), not only the run's
  std::string kind;      // "point", "line", "triangle" (or plural)
  int view = 1;          // 1-based, Table 1 order
  uint64_t index = 0;    // primitive index under the run's seed
  std::string out_path;  // .png; empty: RUN/show/PLATFORM.KIND.vVIEW.INDEX.png
  int scale = 0;         // image pixels per window pixel; 0: about kTargetImageSize px in all
  std::string against;   // another platform (any known one) to draw the same primitive, or ""
};

struct PrimitiveImage {
  std::string path;  // PNG written
  int width = 0,
      height = 0;  // the picture of the window pixels, image pixels (top left of the PNG)
  int image_width = 0, image_height = 0;  // the PNG: the picture, the legend under it
  std::string legend_note;                // why the legend lacks its text, or ""
  int scale = 0;                          // image pixels per window pixel
  geometry::PixelRect shown;              // window pixels shown, GL coordinates
  geometry::View view;
  metrics::Record record;                                   // measure_case() of this rendering
  int64_t both = 0, platform_only = 0, reference_only = 0;  // lit pixels, whole window
  int64_t violating = 0;    // pixels of platform_only + reference_only that GL forbids
  ComposedPicture picture;  // the colours' counts (forbidden, missing), the rings, the inset's
                            // choice and the pixels drawn otherwise (no rgb)
  int inset_x = -1, inset_y = -1;   // the inset's top left in the PNG; -1: none
  std::vector<std::string> legend;  // the legend's rows, as the PNG gives them
};

// Loads RUN/experiment.toml, renders primitive `index` of `kind` in `view` on `platform` in this
// process (and on `against` in a child first, where given), compares it with the reference
// rasterizer and writes the PNG. Throws ra::util::UserError saying what is wrong and what is
// allowed: no run directory, unknown platform or kind, view or index out of range, a scale out of
// range, a file that cannot be written, an `against` that cannot draw.
PrimitiveImage show_primitive(const ShowRequest& request);

}  // namespace ra::triage
