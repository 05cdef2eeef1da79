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
  std::string text;   // e.g. "lit by both (212)"
  bool line = false;  // drawn as a line (the ideal projection), not a square
};

constexpr int kLegendRowHeight = 22;  // image pixels per entry
constexpr int kLegendMinWidth = 360;  // a picture narrower than this (or than the legend's
                                      // longest line) is widened, white on the right

// `picture` at the top left of a white image with the legend's rows under it. `text_drawn` is set
// false when the font could not be loaded (the swatches are drawn; the caller says so).
OIIO::ImageBuf with_legend(const OIIO::ImageBuf& picture, const std::vector<LegendEntry>& entries,
                           bool* text_drawn);

}  // namespace ra::triage
