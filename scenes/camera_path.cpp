// Camera paths for the per-frame measurements (Wimmer & Wonka 2003, section 7.2).
#include "scenes/camera_path.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "scenes/scene_rng.h"
#include "util/atomic_file.h"
#include "util/cell_text.h"
#include "util/errors.h"

namespace ra::scenes {
namespace {

constexpr double kPi = 3.14159265358979323846;

double len2(geometry::Vec2 a) { return geometry::length(a); }
geometry::Vec2 lerp(geometry::Vec2 a, geometry::Vec2 b, double t) { return a + t * (b - a); }

void validate(const CameraPathParams& p) {
  auto bad = [](const std::string& key, const std::string& v, const std::string& allowed) {
    throw std::invalid_argument("camera_path " + key + " = " + v + " is out of range (allowed: " + allowed + ")");
  };
  if (p.frames < 1 || p.frames > 1000000) bad("frames", std::to_string(p.frames), "1 to 1000000");
  if (p.waypoints < 2 || p.waypoints > 10000) bad("waypoints", std::to_string(p.waypoints), "2 to 10000");
  if (!(p.eye_height > 0 && p.eye_height <= 10000)) bad("eye_height", std::to_string(p.eye_height), "> 0 to 10000");
  if (!(p.flight_height > 0 && p.flight_height <= 100000))
    bad("flight_height", std::to_string(p.flight_height), "> 0 to 100000");
  if (!(p.look_ahead > 0 && p.look_ahead <= 100000)) bad("look_ahead", std::to_string(p.look_ahead), "> 0 to 100000");
}

// City: a random walk over street intersections that never turns back, as straight runs along
// the centre lines joined by quarter circles of radius r <= 0.45 street_width inside the
// crossings: every point stays within street_width / 2 of a centre line, and the tangent is
// continuous.
std::vector<geometry::Vec2> street_walk(const SceneLayout& l, const CameraPathParams& p) {
  SceneRng rng(p.seed, ScenePurpose::kCameraWaypoint, 1);
  auto node = [&](int i, int j) {
    return geometry::Vec2{l.street_x0 + i * l.street_pitch, l.street_y0 + j * l.street_pitch};
  };
  const int dirs[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  int i = static_cast<int>(rng.integer(0, l.streets_x - 1)), j = static_cast<int>(rng.integer(0, l.streets_y - 1));
  int d = -1;
  std::vector<geometry::Vec2> corners{node(i, j)};
  std::vector<int> headings;
  for (int step = 1; step < p.waypoints; ++step) {
    int options[4], n = 0;
    for (int c = 0; c < 4; ++c) {
      const int ni = i + dirs[c][0], nj = j + dirs[c][1];
      if (ni < 0 || nj < 0 || ni >= l.streets_x || nj >= l.streets_y) continue;
      if (d >= 0 && c == (d + 2) % 4) continue;  // no U-turns
      options[n++] = c;
    }
    if (n == 0) break;  // a single street crossing (1 x 1 grid): nowhere to go
    bool straight = false;
    for (int k = 0; k < n; ++k) straight |= options[k] == d;
    // keep going straight half of the time when possible, otherwise any allowed way
    d = straight && rng.uniform01() < 0.5 ? d : options[rng.integer(0, n - 1)];
    i += dirs[d][0];
    j += dirs[d][1];
    corners.push_back(node(i, j));
    headings.push_back(d);
  }
  std::vector<geometry::Vec2> raw{corners.front()};
  const double r = std::min(0.45 * l.street_width, 0.25 * l.street_pitch);
  for (size_t k = 1; k + 1 < corners.size(); ++k) {
    const geometry::Vec2 din{double(dirs[headings[k - 1]][0]), double(dirs[headings[k - 1]][1])};
    const geometry::Vec2 dout{double(dirs[headings[k]][0]), double(dirs[headings[k]][1])};
    if (headings[k] == headings[k - 1]) {
      raw.push_back(corners[k]);
      continue;
    }
    const geometry::Vec2 centre = corners[k] - r * din + r * dout;
    for (int a = 0; a <= 16; ++a) {
      const double phi = 0.5 * kPi * a / 16;
      raw.push_back(centre + r * (-std::cos(phi) * dout + std::sin(phi) * din));
    }
  }
  if (corners.size() > 1) raw.push_back(corners.back());
  return raw;
}

// Elsewhere: a walker with a bounded turning radius R (2.5 % of the box's smaller side) steering
// towards seeded waypoints in the box's inner 80 %, taking the next one when within 2R of the
// current one. The heading turns by at most 1/R radians per metre, so the path is smooth (no
// hairpins, continuous tangent) and strays at most ~4R = 10 % of the box beyond the inner part.
// Each waypoint is drawn at least 4R from where the walker is, outside its turning circles, so
// it can always be reached.
std::vector<geometry::Vec2> free_flight(const SceneLayout& l, const CameraPathParams& p) {
  SceneRng rng(p.seed, ScenePurpose::kCameraWaypoint, 2);
  const double w = l.box_max.x - l.box_min.x, h = l.box_max.y - l.box_min.y;
  const geometry::Vec2 lo{l.box_min.x + 0.1 * w, l.box_min.y + 0.1 * h},
      hi{l.box_max.x - 0.1 * w, l.box_max.y - 0.1 * h};
  const double r = free_flight_turn_radius(l), ds = r / 8;
  geometry::Vec2 at{rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y)};
  double heading = rng.uniform(0, 2 * kPi);
  std::vector<geometry::Vec2> raw{at};
  for (int k = 1; k < p.waypoints; ++k) {
    geometry::Vec2 target{}, best{};
    double best_d = -1;
    for (int attempt = 0; attempt < 16; ++attempt) {
      target = {rng.uniform(lo.x, hi.x), rng.uniform(lo.y, hi.y)};
      const double d = len2(target - at);
      if (d > best_d) {
        best_d = d;
        best = target;
      }
      if (d >= 4 * r) break;
    }
    target = best;
    // a reachable target is reached within its distance plus a full turn; the cap only guards
    const int max_steps = static_cast<int>((best_d + 2 * kPi * r) / ds) * 4 + 64;
    for (int step = 0; step < max_steps && len2(target - at) > 2 * r; ++step) {
      const geometry::Vec2 d = target - at;
      double turn = std::remainder(std::atan2(d.y, d.x) - heading, 2 * kPi);
      turn = std::clamp(turn, -ds / r, ds / r);
      heading += turn;
      at = at + ds * geometry::Vec2{std::cos(heading), std::sin(heading)};
      // note: never active by the bound above; keeps a broken layout from leaving the box
      at = {std::clamp(at.x, l.box_min.x, l.box_max.x), std::clamp(at.y, l.box_min.y, l.box_max.y)};
      raw.push_back(at);
    }
  }
  if (raw.size() == 1)
    raw.push_back(raw[0] + ds * geometry::Vec2{std::cos(heading), std::sin(heading)});
  return raw;
}

// The polyline resampled at steps of at most `step` metres of arc length (every raw point kept).
std::vector<geometry::Vec2> densify(const std::vector<geometry::Vec2>& raw, double step) {
  std::vector<geometry::Vec2> out{raw.front()};
  for (size_t k = 1; k < raw.size(); ++k) {
    const double d = len2(raw[k] - raw[k - 1]);
    const int n = std::max(1, static_cast<int>(std::ceil(d / step)));
    for (int m = 1; m <= n; ++m) out.push_back(lerp(raw[k - 1], raw[k], double(m) / n));
  }
  return out;
}

}  // namespace

double free_flight_turn_radius(const SceneLayout& l) {
  return 0.025 * std::min(l.box_max.x - l.box_min.x, l.box_max.y - l.box_min.y);
}

std::vector<Viewpoint> generate_camera_path(const Scene& scene, const CameraPathParams& p) {
  validate(p);
  const SceneLayout& l = scene.layout;
  if (!(l.box_max.x > l.box_min.x && l.box_max.y > l.box_min.y))
    throw std::invalid_argument("camera path: the scene (kind '" + scene.kind + "') has an empty layout box");
  const bool streets = l.streets_x >= 1 && l.streets_y >= 1 && l.street_pitch > 0;
  const bool terrain = !l.ground_z.empty();
  const std::vector<geometry::Vec2> raw = streets ? street_walk(l, p) : free_flight(l, p);

  // dense samples, closer than a ground cell so that the flight envelope below sees every cell
  const double step = terrain ? 0.5 * l.ground_spacing : 1.0;
  const std::vector<geometry::Vec2> pts = densify(raw, step);
  std::vector<double> arc(pts.size(), 0.0);
  for (size_t k = 1; k < pts.size(); ++k) arc[k] = arc[k - 1] + len2(pts[k] - pts[k - 1]);

  std::vector<double> z(pts.size(), p.eye_height);
  if (terrain) {
    // c: the highest ground of the 3 x 3 cells about each sample (so of every cell within one
    // spacing of it); e: its maximum over +-W; z: e averaged over +-W/2 plus flight_height. Every
    // sample within W/2 of j has e >= c_j, so z_j >= c_j + flight_height, and z is continuous.
    const double s = l.ground_spacing;
    std::vector<double> c(pts.size());
    for (size_t k = 0; k < pts.size(); ++k) {
      double top = -1e300;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) top = std::max(top, l.ground_ceiling(pts[k].x + dx * s, pts[k].y + dy * s));
      c[k] = top;
    }
    const double w = std::max(4 * s, 4 * p.flight_height);
    const int half = std::max(1, static_cast<int>(std::ceil(w / step)));
    auto window_max = [&](const std::vector<double>& v, int h) {
      std::vector<double> out(v.size());
      for (size_t k = 0; k < v.size(); ++k) {
        const size_t a = k >= size_t(h) ? k - h : 0, b = std::min(v.size() - 1, k + h);
        out[k] = *std::max_element(v.begin() + a, v.begin() + b + 1);
      }
      return out;
    };
    const std::vector<double> e = window_max(c, half);
    std::vector<double> prefix(e.size() + 1, 0.0);
    for (size_t k = 0; k < e.size(); ++k) prefix[k + 1] = prefix[k] + e[k];
    const int h2 = half / 2;
    for (size_t k = 0; k < e.size(); ++k) {
      const size_t a = k >= size_t(h2) ? k - h2 : 0, b = std::min(e.size() - 1, k + h2);
      z[k] = (prefix[b + 1] - prefix[a]) / double(b - a + 1) + p.flight_height;
    }
  }

