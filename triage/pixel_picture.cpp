// Window pixels as a picture read at page size (pixel_picture.h).
#include "triage/pixel_picture.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <map>
#include <utility>

namespace ra::triage {
namespace {

using Point = std::pair<int, int>;  // image pixels, or window pixels where said

Rgb8 darker(Rgb8 c) { return {uint8_t(c.r * 4 / 5), uint8_t(c.g * 4 / 5), uint8_t(c.b * 4 / 5)}; }

void put(PixelPicture& pic, int x, int y, Rgb8 c) {
  if (x < 0 || y < 0 || x >= pic.width || y >= pic.height) return;
  uint8_t* px = &pic.rgb[(std::size_t(y) * pic.width + x) * 3];
  px[0] = c.r, px[1] = c.g, px[2] = c.b;
}

// Clusters of points: points in cells of side `join` that touch (8 neighbours) are one cluster.
// Returns each cluster's bounding box {x0, y0, x1, y1} (inclusive) and its points, in the order of
// their first point.
struct Cluster {
  std::array<int, 4> box;
  std::vector<Point> points;
};
std::vector<Cluster> clusters(const std::vector<Point>& points, int join) {
  std::map<Point, int> cell_of;  // cell -> index into `parent`
  std::vector<int> parent;
  const auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const auto& [x, y] : points) {
    const Point c{x / join, y / join};
    if (!cell_of.count(c)) {
      cell_of[c] = int(parent.size());
      parent.push_back(int(parent.size()));
    }
  }
  for (const auto& [c, i] : cell_of)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const auto it = cell_of.find({c.first + dx, c.second + dy});
        if (it != cell_of.end()) parent[find(i)] = find(it->second);
      }
  std::map<int, std::size_t> index_of_root;
  std::vector<Cluster> out;
  for (const auto& [x, y] : points) {
    const int root = find(cell_of[{x / join, y / join}]);
    auto [it, fresh] = index_of_root.try_emplace(root, out.size());
    if (fresh) out.push_back({{x, y, x, y}, {}});
    Cluster& c = out[it->second];
    c.box = {std::min(c.box[0], x), std::min(c.box[1], y), std::max(c.box[2], x),
             std::max(c.box[3], y)};
    c.points.push_back({x, y});
  }
  return out;
}

int64_t cross(Point o, Point a, Point b) {
  return int64_t(a.first - o.first) * (b.second - o.second) -
         int64_t(a.second - o.second) * (b.first - o.first);
}

