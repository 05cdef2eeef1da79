// The legend `show` draws under a primitive's picture: each colour with what it means and how many
// window pixels have it, the rings, the ideal projection and the inset, so that the PNG explains
// itself away from the terminal. Text in DejaVu Sans (Debian's fonts-dejavu-core) through
// OpenImageIO; image pixels, origin at the top left.
//
// The PNG: the picture at the top left; under it (on its right, for a picture taller than wide)
// the inset, framed, where there is one, and the legend's rows beside that. The text is sized to
// the PNG (about 1/32 of the picture's longer side, or of twice the inset's width, 14 px at
// least), so that it reads at the size the PNG is set on a page (900 px set 3 inches wide: 7 pt),
// and a row too long for its column wraps.
#pragma once

#include <OpenImageIO/imagebuf.h>

#include <string>
#include <vector>

#include "triage/pixel_picture.h"

namespace ra::triage {

// How a legend row shows what it names.
enum class Swatch {
  kSquare,  // a filled square of the colour
  kHatch,   // a square hatched as a missing pixel is
  kLine,    // a line (the ideal projection)
  kRing,    // a small ring (the marker around forbidden and missing pixels)
  kFrame,   // a hollow square in kFrameColor (the inset's frame)
  kDot,     // a dot of the colour on a white square (the pixels drawn otherwise, in the inset)
  kNone,    // text only (a note on a count)
};

struct LegendEntry {
  Rgb8 colour;
  std::string text;  // e.g. "lit by both: 212 pixels"
  Swatch swatch = Swatch::kSquare;
};

constexpr int kLegendMinWidth = 360;  // a picture narrower than this (or than the legend) is
                                      // widened, white on the right

// The text size of the legend under a picture `picture_width` image pixels wide, pixels.
int legend_font_size(int picture_width);

// The rows of the legend under a `show` picture of `platform`: one count per colour, each with what
// it means ("forbidden by GL: 1 pixel (ringed), lit where no conforming driver lights one"),
// the rings when drawn, the record's violating_pixels when the rules counted other than the
// pixels marked, the ideal projection, and where the picture has them the inset ("framed: window
// pixels x 430-461, y 470-501, enlarged 10 times at the left") and the pixels `other` draws
// otherwise. `record_violating_pixels` < 0: not judged (the reference platform), one row says so
// instead of the forbidden and missing counts.
std::vector<LegendEntry> picture_legend(const ComposedPicture& picture, const std::string& platform,
                                        const std::string& other, int64_t record_violating_pixels);
// "1 pixel", "2 pixels".
std::string pixels_text(int64_t n);

// The picture's PNG (see the header comment): `picture` (width x height, rgb rows from the top) at
// the top left, `inset` framed under or beside it where its rgb is not empty, the legend's rows.
// `text_drawn`
// is set false when the font could not be loaded (the swatches are drawn; the caller says so).
// `inset_at` receives the inset's top left in the PNG ({-1, -1} where none).
OIIO::ImageBuf with_legend(const PixelPicture& picture, const PixelPicture& inset,
                           const std::vector<LegendEntry>& entries, bool* text_drawn,
                           std::pair<int, int>* inset_at = nullptr);

}  // namespace ra::triage