  // frames evenly spaced in arc length, linear between dense samples
  auto at = [&](double s, geometry::Vec2& xy, double& zz) {
    const size_t k = std::min<size_t>(pts.size() - 1,
        static_cast<size_t>(std::upper_bound(arc.begin(), arc.end(), s) - arc.begin()));
    if (k == 0) {
      xy = pts[0];
      zz = z[0];
      return;
    }
    const double span = arc[k] - arc[k - 1];
    const double t = span > 0 ? std::clamp((s - arc[k - 1]) / span, 0.0, 1.0) : 1.0;
    xy = lerp(pts[k - 1], pts[k], t);
    zz = z[k - 1] + t * (z[k] - z[k - 1]);
  };
  const double total = arc.back();
  std::vector<Viewpoint> out;
  out.reserve(p.frames);
  geometry::Vec2 last_dir{1, 0};
  for (int f = 0; f < p.frames; ++f) {
    const double s = p.frames == 1 ? 0.0 : total * f / (p.frames - 1);
    geometry::Vec2 xy, a, b;
    double zz, za, zb;
    at(s, xy, zz);
    // heading: the chord over +-2 m of path (one-sided at the ends)
    at(std::max(0.0, s - 2), a, za);
    at(std::min(total, s + 2), b, zb);
    geometry::Vec2 dir = b - a;
    if (len2(dir) > 1e-9) last_dir = (1 / len2(dir)) * dir;
    Viewpoint v;
    v.eye = {xy.x, xy.y, zz};
    const double drop = terrain ? 0.25 * p.look_ahead : 0.0;  // flying: look slightly down
    v.target = {xy.x + p.look_ahead * last_dir.x, xy.y + p.look_ahead * last_dir.y, zz - drop};
    out.push_back(v);
  }
  return out;
}

