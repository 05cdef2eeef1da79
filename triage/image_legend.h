// The legend `show` draws under a primitive's picture: each colour with what it means and how many
// window pixels have it, and the line of the ideal projection, so that the PNG explains itself
// away from the terminal. Text in DejaVu Sans (Debian's fonts-dejavu-core) through OpenImageIO;
// image pixels, origin at the top left.
#pragma once

#include <OpenImageIO/imagebuf.h>

#include <string>
#include <vector>

#include "triage/primitive_image.h"

namespace ra::triage {

struct LegendEntry {
  Rgb8 colour;
  std::string text;   // e.g. "lit by both: 212 pixels"
  bool line = false;  // drawn as a line (the ideal projection), not a square
  bool ring = false;  // drawn as a small ring (the marker around forbidden and missing pixels)
  bool no_swatch = false;  // text only (a note on a count)
};

constexpr int kLegendRowHeight = 22;  // image pixels per entry
constexpr int kLegendMinWidth = 360;  // a picture narrower than this (or than the legend's
                                      // longest line) is widened, white on the right

// The rows of the legend under a `show` picture of `platform`: one count per colour, each with what
// it means ("forbidden by GL: 1 pixel (ringed), lit where no conforming driver lights one"),
// the rings when drawn, the record's violating_pixels when the rules counted other than the
// pixels marked, and the ideal projection. `record_violating_pixels` < 0: not judged (the
// reference platform), one row says so instead of the forbidden and missing counts.
std::vector<LegendEntry> picture_legend(const PixelPicture& picture, const std::string& platform,
                                        int64_t record_violating_pixels);
// "1 pixel", "2 pixels".
std::string pixels_text(int64_t n);

// `picture` at the top left of a white image with the legend's rows under it. `text_drawn` is set
// false when the font could not be loaded (the swatches are drawn; the caller says so).
OIIO::ImageBuf with_legend(const OIIO::ImageBuf& picture, const std::vector<LegendEntry>& entries,
                           bool* text_drawn);

}  // namespace ra::triage
