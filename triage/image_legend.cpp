// The legend under a `show` picture (see the header).
#include "triage/image_legend.h"

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>

namespace ra::triage {
namespace {

constexpr int kSwatch = 14;    // side of a colour square, image pixels
constexpr int kPadding = 8;    // around the legend and between swatch and text
constexpr int kFontSize = 14;  // pixels

void fill(OIIO::ImageBuf& image, Rgb8 c, int x0, int x1, int y0, int y1) {
  const float v[3] = {c.r / 255.f, c.g / 255.f, c.b / 255.f};
  OIIO::ImageBufAlgo::fill(image, v, OIIO::ROI(x0, x1, y0, y1, 0, 1, 0, 3));
}

}  // namespace

OIIO::ImageBuf with_legend(const OIIO::ImageBuf& picture, const std::vector<LegendEntry>& entries,
                           bool* text_drawn) {
  int width = std::max(picture.spec().width, kLegendMinWidth);
  for (const LegendEntry& e : entries) {  // wide enough for the longest line (a long platform name)
    const OIIO::ROI text = OIIO::ImageBufAlgo::text_size(e.text, kFontSize, "DejaVuSans");
    if (text.defined()) width = std::max(width, kSwatch + 3 * kPadding + text.width());
  }
  const int top = picture.spec().height;
  const int height = top + 2 * kPadding + int(entries.size()) * kLegendRowHeight;
  OIIO::ImageSpec spec = picture.spec();
  spec.width = spec.full_width = width;
  spec.height = spec.full_height = height;
  OIIO::ImageBuf out(spec);
  fill(out, kUnlitColor, 0, width, 0, height);
  OIIO::ImageBufAlgo::paste(out, 0, 0, 0, 0, picture);
  fill(out, Rgb8{120, 120, 120}, 0, width, top, top + 1);  // a rule between picture and legend
  *text_drawn = true;
  const float black[3] = {0, 0, 0};
  for (std::size_t i = 0; i < entries.size(); ++i) {
    const LegendEntry& e = entries[i];
    const int y = top + kPadding + int(i) * kLegendRowHeight;  // the row's top
    const int x = kPadding;
    if (e.line) {
      fill(out, e.colour, x, x + kSwatch, y + kSwatch / 2 - 1, y + kSwatch / 2 + 1);
    } else {
      fill(out, Rgb8{60, 60, 60}, x, x + kSwatch, y, y + kSwatch);  // outline: white shows too
      fill(out, e.colour, x + 1, x + kSwatch - 1, y + 1, y + kSwatch - 1);
    }
    if (*text_drawn &&
        !OIIO::ImageBufAlgo::render_text(out, x + kSwatch + kPadding, y + kSwatch - 2, e.text,
                                         kFontSize, "DejaVuSans", black))
      *text_drawn = false;
  }
  return out;
}

}  // namespace ra::triage
