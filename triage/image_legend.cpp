// The legend under a `show` picture (see the header).
#include "triage/image_legend.h"

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>

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

std::string pixels_text(int64_t n) { return std::to_string(n) + (n == 1 ? " pixel" : " pixels"); }

std::vector<LegendEntry> picture_legend(const PixelPicture& pic, const std::string& platform,
                                        int64_t record_violating_pixels) {
  std::vector<LegendEntry> rows = {
      {kBothColor, "lit by both: " + pixels_text(pic.both)},
      {kPlatformOnlyColor, "lit by " + platform + " only, as GL allows: " +
                               pixels_text(pic.platform_only)},
      {kReferenceOnlyColor, "lit by the reference only, as GL allows: " +
                                pixels_text(pic.reference_only)}};
  if (record_violating_pixels < 0) {
    rows.push_back({kViolationColor, "forbidden or missing by GL: not judged here"});
  } else {
    // how the black pixels are found: every one ringed, the small groups ringed, or in plain sight
    const std::string marker = pic.rings.empty()    ? ""
                               : pic.large_clusters ? " (small groups ringed)"
                                                    : " (ringed)";
    rows.push_back({kViolationColor, "forbidden by GL: " + pixels_text(pic.forbidden) +
                                         (pic.forbidden ? marker : "") +
                                         ", lit where no conforming driver lights one"});
    rows.push_back({kViolationColor, "missing: " + pixels_text(pic.missing) +
                                         (pic.missing ? marker : "") +
                                         ", dark where every conforming driver lights one"});
    if (!pic.rings.empty())
      rows.push_back({kMarkerColor, "ring: around a forbidden or missing pixel, or a group of them",
                      false, true});
    if (record_violating_pixels != pic.forbidden + pic.missing)
      rows.push_back({kUnlitColor,
                      "the record's violating_pixels: " + std::to_string(record_violating_pixels) +
                          ", as the rules count (a column of two fragments: one too many)",
                      false, false, true});
  }
  rows.push_back({kIdealColor, "the ideal projection", true});
  return rows;
}

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
    if (e.no_swatch) {
    } else if (e.line) {
      fill(out, e.colour, x, x + kSwatch, y + kSwatch / 2 - 1, y + kSwatch / 2 + 1);
    } else if (e.ring) {  // a ring of radius 6 in the swatch's square
      const float v[3] = {e.colour.r / 255.f, e.colour.g / 255.f, e.colour.b / 255.f};
      const float c = (kSwatch - 1) / 2.f;
      for (int i = 0; i < kSwatch; ++i)
        for (int j = 0; j < kSwatch; ++j) {
          const float d = std::hypot(float(j) - c, float(i) - c) - 5.5f;
          if (d >= -1.f && d <= 1.f) out.setpixel(x + j, y + i, v, 3);
        }
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
