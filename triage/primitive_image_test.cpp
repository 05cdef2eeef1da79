// `renderaudit show`'s picture: the forbidden and missing pixels ringed, the legend's counts.
#include "triage/primitive_image.h"

#include <gtest/gtest.h>

#include "triage/image_legend.h"

namespace ra::triage {
namespace {

// A 40 x 40 block lit by both, and one pixel at (50, 20) lit by the platform alone where GL
// forbids it, shown in window pixels 0-79 x 0-49.
struct OneForbidden {
  geometry::PixelSet lit, reference, violating;
  const geometry::PixelRect shown{0, 0, 80, 50};
  OneForbidden() {
    for (int y = 0; y < 40; ++y)
      for (int x = 0; x < 40; ++x) lit.insert({x, y}), reference.insert({x, y});
    lit.insert({50, 20});
    violating.insert({50, 20});
  }
};

Rgb8 at(const PixelPicture& pic, int x, int y) {
  const uint8_t* p = &pic.rgb[(std::size_t(y) * pic.width + x) * 3];
  return {p[0], p[1], p[2]};
}

// Why: triangle 782 lights 42,843 pixels; its one forbidden pixel was a 2 x 2 black dot with no
// marker, lost at page size. A ring of kMarkerColor around it finds it.
TEST(PixelPicture, RingsTheOneForbiddenPixelAmongManyLit) {
  const OneForbidden in;
  for (const int scale : {1, 2, 8}) {
    const PixelPicture pic = draw_pixel_picture(in.lit, in.reference, in.violating, in.shown, scale);
    ASSERT_EQ(pic.width, 80 * scale);
    ASSERT_EQ(pic.height, 50 * scale);
    EXPECT_EQ(pic.both, 1600);
    EXPECT_EQ(pic.forbidden, 1);
    EXPECT_EQ(pic.missing, 0);
    EXPECT_EQ(pic.platform_only, 0);  // the one platform-only pixel is the forbidden one
    ASSERT_EQ(pic.rings.size(), 1u) << "scale " << scale;
    const MarkerRing& r = pic.rings[0];
    // centred on the pixel's block (window row 20 is image row (49 - 20) * scale from the top)
    EXPECT_EQ(r.cx, 50 * scale + scale / 2);
    EXPECT_EQ(r.cy, 29 * scale + scale / 2);
    EXPECT_EQ(at(pic, r.cx, r.cy), kViolationColor);
    EXPECT_GE(r.radius, kMarkerMinRadius);
    EXPECT_GT(r.radius, scale);  // around the block, not on it
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}})
      EXPECT_EQ(at(pic, r.cx + dx * r.radius, r.cy + dy * r.radius), kMarkerColor)
          << "scale " << scale << " direction " << dx << "," << dy;
    // a white halo just outside the ring, so it reads on grey, orange or blue blocks
    EXPECT_EQ(at(pic, r.cx + r.radius + r.half_width + 1, r.cy), kUnlitColor);
    // and the lit block far from it carries no ring
    EXPECT_EQ(at(pic, 10 * scale + scale / 2, 30 * scale + scale / 2), kBothColor);
  }
}

TEST(PixelPicture, NearbyPixelsShareARingAndALargeBlackAreaNeedsNone) {
  geometry::PixelSet lit, reference, violating;
  // a block of 60 x 40 missing pixels along the bottom, three forbidden ones near the top
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 60; ++x) reference.insert({x, y}), violating.insert({x, y});
  for (const geometry::Pixel p : {geometry::Pixel{40, 95}, {41, 96}, {43, 95}}) {
    lit.insert(p);
    violating.insert(p);
  }
  const PixelPicture pic = draw_pixel_picture(lit, reference, violating, {0, 0, 80, 100}, 1);
  EXPECT_EQ(pic.forbidden, 3);
  EXPECT_EQ(pic.missing, 2400);
  EXPECT_EQ(pic.rings.size(), 1u);  // the three forbidden pixels, together
  EXPECT_EQ(pic.large_clusters, 1);  // the block of 2400, seen as it is
  // a crack one pixel wide is ringed however long (softpipe's 79-pixel diagonal)
  geometry::PixelSet crack;
  for (int i = 0; i < 79; ++i) crack.insert({i, i});
  const PixelPicture cracked = draw_pixel_picture({}, crack, crack, {0, 0, 100, 100}, 1);
  EXPECT_EQ(cracked.missing, 79);
  EXPECT_EQ(cracked.rings.size(), 1u);
  EXPECT_EQ(cracked.large_clusters, 0);
}

TEST(PictureLegend, GivesOneCountPerColourWithWhatItMeans) {
  const OneForbidden in;
  const PixelPicture pic = draw_pixel_picture(in.lit, in.reference, in.violating, in.shown, 1);
  const std::vector<LegendEntry> rows = picture_legend(pic, "osmesa-llvmpipe", 1);
  std::vector<std::string> text;
  for (const LegendEntry& e : rows) text.push_back(e.text);
  EXPECT_EQ(text, (std::vector<std::string>{
                      "lit by both: 1600 pixels",
                      "lit by osmesa-llvmpipe only, as GL allows: 0 pixels",
                      "lit by the reference only, as GL allows: 0 pixels",
                      "forbidden by GL: 1 pixel (ringed), lit where no conforming driver lights one",
                      "missing: 0 pixels, dark where every conforming driver lights one",
                      "ring: around a forbidden or missing pixel, or a group of them",
                      "the ideal projection"}));
  EXPECT_EQ(rows[3].colour, kViolationColor);
  EXPECT_TRUE(rows[5].ring);
  EXPECT_EQ(rows[5].colour, kMarkerColor);
  // the record's own count, when its rules counted otherwise, in a row of its own
  const std::vector<LegendEntry> column = picture_legend(pic, "p", 2);
  ASSERT_EQ(column.size(), rows.size() + 1);
  EXPECT_EQ(column[6].text.rfind("the record's violating_pixels: 2, as the rules count", 0), 0u)
      << column[6].text;
  // not judged (the reference platform): one row says so
  const std::vector<LegendEntry> reference = picture_legend(pic, "reference", -1);
  ASSERT_EQ(reference.size(), 5u);
  EXPECT_EQ(reference[3].text, "forbidden or missing by GL: not judged here");
}

}  // namespace
}  // namespace ra::triage
