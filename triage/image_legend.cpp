// The legend under a `show` picture (see the header).
#include "triage/image_legend.h"

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ra::triage {
namespace {

constexpr const char* kFont = "DejaVuSans";

void fill(OIIO::ImageBuf& image, Rgb8 c, int x0, int x1, int y0, int y1) {
  const float v[3] = {c.r / 255.f, c.g / 255.f, c.b / 255.f};
  OIIO::ImageBufAlgo::fill(image, v, OIIO::ROI(x0, x1, y0, y1, 0, 1, 0, 3));
}

// An outline `width` pixels wide just inside [x0, x1) x [y0, y1).
void outline(OIIO::ImageBuf& image, Rgb8 c, int x0, int x1, int y0, int y1, int width) {
  fill(image, c, x0, x1, y0, y0 + width);
  fill(image, c, x0, x1, y1 - width, y1);
  fill(image, c, x0, x0 + width, y0, y1);
  fill(image, c, x1 - width, x1, y0, y1);
}

OIIO::ImageBuf image_of(const PixelPicture& p) {
  OIIO::ImageSpec spec(p.width, p.height, 3, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf buf(spec);
  buf.set_pixels(OIIO::ROI(0, p.width, 0, p.height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8,
                 p.rgb.data());
  return buf;
}

int text_width(const std::string& text, int size) {
  const OIIO::ROI r = OIIO::ImageBufAlgo::text_size(text, size, kFont);
  return r.defined() ? r.width() : int(text.size()) * size * 6 / 10;
}

// `text` in lines no wider than `width` pixels, broken between words.
std::vector<std::string> wrap(const std::string& text, int size, int width) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    const std::string longer = line.empty() ? word : line + " " + word;
    if (!line.empty() && text_width(longer, size) > width) {
      lines.push_back(line);
      line = word;
    } else {
      line = longer;
    }
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

// The swatch of `e` in the square of side `side` at (x, y).
void draw_swatch(OIIO::ImageBuf& out, const LegendEntry& e, int x, int y, int side) {
  const int w = std::max(1, side / 8);  // lines of the line, ring and frame swatches
  switch (e.swatch) {
    case Swatch::kNone:
      break;
    case Swatch::kLine:
      fill(out, e.colour, x, x + side, y + side / 2 - w / 2, y + side / 2 - w / 2 + w);
      break;
    case Swatch::kRing: {
      const float v[3] = {e.colour.r / 255.f, e.colour.g / 255.f, e.colour.b / 255.f};
      const float c = (side - 1) / 2.f, r = side / 2.f - w;
      for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
          if (std::fabs(std::hypot(float(j) - c, float(i) - c) - r) <= w / 2.f + 0.5f)
            out.setpixel(x + j, y + i, v, 3);
      break;
    }
    case Swatch::kFrame:
      outline(out, e.colour, x, x + side, y, y + side, std::max(2, w));
      break;
    case Swatch::kDot: {
      outline(out, Rgb8{60, 60, 60}, x, x + side, y, y + side, 1);
      const float v[3] = {e.colour.r / 255.f, e.colour.g / 255.f, e.colour.b / 255.f};
      const float c = (side - 1) / 2.f;
      for (int i = 0; i < side; ++i)
        for (int j = 0; j < side; ++j)
          if (std::hypot(float(j) - c, float(i) - c) <= side / 6.f + 0.5f)
            out.setpixel(x + j, y + i, v, 3);
      break;
    }
    case Swatch::kHatch:
    case Swatch::kSquare: {
      fill(out, Rgb8{60, 60, 60}, x, x + side, y, y + side);  // outline: white shows too
      fill(out, e.colour, x + 1, x + side - 1, y + 1, y + side - 1);
      if (e.swatch == Swatch::kHatch)  // the hatching of a missing pixel's block at this size
        for (int i = 1; i < side - 1; ++i)
          for (int j = 1; j < side - 1; ++j)
            if (!missing_hatch(j, i, side))
              fill(out, kUnlitColor, x + j, x + j + 1, y + i, y + i + 1);
      break;
    }
  }
}

}  // namespace

int legend_font_size(int picture_width) {
  return std::clamp(int(std::lround(picture_width / 32.0)), 14, 40);
}

std::string pixels_text(int64_t n) { return std::to_string(n) + (n == 1 ? " pixel" : " pixels"); }

std::vector<LegendEntry> picture_legend(const ComposedPicture& c, const std::string& platform,
                                        const std::string& other, int64_t record_violating_pixels) {
  const PixelPicture& pic = c.main;
  std::vector<LegendEntry> rows = {
      {kBothColor, "lit by both: " + pixels_text(pic.both)},
      {kPlatformOnlyColor,
       "lit by " + platform + " only, as GL allows: " + pixels_text(pic.platform_only)},
      {kReferenceOnlyColor,
       "lit by the reference only, as GL allows: " + pixels_text(pic.reference_only)}};
  if (record_violating_pixels < 0) {
    rows.push_back({kForbiddenColor, "forbidden or missing by GL: not judged here"});
  } else {
    // how they are found: every one ringed, the small groups ringed, or in plain sight
    const std::string marker = pic.rings.empty()    ? ""
                               : pic.large_clusters ? " (small groups ringed)"
                                                    : " (ringed)";
    rows.push_back({kForbiddenColor, "forbidden by GL: " + pixels_text(pic.forbidden) +
                                         (pic.forbidden ? marker : "") +
                                         ", lit where no conforming driver lights one"});
    rows.push_back({kMissingColor,
                    "missing: " + pixels_text(pic.missing) + (pic.missing ? marker : "") +
                        ", dark where every conforming driver lights one",
                    Swatch::kHatch});
    if (!pic.rings.empty())
      rows.push_back({kMarkerColor, "ring: around forbidden or missing pixels", Swatch::kRing});
    if (record_violating_pixels != pic.forbidden + pic.missing)
      rows.push_back({kUnlitColor,
                      "the record's violating_pixels: " + std::to_string(record_violating_pixels) +
                          ", as GL's rules count them (a column of two fragments: one too many)",
                      Swatch::kNone});
  }
  rows.push_back({kIdealColor, "the ideal projection", Swatch::kLine});
  const InsetChoice& in = c.inset_choice;
  if (!in.window.empty())
    rows.push_back({kFrameColor,
                    "framed: window pixels x " + std::to_string(in.window.x0) + "-" +
                        std::to_string(in.window.x1 - 1) + ", y " + std::to_string(in.window.y0) +
                        "-" + std::to_string(in.window.y1 - 1) + ", enlarged " +
                        std::to_string(in.scale) + " times at the left",
                    Swatch::kFrame});
  if (c.drawn_otherwise >= 0)
    rows.push_back({kMarkerColor,
                    "drawn otherwise by " + other + ": " + pixels_text(c.drawn_otherwise) +
                        (!c.dotted            ? ""
                         : !in.window.empty() ? " (dotted in the inset)"
                                              : " (dotted)"),
                    c.dotted ? Swatch::kDot : Swatch::kNone});
  return rows;
}

OIIO::ImageBuf with_legend(const PixelPicture& picture, const PixelPicture& inset,
                           const std::vector<LegendEntry>& entries, bool* text_drawn,
                           std::pair<int, int>* inset_at) {
  const bool has_inset = !inset.rgb.empty();
  // a picture taller than wide (a steep line) has the inset and the rows on its right, else under
  const bool beside = picture.height > picture.width;
  // the text sized to what the PNG will be: the picture, or the inset and a column beside it
  const int base =
      std::max({picture.width, picture.height, kLegendMinWidth, has_inset ? 2 * inset.width : 0});
  const int size = legend_font_size(base);
  const int pad = size / 2 + 2, line_h = size * 5 / 4, swatch = size;
  const int frame = has_inset ? std::max(2, size / 6) : 0;
  // where the inset and the rows begin: under the picture or beside it, past a 1-px rule
  const int bx = beside ? picture.width + 1 : 0, by = beside ? 0 : picture.height + 1;
  // the inset framed on the left, the rows beside it in a column of at least 16 em
  const int left = bx + (has_inset ? pad + inset.width + 2 * frame + pad : 0);
  const int column = std::max(beside ? 0 : base - left - pad, 16 * size);
  const int text_x = left + pad + swatch + pad;
  std::vector<std::vector<std::string>> lines;
  int rows_h = 0, text_w = 0;
  for (const LegendEntry& e : entries) {
    lines.push_back(wrap(e.text, size, column - swatch - pad));
    rows_h += int(lines.back().size()) * line_h + size / 3;
    for (const std::string& l : lines.back()) text_w = std::max(text_w, text_width(l, size));
  }
  const int band = std::max(has_inset ? inset.height + 2 * frame + 2 * pad : 0, rows_h + 2 * pad);
  const int width = std::max({beside ? 0 : base, kLegendMinWidth, text_x + text_w + pad});
  const int height = beside ? std::max(picture.height, band) : by + band;
  OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
  OIIO::ImageBuf out(spec);
  fill(out, kUnlitColor, 0, width, 0, height);
  OIIO::ImageBufAlgo::paste(out, 0, 0, 0, 0, image_of(picture));
  // a rule between picture and legend
  if (beside)
    fill(out, Rgb8{120, 120, 120}, bx - 1, bx, 0, height);
  else
    fill(out, Rgb8{120, 120, 120}, 0, width, by - 1, by);
  if (inset_at) *inset_at = {-1, -1};
  if (has_inset) {
    const int x = bx + pad + frame, y = by + pad + frame;
    OIIO::ImageBufAlgo::paste(out, x, y, 0, 0, image_of(inset));
    outline(out, kFrameColor, x - frame, x + inset.width + frame, y - frame,
            y + inset.height + frame, frame);
    if (inset_at) *inset_at = {x, y};
  }
  *text_drawn = true;
  const float black[3] = {0, 0, 0};
  int y = by + pad;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    draw_swatch(out, entries[i], left + pad, y + (line_h - swatch) / 2, swatch);
    for (const std::string& l : lines[i]) {
      if (*text_drawn &&
          !OIIO::ImageBufAlgo::render_text(out, text_x, y + size, l, size, kFont, black))
        *text_drawn = false;
      y += line_h;
    }
    y += size / 3;
  }
  return out;
}

}  // namespace ra::triage
