// The picture of one primitive's window pixels (`renderaudit show`, the upgrade report): the
// forbidden and missing pixels told apart and ringed where the ring can be seen, a line not drawn
// unlike the same line drawn at page size, and the inset of a small difference.
#include "triage/pixel_picture.h"

#include <gtest/gtest.h>

#include <cmath>

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

int64_t pixels_with(const PixelPicture& pic, Rgb8 c) {
  int64_t n = 0;
  for (int y = 0; y < pic.height; ++y)
    for (int x = 0; x < pic.width; ++x) n += at(pic, x, y) == c;
  return n;
}

// Luma (ITU-R BT.601), 0-255.
double grey(Rgb8 c) { return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b; }

// The picture at half size: each 2 x 2 square of pixels averaged (as a page at half the
// resolution shows it).
PixelPicture half(const PixelPicture& pic) {
  PixelPicture h;
  h.width = pic.width / 2, h.height = pic.height / 2;
  h.rgb.resize(std::size_t(h.width) * h.height * 3);
  for (int y = 0; y < h.height; ++y)
    for (int x = 0; x < h.width; ++x)
      for (int k = 0; k < 3; ++k) {
        int sum = 0;
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx)
            sum += pic.rgb[(std::size_t(2 * y + dy) * pic.width + 2 * x + dx) * 3 + k];
        h.rgb[(std::size_t(y) * h.width + x) * 3 + k] = uint8_t((sum + 2) / 4);
      }
  return h;
}

// Pixels of two pictures of one size whose grey levels differ by more than 40 of 255: what a
// reader sees as different.
int64_t visibly_different(const PixelPicture& a, const PixelPicture& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  int64_t n = 0;
  for (int y = 0; y < std::min(a.height, b.height); ++y)
    for (int x = 0; x < std::min(a.width, b.width); ++x)
      n += std::fabs(grey(at(a, x, y)) - grey(at(b, x, y))) > 40;
  return n;
}