// The convex hull (Andrew's monotone chain), counter-clockwise in a y-up frame, collinear points
// dropped: 1 point for one, 2 for points on a line.
std::vector<Point> convex_hull(std::vector<Point> p) {
  std::sort(p.begin(), p.end());
  p.erase(std::unique(p.begin(), p.end()), p.end());
  if (p.size() < 3) return p;
  std::vector<Point> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower
    while (k >= 2 && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {  // upper
    while (k >= t && cross(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

double segment_distance(double px, double py, Point a, Point b) {
  const double dx = b.first - a.first, dy = b.second - a.second;
  const double len2 = dx * dx + dy * dy;
  double t = len2 > 0 ? ((px - a.first) * dx + (py - a.second) * dy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  return std::hypot(px - (a.first + t * dx), py - (a.second + t * dy));
}

// Distance of (x, y) from the convex polygon `hull` (0 inside), in its units.
double hull_distance(const std::vector<Point>& hull, double x, double y) {
  if (hull.size() == 1) return std::hypot(x - hull[0].first, y - hull[0].second);
  bool inside = hull.size() >= 3;
  double d = INFINITY;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const Point a = hull[i], b = hull[(i + 1) % hull.size()];
    inside = inside && (double(b.first - a.first) * (y - a.second) -
                        double(b.second - a.second) * (x - a.first)) >= 0;
    d = std::min(d, segment_distance(x, y, a, b));
    if (hull.size() == 2) break;
  }
  return inside ? 0 : d;
}

// Draws the rings: every halo first, then every ring, so that a halo never cuts a neighbouring
// ring. A ring never hides what a window pixel is: it leaves the centre of each block of 3 image
// pixels or more it crosses.
void draw_rings(PixelPicture& pic, int scale) {
  for (const bool halo : {true, false})
    for (const MarkerRing& r : pic.rings) {
      int x0 = pic.width, y0 = pic.height, x1 = 0, y1 = 0;
      for (const auto& [x, y] : r.hull)
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
      const int reach = r.radius + r.half_width + 2;
      for (int y = std::max(0, y0 - reach); y <= std::min(pic.height - 1, y1 + reach); ++y)
        for (int x = std::max(0, x0 - reach); x <= std::min(pic.width - 1, x1 + reach); ++x) {
          const double d = std::fabs(hull_distance(r.hull, x, y) - r.radius);
          if (halo ? d > r.half_width + 1 : d > r.half_width) continue;
          if (scale >= 3 && x % scale == scale / 2 && y % scale == scale / 2) continue;
          put(pic, x, y, halo ? kUnlitColor : kMarkerColor);
        }
    }
}

// Clear of the blocks; in a large picture farther and thicker, so that it reads at page size.
int ring_radius(int longer, int S) {
  return std::max({kMarkerMinRadius, longer / 40, int(std::ceil(0.7072 * S)) + 6});
}
int ring_half_width(int longer) { return longer >= 600 ? 2 : 1; }

// The rings around the marked blocks (centres, image pixels) of `pic`: clusters of nearby ones
// share one; too many clusters are joined over longer distances until a reader can take them in.
void ring_marked(PixelPicture& pic, const std::vector<Point>& marked, int S) {
  if (marked.empty()) return;
  std::vector<Cluster> groups;
  for (int join = std::max(kMarkerJoin, S + 1);; join *= 2) {
    groups = clusters(marked, join);
    if (groups.size() <= kMarkerMaxRings || join > pic.width + pic.height) break;
  }
  const int longer = std::max(pic.width, pic.height);
  const int radius = ring_radius(longer, S);
  for (const Cluster& g : groups) {
    const auto& b = g.box;
    const int64_t area = int64_t(g.points.size()) * S * S;  // image pixels of black
    const int64_t length = std::max(b[2] - b[0], b[3] - b[1]) + S;
    // as much black as a square of kMarkerLargeCluster, and thick, is seen without a ring; a
    // thin crack is not
    if (area >= int64_t(kMarkerLargeCluster) * kMarkerLargeCluster &&
        area >= int64_t(kMarkerThick) * length) {
      ++pic.large_clusters;
      continue;
    }
    MarkerRing r;
    r.cx = (b[0] + b[2]) / 2;
    r.cy = (b[1] + b[3]) / 2;
    r.radius = radius;
    r.half_width = ring_half_width(longer);
    r.hull = convex_hull(g.points);
    pic.rings.push_back(std::move(r));
  }
  draw_rings(pic, S);
}

// A line of image pixels from a to b (Bresenham), only where it lies on the picture.
void draw_segment(PixelPicture& pic, Point a, Point b, Rgb8 c) {
  const int dx = std::abs(b.first - a.first), dy = -std::abs(b.second - a.second);
  const int sx = a.first < b.first ? 1 : -1, sy = a.second < b.second ? 1 : -1;
  int err = dx + dy, x = a.first, y = a.second;
  for (;;) {
    put(pic, x, y, c);
    if (x == b.first && y == b.second) break;
    const int e2 = 2 * err;
    if (e2 >= dy) err += dy, x += sx;
    if (e2 <= dx) err += dx, y += sy;
  }
}

// The ideal projection as a 1-px red line on a picture of `shown` at `scale`. `clamp`: ends on the
// window's far edges land on the last pixel (the picture holds the whole projection); otherwise
// the line runs past the picture's edges (an inset).
void draw_ideal(PixelPicture& pic, const std::vector<geometry::Vec2>& pts,
                const geometry::PixelRect& shown, int S, bool clamp) {
  const auto to_image = [&](geometry::Vec2 p) {
    const double x = std::floor((p.x - shown.x0) * S), y = std::floor((shown.y1 - p.y) * S);
    if (clamp)
      return Point{std::clamp(int(x), 0, pic.width - 1), std::clamp(int(y), 0, pic.height - 1)};
    // far beyond an inset: cut, so that the line's steps stay few
    constexpr double kFar = 1 << 20;
    return Point{int(std::clamp(x, -kFar, kFar)), int(std::clamp(y, -kFar, kFar))};
  };
  if (pts.size() == 1) {
    const auto [cx, cy] = to_image(pts[0]);
    const int arm = std::max(3, S / 3);
    draw_segment(pic, {cx - arm, cy}, {cx + arm, cy}, kIdealColor);
    draw_segment(pic, {cx, cy - arm}, {cx, cy + arm}, kIdealColor);
  } else if (pts.size() == 2) {
    draw_segment(pic, to_image(pts[0]), to_image(pts[1]), kIdealColor);
  } else {
    for (std::size_t i = 0; i < pts.size(); ++i)
      draw_segment(pic, to_image(pts[i]), to_image(pts[(i + 1) % pts.size()]), kIdealColor);
  }
}

// The pixels of a or b but not both.
std::vector<geometry::Pixel> differing(const geometry::PixelSet& a, const geometry::PixelSet& b) {
  std::vector<geometry::Pixel> out = geometry::set_difference(a, b).pixels();
  const std::vector<geometry::Pixel> more = geometry::set_difference(b, a).pixels();
  out.insert(out.end(), more.begin(), more.end());
  std::sort(out.begin(), out.end());
  return out;
}

// A magenta dot on each block of `pixels` within `shown`, drawn at `scale`: small enough that the
// block's own colour stays what is seen. Only where they are few (at most an eighth of the
// pixels shown): a change of many pixels is seen without them, and dots all over would hide it.
// Returns whether it dotted them.
bool dot(PixelPicture& pic, const std::vector<geometry::Pixel>& pixels,
         const geometry::PixelRect& shown, int S) {
  const auto in = [&](const geometry::Pixel& p) {
    return p.x >= shown.x0 && p.x < shown.x1 && p.y >= shown.y0 && p.y < shown.y1;
  };
  const int64_t n = std::count_if(pixels.begin(), pixels.end(), in);
  if (n == 0 || n * 8 > shown.area()) return false;
  const double r = std::max(1.0, S / 6.0);
  for (const geometry::Pixel& p : pixels) {
    if (!in(p)) continue;
    const double cx = (p.x - shown.x0) * S + S / 2.0, cy = (shown.y1 - 1 - p.y) * S + S / 2.0;
    for (int y = int(cy - r) - 1; y <= int(cy + r) + 1; ++y)
      for (int x = int(cx - r) - 1; x <= int(cx + r) + 1; ++x)
        if (std::hypot(x + 0.5 - cx, y + 0.5 - cy) <= r) put(pic, x, y, kMarkerColor);
  }
  return true;
}

// An outline `width` image pixels wide just inside the rectangle [x0, x1] x [y0, y1] (inclusive)
// on a picture of blocks of `scale`: like a ring, it leaves the centre of each block of 3 image
// pixels or more.
void outline(PixelPicture& pic, int x0, int y0, int x1, int y1, int width, Rgb8 c, int scale) {
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) {
      if (!(x < x0 + width || x > x1 - width || y < y0 + width || y > y1 - width)) continue;
      if (scale >= 3 && x % scale == scale / 2 && y % scale == scale / 2) continue;
      put(pic, x, y, c);
    }
}

}  // namespace

int marker_ring_reach(int longer_side, int scale) {
  return ring_radius(longer_side, scale) + ring_half_width(longer_side) + 1;
}

bool missing_hatch(int x, int y, int scale) {
  const int w = std::max(1, scale / 4);
  return ((x + y) / w) % 2 == 0;
}

PixelPicture draw_pixel_picture(const geometry::PixelSet& lit, const geometry::PixelSet& reference,
                                const geometry::PixelSet& violating,
                                const geometry::PixelRect& shown, int S) {
  PixelPicture pic;
  const int cols = shown.x1 - shown.x0, rows = shown.y1 - shown.y0;
  pic.width = cols * S;
  pic.height = rows * S;
  // the colours' counts, whole window
  for (const geometry::Pixel& p : lit) {
    if (violating.contains(p))
      ++pic.forbidden;
    else
      (reference.contains(p) ? pic.both : pic.platform_only) += 1;
  }
  for (const geometry::Pixel& p : reference)
    if (!lit.contains(p)) (violating.contains(p) ? pic.missing : pic.reference_only) += 1;
  for (const geometry::Pixel& p : violating)
    if (!lit.contains(p) && !reference.contains(p)) ++pic.missing;

  // Which rasterizer lit each shown pixel: bit 0 platform, bit 1 reference, bit 2 a rule's.
  std::vector<uint8_t> who(std::size_t(cols) * rows, 0);
  auto mark = [&](const geometry::PixelSet& s, uint8_t bit) {
    for (const geometry::PixelRun& run : s.runs()) {
      if (run.y < shown.y0 || run.y >= shown.y1) continue;
      for (int x = std::max(run.x_begin, shown.x0); x < std::min(run.x_end, shown.x1); ++x)
        who[std::size_t(run.y - shown.y0) * cols + (x - shown.x0)] |= bit;
    }
  };
  mark(lit, 1);
  mark(reference, 2);
  mark(violating, 4);
  const Rgb8 colors[4] = {kUnlitColor, kPlatformOnlyColor, kReferenceOnlyColor, kBothColor};

  // Blocks, rows flipped: window row y (up) is image rows (shown.y1 - 1 - y) * S ... + S - 1.
  pic.rgb.resize(std::size_t(pic.width) * pic.height * 3);
  std::vector<Point> marked;  // centres of the forbidden and missing blocks, image pixels
  for (int wy = 0; wy < rows; ++wy)
    for (int wx = 0; wx < cols; ++wx) {
      const uint8_t w = who[std::size_t(wy) * cols + wx];
      const bool forbidden = (w & 4) && (w & 1), missing = (w & 4) && !(w & 1);
      const Rgb8 fill = forbidden ? kForbiddenColor : missing ? kMissingColor : colors[w & 3];
      const Rgb8 edge = S >= 8 ? darker(fill) : fill;
      const int top = (rows - 1 - wy) * S, left = wx * S;
      if (w & 4) marked.push_back({left + S / 2, top + S / 2});
      for (int i = 0; i < S; ++i)
        for (int j = 0; j < S; ++j) {
          const bool border = i == 0 || j == 0;
          // a missing pixel: stripes on white, a hole where ink must be
          const bool blank = missing && !border && !missing_hatch(left + j, top + i, S);
          const Rgb8 c = blank ? kUnlitColor : border ? edge : fill;
          uint8_t* px = &pic.rgb[(std::size_t(top + i) * pic.width + left + j) * 3];
          px[0] = c.r, px[1] = c.g, px[2] = c.b;
        }
    }
  ring_marked(pic, marked, S);
  return pic;
}

InsetChoice choose_inset(const PictureLayers& L, int scale) {
  InsetChoice out;
  if (scale >= kInsetBelowScale) return out;
  // the differing pixels: from the other drawing, else the rules', else the reference's
  std::vector<geometry::Pixel> focus;
  if (L.has_other) {
    focus = differing(L.lit, L.other);
  } else {
    focus = L.violating.pixels();
    if (focus.empty()) focus = differing(L.lit, L.reference);
  }
  if (focus.empty() || L.window_width <= 0 || L.window_height <= 0) return out;
  out.differing = int64_t(focus.size());
  std::vector<Point> points;  // window pixels
  for (const geometry::Pixel& p : focus) points.push_back({p.x, p.y});
  // the largest cluster (the first of equals), and its pixel nearest the middle of its box
  const std::vector<Cluster> groups = clusters(points, kInsetMaxWindow / 2);
  const Cluster* best = &groups.front();
  for (const Cluster& g : groups)
    if (g.points.size() > best->points.size()) best = &g;
  const auto& b = best->box;
  const double mx = 0.5 * (b[0] + b[2]), my = 0.5 * (b[1] + b[3]);
  Point centre = best->points.front();
  for (const Point& p : best->points)
    if (std::hypot(p.first - mx, p.second - my) < std::hypot(centre.first - mx, centre.second - my))
      centre = p;
  // a little more than the cluster, within limits and the window; then each side cut to the
  // differing pixels it holds (a line's strip, not a square of white)
  const auto window_around = [&](int cx, int cy, int wx, int wy) {
    wx = std::min(std::clamp(wx, kInsetMinWindow, kInsetMaxWindow), L.window_width);
    wy = std::min(std::clamp(wy, kInsetMinWindow, kInsetMaxWindow), L.window_height);
    const int x0 = std::clamp(cx - wx / 2, 0, L.window_width - wx);
    const int y0 = std::clamp(cy - wy / 2, 0, L.window_height - wy);
    return geometry::PixelRect{x0, y0, x0 + wx, y0 + wy};
  };
  constexpr int kAround = 2;  // window pixels around the differing ones
  const geometry::PixelRect first = window_around(
      centre.first, centre.second, b[2] - b[0] + 1 + 2 * kAround, b[3] - b[1] + 1 + 2 * kAround);
  int x0 = first.x1, y0 = first.y1, x1 = first.x0, y1 = first.y0;
  for (const Point& p : best->points)
    if (p.first >= first.x0 && p.first < first.x1 && p.second >= first.y0 && p.second < first.y1)
      x0 = std::min(x0, p.first), x1 = std::max(x1, p.first), y0 = std::min(y0, p.second),
      y1 = std::max(y1, p.second);
  out.window = window_around((x0 + x1 + 1) / 2, (y0 + y1 + 1) / 2,
                             std::min(x1 - x0 + 1 + 2 * kAround, first.x1 - first.x0),
                             std::min(y1 - y0 + 1 + 2 * kAround, first.y1 - first.y0));
  const int longer = std::max(out.window.x1 - out.window.x0, out.window.y1 - out.window.y0);
  out.scale = (kInsetSide + longer - 1) / longer;
  return out;
}

ComposedPicture compose_picture(const PictureLayers& L, const geometry::PixelRect& shown,
                                int scale) {
  ComposedPicture out;
  out.main = draw_pixel_picture(L.lit, L.reference, L.violating, shown, scale);
  draw_ideal(out.main, L.ideal, shown, scale, true);
  if (L.has_other) out.drawn_otherwise = geometry::symmetric_difference_size(L.lit, L.other);
  out.inset_choice = choose_inset(L, scale);
  const InsetChoice& in = out.inset_choice;
  if (in.window.empty()) {  // the pixels are seen in the picture: the ones drawn otherwise dotted
    if (L.has_other && scale >= 3)
      out.dotted = dot(out.main, differing(L.lit, L.other), shown, scale);
    return out;
  }
  // where the inset lies in the picture: a frame, with a white halo, thick enough for the page
  out.frame_width = std::max(2, std::max(out.main.width, out.main.height) / 300);
  const int fw = out.frame_width;
  const int x0 = (in.window.x0 - shown.x0) * scale, x1 = (in.window.x1 - shown.x0) * scale - 1;
  const int y0 = (shown.y1 - in.window.y1) * scale, y1 = (shown.y1 - in.window.y0) * scale - 1;
  outline(out.main, x0 - fw - 1, y0 - fw - 1, x1 + fw + 1, y1 + fw + 1, 1, kUnlitColor, scale);
  outline(out.main, x0 - fw, y0 - fw, x1 + fw, y1 + fw, fw, kFrameColor, scale);
  outline(out.main, x0, y0, x1, y1, 1, kUnlitColor, scale);
  // the inset itself, and in it the pixels the other platform draws otherwise, dotted
  const int S = in.scale;
  out.inset = draw_pixel_picture(L.lit, L.reference, L.violating, in.window, S);
  draw_ideal(out.inset, L.ideal, in.window, S, false);
  if (L.has_other) out.dotted = dot(out.inset, differing(L.lit, L.other), in.window, S);
  return out;
}

}  // namespace ra::triage
