// The legend under a `show` picture: one count per colour with what it means, swatches that tell
// forbidden from missing, text that reads at page size, the inset beside it.
#include "triage/image_legend.h"

#include <gtest/gtest.h>

#include <array>

namespace ra::triage {
namespace {

// A 40 x 40 block lit by both, and one pixel at (50, 20) lit by the platform alone where GL
// forbids it, shown in window pixels 0-79 x 0-49.
ComposedPicture one_forbidden(int scale) {
  PictureLayers l;
  for (int y = 0; y < 40; ++y) l.lit.append_run(y, 0, 40), l.reference.append_run(y, 0, 40);
  l.lit.insert({50, 20});
  l.violating.insert({50, 20});
  l.window_width = 80, l.window_height = 50;
  return compose_picture(l, {0, 0, 80, 50}, scale);
}

std::vector<std::string> texts(const std::vector<LegendEntry>& rows) {
  std::vector<std::string> out;
  for (const LegendEntry& e : rows) out.push_back(e.text);
  return out;
}

// Pixels of colour `c` in the rectangle [x0, x1) x [y0, y1) of `image`.
int64_t pixels_with(const OIIO::ImageBuf& image, Rgb8 c, std::array<int, 4> r) {
  int64_t n = 0;
  const OIIO::ImageSpec& s = image.spec();
  std::vector<uint8_t> rgb(std::size_t(s.width) * s.height * 3);
  image.get_pixels(OIIO::ROI(0, s.width, 0, s.height, 0, 1, 0, 3), OIIO::TypeDesc::UINT8,
                   rgb.data());
  for (int y = std::max(0, r[1]); y < std::min(s.height, r[3]); ++y)
    for (int x = std::max(0, r[0]); x < std::min(s.width, r[2]); ++x) {
      const uint8_t* p = &rgb[(std::size_t(y) * s.width + x) * 3];
      n += Rgb8{p[0], p[1], p[2]} == c;
    }
  return n;
}
// ... under the picture's `top` rows.
int64_t pixels_with(const OIIO::ImageBuf& image, Rgb8 c, int top) {
  return pixels_with(image, c, {0, top, image.spec().width, image.spec().height});
}

TEST(PictureLegend, GivesOneCountPerColourWithWhatItMeans) {
  const ComposedPicture pic = one_forbidden(8);  // at 8 px a pixel is seen: no inset
  const std::vector<LegendEntry> rows = picture_legend(pic, "osmesa-llvmpipe", "", 1);
  EXPECT_EQ(texts(rows),
            (std::vector<std::string>{
                "lit by both: 1600 pixels", "lit by osmesa-llvmpipe only, as GL allows: 0 pixels",
                "lit by the reference only, as GL allows: 0 pixels",
                "forbidden by GL: 1 pixel (ringed), lit where no conforming driver "
                "lights one",
                "missing: 0 pixels, dark where every conforming driver lights one",
                "ring: around forbidden or missing pixels", "the ideal projection"}));
  // forbidden and missing told apart: colour and swatch
  EXPECT_EQ(rows[3].colour, kForbiddenColor);
  EXPECT_EQ(rows[3].swatch, Swatch::kSquare);
  EXPECT_EQ(rows[4].colour, kMissingColor);
  EXPECT_EQ(rows[4].swatch, Swatch::kHatch);
  EXPECT_EQ(rows[5].swatch, Swatch::kRing);
  EXPECT_EQ(rows[5].colour, kMarkerColor);
  // the record's own count, when its rules counted otherwise, in a row of its own
  const std::vector<LegendEntry> column = picture_legend(pic, "p", "", 2);
  ASSERT_EQ(column.size(), rows.size() + 1);
  EXPECT_EQ(column[6].text.rfind("the record's violating_pixels: 2, as GL's rules count them", 0),
            0u)
      << column[6].text;
  // not judged (the reference platform): one row says so
  const std::vector<LegendEntry> reference = picture_legend(pic, "reference", "", -1);
  ASSERT_EQ(reference.size(), 5u);
  EXPECT_EQ(reference[3].text, "forbidden or missing by GL: not judged here");
}

// The inset and the pixels another platform draws otherwise each get their row.
TEST(PictureLegend, NamesTheInsetAndThePixelsDrawnOtherwise) {
  ComposedPicture pic = one_forbidden(1);  // at 1 px: an inset around the forbidden pixel
  const InsetChoice& in = pic.inset_choice;
  ASSERT_FALSE(in.window.empty());
  pic.drawn_otherwise = 3;
  pic.dotted = true;
  const std::vector<LegendEntry> rows = picture_legend(pic, "p", "p@backports", 1);
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows[rows.size() - 2].text, "framed: window pixels x " + std::to_string(in.window.x0) +
                                            "-" + std::to_string(in.window.x1 - 1) + ", y " +
                                            std::to_string(in.window.y0) + "-" +
                                            std::to_string(in.window.y1 - 1) + ", enlarged " +
                                            std::to_string(in.scale) + " times at the left");
  EXPECT_EQ(rows[rows.size() - 2].swatch, Swatch::kFrame);
  EXPECT_EQ(rows.back().text, "drawn otherwise by p@backports: 3 pixels (dotted in the inset)");
  EXPECT_EQ(rows.back().swatch, Swatch::kDot);
  // too many to dot (a change seen without them): said, not dotted
  pic.drawn_otherwise = 20233;
  pic.dotted = false;
  const LegendEntry many = picture_legend(pic, "p", "p@backports", 1).back();
  EXPECT_EQ(many.text, "drawn otherwise by p@backports: 20233 pixels");
  EXPECT_EQ(many.swatch, Swatch::kNone);
}

// Why: the legend was 14 px text under pictures of 900 px, about 3 pt once the picture was set on
// a page, and the forbidden and missing swatches were the same black. Now the text grows with the
// picture, long rows wrap within the PNG, the inset sits beside the rows, and the missing swatch
// is hatched green.
TEST(PictureLegend, ReadsAtPageSizeWithTheInsetBesideIt) {
  EXPECT_EQ(legend_font_size(512), 16);
  EXPECT_EQ(legend_font_size(900), 28);
  EXPECT_EQ(legend_font_size(100), 14);
  PixelPicture wide;  // a long line's strip
  wide.width = 900, wide.height = 60;
  wide.rgb.assign(std::size_t(wide.width) * wide.height * 3, 255);
  PixelPicture inset;
  inset.width = 384, inset.height = 144;
  inset.rgb.assign(std::size_t(inset.width) * inset.height * 3, 150);  // grey
  std::vector<LegendEntry> rows =
      picture_legend(one_forbidden(8), "osmesa-llvmpipe@backports", "", 1);
  bool text = false;
  std::pair<int, int> at;
  const OIIO::ImageBuf png = with_legend(wide, inset, rows, &text, &at);
  EXPECT_TRUE(text) << "DejaVu Sans (fonts-dejavu-core) is needed for the legend's text";
  // about as wide as the picture: the rows wrapped into a column beside the inset (one row of
  // 80 characters unwrapped would be 1,300 px at this size)
  EXPECT_LE(png.spec().width, 900 * 9 / 8);
  EXPECT_GT(at.first, 0);
  EXPECT_EQ(at.second > wide.height, true);  // under the picture
  EXPECT_GE(png.spec().height, wide.height + inset.height);
  // the inset pasted whole, its frame around it
  EXPECT_EQ(pixels_with(png, kBothColor, {at.first, at.second, at.first + 384, at.second + 144}),
            int64_t(384) * 144);
  EXPECT_GT(pixels_with(png, kFrameColor, wide.height), 2 * (384 + 144));
  // the hatched swatch: the only green in the legend, about half of its 26 x 26
  EXPECT_NEAR(double(pixels_with(png, kMissingColor, wide.height)), 26 * 26 / 2.0, 26);
}

// A picture taller than wide (a steep line's strip) has the inset and the rows on its right, so
// that the PNG is not twice as tall as wide and shrunk to fit a page's height.
TEST(PictureLegend, ATallPictureHasItsLegendBeside) {
  PixelPicture tall;
  tall.width = 156, tall.height = 550;
  tall.rgb.assign(std::size_t(tall.width) * tall.height * 3, 255);
  PixelPicture inset;
  inset.width = 312, inset.height = 416;
  inset.rgb.assign(std::size_t(inset.width) * inset.height * 3, 150);
  const std::vector<LegendEntry> rows = picture_legend(one_forbidden(8), "p", "", 1);
  bool text = false;
  std::pair<int, int> at;
  const OIIO::ImageBuf png = with_legend(tall, inset, rows, &text, &at);
  EXPECT_GT(at.first, tall.width);  // beside the picture
  EXPECT_LT(at.second, 40);         // at its top
  EXPECT_LT(png.spec().height, tall.height * 5 / 4);
  EXPECT_LT(png.spec().height, png.spec().width);
}

}  // namespace
}  // namespace ra::triage