// Why: triangle 782 lights 42,843 pixels; its one forbidden pixel was a 2 x 2 black dot with no
// marker, lost at page size. A ring of kMarkerColor around it finds it.
TEST(PixelPicture, RingsTheOneForbiddenPixelAmongManyLit) {
  const OneForbidden in;
  for (const int scale : {1, 2, 8}) {
    const PixelPicture pic =
        draw_pixel_picture(in.lit, in.reference, in.violating, in.shown, scale);
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
    ASSERT_EQ(r.hull.size(), 1u);  // one pixel: a circle
    EXPECT_EQ(at(pic, r.cx, r.cy), kForbiddenColor);
    EXPECT_GE(r.radius, kMarkerMinRadius);
    EXPECT_GT(r.radius, scale);  // around the block, not on it
    // the ring, within its width of the radius (it leaves the centre of each block it crosses)
    for (const auto& [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      int ring = 0;
      for (int k = -r.half_width; k <= r.half_width; ++k)
        ring += at(pic, r.cx + dx * (r.radius + k), r.cy + dy * (r.radius + k)) == kMarkerColor;
      EXPECT_GE(ring, r.half_width * 2) << "scale " << scale << " direction " << dx << "," << dy;
    }
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
  EXPECT_EQ(pic.rings.size(), 1u);   // the three forbidden pixels, together
  EXPECT_EQ(pic.large_clusters, 1);  // the block of 2400, seen as it is
  // a crack one pixel wide is ringed however long (softpipe's 79-pixel diagonal)
  geometry::PixelSet crack;
  for (int i = 0; i < 79; ++i) crack.insert({i, i});
  const PixelPicture cracked = draw_pixel_picture({}, crack, crack, {0, 0, 100, 100}, 1);
  EXPECT_EQ(cracked.missing, 79);
  EXPECT_EQ(cracked.rings.size(), 1u);
  EXPECT_EQ(cracked.large_clusters, 0);
}

// Why: forbidden and missing pixels were the same black, so a line not drawn (its pixels
// "missing") looked like ink. Forbidden is solid black; missing is hatched green on white, a hole.
TEST(PixelPicture, ForbiddenIsInkAndMissingIsAHole) {
  geometry::PixelSet lit, reference, violating;
  lit.insert({2, 2}), violating.insert({2, 2});        // forbidden
  reference.insert({5, 2}), violating.insert({5, 2});  // missing
  const PixelPicture pic = draw_pixel_picture(lit, reference, violating, {0, 0, 8, 5}, 16);
  EXPECT_EQ(pic.forbidden, 1);
  EXPECT_EQ(pic.missing, 1);
  // the blocks' insides (the 15 x 15 within the grid line), window row 2 = image rows 32-47
  int black[2] = {0, 0}, green[2] = {0, 0}, white[2] = {0, 0};
  for (int b = 0; b < 2; ++b)
    for (int y = 33; y < 48; ++y)
      for (int x = 1; x < 16; ++x) {
        const Rgb8 c = at(pic, (b == 0 ? 2 : 5) * 16 + x, y);
        black[b] += c == kForbiddenColor, green[b] += c == kMissingColor,
            white[b] += c == kUnlitColor;
      }
  EXPECT_EQ(black[0], 15 * 15) << "the forbidden block is solid black";
  EXPECT_EQ(green[0] + white[0], 0);
  EXPECT_EQ(black[1], 0) << "the missing block has no black";
  // stripes a quarter of a block wide: half of it green, half white
  EXPECT_NEAR(green[1], 15 * 15 / 2, 15);
  EXPECT_EQ(green[1] + white[1], 15 * 15);
  EXPECT_GT(std::fabs(grey(kMissingColor) - grey(kForbiddenColor)), 40);
  EXPECT_GT(std::fabs(grey(kMissingColor) - grey(kBothColor)), 40);
}

// A line of window pixels, one per column (x-major): from (5, 20) to (404, 59), 400 pixels, and
// its ideal segment through the end pixels' centres.
geometry::PixelSet a_line() {
  geometry::PixelSet s;
  for (int x = 5; x <= 404; ++x) s.insert({x, int(std::lround(20 + (x - 5) * 39.0 / 399.0))});
  return s;
}

PictureLayers line_layers(bool drawn) {
  PictureLayers l;
  l.reference = a_line();
  if (drawn)
    l.lit = l.reference;
  else
    l.violating = l.reference;  // every pixel of it missing
  l.ideal = {{5.5, 20.5}, {404.5, 59.5}};
  l.window_width = 420, l.window_height = 80;
  return l;
}

// Why: on the upgrade report's page 2 a line drawn and the same line not drawn at all looked the
// same (a thin red line on white): of 185,935 pixels, 169 differed by more than 40 grey levels, 16
// at half size. Now the missing pixels are a hatched hole, ringed by a capsule that lies on the
// picture, and a reader tells the two apart at full and at half size.
TEST(PixelPicture, ALineNotDrawnLooksUnlikeTheLineDrawn) {
  const geometry::PixelRect shown{0, 0, 420, 80};
  const ComposedPicture drawn = compose_picture(line_layers(true), shown, 1);
  const ComposedPicture missing = compose_picture(line_layers(false), shown, 1);
  EXPECT_EQ(missing.main.missing, 400);
  ASSERT_EQ(missing.main.rings.size(), 1u);
  // a capsule along the line, not a circle: its hull spans the line
  int hull_x0 = 1 << 20, hull_x1 = -1;
  for (const auto& [x, y] : missing.main.rings[0].hull)
    hull_x0 = std::min(hull_x0, x), hull_x1 = std::max(hull_x1, x);
  EXPECT_EQ(hull_x0, 5);
  EXPECT_EQ(hull_x1, 404);
  // the ring lies on the picture: along both sides of the line (3 px wide), not off it
  EXPECT_GT(pixels_with(missing.main, kMarkerColor), 2 * 400 * 2);
  const int64_t full = visibly_different(drawn.main, missing.main);
  const int64_t halved = visibly_different(half(drawn.main), half(missing.main));
  EXPECT_GT(full, 2 * 400 * 2) << "pixels visibly different at full size";
  EXPECT_GT(halved, 2 * 200) << "pixels visibly different at half size";
}

// Each side drawn against the other (the upgrade report's pair): the same inset, and in it the
// line's blocks grey on one side and a hatched hole on the other, the pixels drawn otherwise
// dotted.
TEST(PixelPicture, APairDrawnAgainstEachOtherInsetsTheSamePixels) {
  const geometry::PixelRect shown{0, 0, 420, 80};
  PictureLayers installed = line_layers(true), upgraded = line_layers(false);
  installed.has_other = upgraded.has_other = true;
  installed.other = upgraded.lit;  // nothing
  upgraded.other = installed.lit;  // the line
  const ComposedPicture a = compose_picture(installed, shown, 1);
  const ComposedPicture b = compose_picture(upgraded, shown, 1);
  EXPECT_EQ(a.drawn_otherwise, 400);
  EXPECT_EQ(b.drawn_otherwise, 400);
  const InsetChoice& in = a.inset_choice;
  ASSERT_FALSE(in.window.empty());
  EXPECT_EQ(in.window.x0, b.inset_choice.window.x0);
  EXPECT_EQ(in.window.y0, b.inset_choice.window.y0);
  EXPECT_EQ(in.window.x1, b.inset_choice.window.x1);
  EXPECT_EQ(in.window.y1, b.inset_choice.window.y1);
  EXPECT_EQ(in.scale, b.inset_choice.scale);
  // at most kInsetMaxWindow wide, cut to the line's rows: a strip, enlarged to about kInsetSide
  const int w = in.window.x1 - in.window.x0, h = in.window.y1 - in.window.y0;
  EXPECT_EQ(w, kInsetMaxWindow);
  EXPECT_EQ(h, kInsetMinWindow);
  EXPECT_EQ(in.scale, (kInsetSide + w - 1) / w);
  ASSERT_EQ(a.inset.width, w * in.scale);
  ASSERT_EQ(b.inset.height, h * in.scale);
  // the line's pixels in the inset, and what a reader sees of them
  int64_t inside = 0;
  for (const geometry::Pixel& p : a_line())
    inside +=
        p.x >= in.window.x0 && p.x < in.window.x1 && p.y >= in.window.y0 && p.y < in.window.y1;
  EXPECT_GE(inside, w - 1);
  const int S = in.scale;
  EXPECT_GT(visibly_different(a.inset, b.inset), inside * (S - 1) * (S - 1) / 2);
  EXPECT_GT(pixels_with(a.inset, kMarkerColor), 0);  // the dots
  EXPECT_GT(pixels_with(b.inset, kMissingColor), inside * (S - 1) * (S - 1) / 3);
  EXPECT_EQ(pixels_with(a.inset, kMissingColor), 0);
  // the inset's place framed in both pictures
  EXPECT_GT(pixels_with(a.main, kFrameColor), 2 * (w + h));
  EXPECT_GT(pixels_with(b.main, kFrameColor), 2 * (w + h));
}

// Why: two triangles of 108,462 pixels, 4 pixels apart, looked identical at page size. The inset
// enlarges the window pixels where they differ, the same for both.
TEST(PixelPicture, ASmallDifferenceGetsAnInset) {
  PictureLayers one;
  for (int y = 20; y < 170; ++y) one.lit.append_run(y, 20, 220);
  one.reference = one.lit;
  one.window_width = 240, one.window_height = 200;
  PictureLayers two = one;
  two.lit.erase({100, 169});
  two.lit.insert({101, 170});
  one.has_other = two.has_other = true;
  one.other = two.lit, two.other = one.lit;
  const geometry::PixelRect shown{0, 0, 240, 200};
  const InsetChoice a = choose_inset(one, 1), b = choose_inset(two, 1);
  EXPECT_EQ(a.differing, 2);
  EXPECT_EQ(a.window.x0, b.window.x0);
  EXPECT_EQ(a.window.y0, b.window.y0);
  EXPECT_EQ(a.scale, b.scale);
  // the smallest inset, holding both pixels
  EXPECT_EQ(a.window.x1 - a.window.x0, kInsetMinWindow);
  EXPECT_EQ(a.window.y1 - a.window.y0, kInsetMinWindow);
  for (const geometry::Pixel p : {geometry::Pixel{100, 169}, {101, 170}})
    EXPECT_TRUE(p.x >= a.window.x0 && p.x < a.window.x1 && p.y >= a.window.y0 && p.y < a.window.y1);
  EXPECT_EQ(a.scale, (kInsetSide + kInsetMinWindow - 1) / kInsetMinWindow);
  // in the inset of `two`, pixel (100, 169) is a hole in the grey (reference only: blue), dotted
  const ComposedPicture c = compose_picture(two, shown, 1);
  const int S = a.scale;
  const int left = (100 - a.window.x0) * S, top = (a.window.y1 - 1 - 169) * S;
  EXPECT_EQ(at(c.inset, left + 2, top + 2), kReferenceOnlyColor);
  EXPECT_EQ(at(c.inset, left + S / 2, top + S / 2), kMarkerColor);
  // and the same pixel in the picture of `one` grey
  const ComposedPicture d = compose_picture(one, shown, 1);
  EXPECT_EQ(at(d.inset, left + 2, top + 2), kBothColor);
  // at a scale a pixel is seen at: no inset, the pixels drawn otherwise dotted in the picture
  const ComposedPicture e = compose_picture(two, shown, kInsetBelowScale);
  EXPECT_TRUE(e.inset.rgb.empty());
  const int T = kInsetBelowScale;
  EXPECT_EQ(at(e.main, 100 * T + T / 2, (199 - 169) * T + T / 2), kMarkerColor);
  EXPECT_EQ(at(e.main, 100 * T + 1, (199 - 169) * T + 1), kReferenceOnlyColor);
  EXPECT_EQ(pixels_with(e.main, kFrameColor), 0);
  // without another drawing: an inset where a window pixel is too small to see and something
  // differs from the reference; none at a scale a pixel is seen at, or where nothing differs
  two.has_other = false;
  EXPECT_FALSE(choose_inset(two, 1).window.empty());
  EXPECT_TRUE(choose_inset(two, kInsetBelowScale).window.empty());
  one.has_other = false;
  EXPECT_TRUE(choose_inset(one, 1).window.empty());
}

}  // namespace
}  // namespace ra::triage