std::vector<Viewpoint> parse_camera_path_csv(const std::string& text, const std::string& file_name) {
  static const char* kHeader = "frame,eye_x,eye_y,eye_z,target_x,target_y,target_z";
  static const char* kNames[7] = {"frame", "eye_x", "eye_y", "eye_z", "target_x", "target_y", "target_z"};
  auto fail = [&](int line, const std::string& what) -> void {
    throw util::UserError(file_name + ":" + std::to_string(line) + ": " + what);
  };
  std::vector<Viewpoint> out;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    if (!header) {
      std::string compact;
      for (char ch : line)
        if (ch != ' ' && ch != '\t') compact += ch;
      if (compact != kHeader) fail(line_no, "expected the header '" + std::string(kHeader) + "', found '" + line + "'");
      header = true;
      continue;
    }
    std::vector<std::string> fields;
    try {
      fields = util::split_csv_line(line);
    } catch (const std::invalid_argument& e) {
      fail(line_no, e.what());
    }
    if (fields.size() != 7)
      fail(line_no, "expected 7 comma-separated values (" + std::string(kHeader) + "), found " + std::to_string(fields.size()));
    double v[7];
    for (int k = 0; k < 7; ++k) {
      const std::string& s = fields[k];
      const char* b = s.c_str();
      char* e = nullptr;
      v[k] = std::strtod(b, &e);
      while (e && (*e == ' ' || *e == '\t')) ++e;
      const bool blank = s.find_first_not_of(" \t") == std::string::npos;
      if (blank || e == b || *e != '\0') fail(line_no, std::string(kNames[k]) + " = '" + s + "' is not a number");
      if (!std::isfinite(v[k])) fail(line_no, std::string(kNames[k]) + " = '" + s + "' is not finite");
    }
    const auto expected = static_cast<double>(out.size());
    if (v[0] != expected)
      fail(line_no, "frame = " + fields[0] + " is out of sequence (expected " + std::to_string(out.size()) + ")");
    Viewpoint vp;
    vp.eye = {v[1], v[2], v[3]};
    vp.target = {v[4], v[5], v[6]};
    const geometry::Vec3 d = vp.target - vp.eye;
    if (geometry::dot(d, d) == 0) fail(line_no, "the target equals the eye: no viewing direction");
    out.push_back(vp);
  }
  if (!header) fail(std::max(1, line_no), "no header line '" + std::string(kHeader) + "'");
  if (out.empty()) fail(line_no, "no frames after the header");
  return out;
}

std::vector<Viewpoint> read_camera_path_csv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw util::UserError(path + ":1: cannot open the camera path file");
  std::stringstream buf;
  buf << in.rdbuf();
  return parse_camera_path_csv(buf.str(), path);
}

void write_camera_path_csv(const std::vector<Viewpoint>& path, const std::string& file) {
  std::string text = "frame,eye_x,eye_y,eye_z,target_x,target_y,target_z\n";
  for (size_t k = 0; k < path.size(); ++k) {
    const Viewpoint& v = path[k];
    text += std::to_string(k);
    for (double x : {v.eye.x, v.eye.y, v.eye.z, v.target.x, v.target.y, v.target.z})
      text += "," + util::full_precision(x);
    text += "\n";
  }
  util::write_file_atomic(file, text);  // complete or absent
}

}  // namespace ra::scenes
