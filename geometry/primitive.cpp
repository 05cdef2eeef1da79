#include "geometry/primitive.h"

#include "util/counter_rng.h"

namespace ra::geometry {

const char* kind_name(Kind k) {
  switch (k) {
    case Kind::kPoint: return "point";
    case Kind::kLine: return "line";
    case Kind::kTriangle: return "triangle";
  }
  return "?";
}

const char* kind_plural(Kind k) {
  switch (k) {
    case Kind::kPoint: return "points";
    case Kind::kLine: return "lines";
    case Kind::kTriangle: return "triangles";
  }
  return "?";
}

std::optional<Kind> parse_kind(std::string_view s, KindSpelling spelling) {
  for (Kind k : {Kind::kPoint, Kind::kLine, Kind::kTriangle}) {
    if (s == kind_name(k) || (spelling == KindSpelling::kNameOrPlural && s == kind_plural(k)))
      return k;
  }
  return std::nullopt;
}

bool parse_kind(const std::string& s, Kind* out) {
  const std::optional<Kind> k = parse_kind(s, KindSpelling::kNameOrPlural);
  if (k) *out = *k;
  return k.has_value();
}

static util::RngStream stream_of(Kind k) {
  switch (k) {
    case Kind::kPoint:
      return util::RngStream::kPoint;
    case Kind::kLine:
      return util::RngStream::kLine;
    case Kind::kTriangle:
      return util::RngStream::kTriangle;
  }
  return util::RngStream::kPoint;
}

Primitive make_primitive(uint64_t seed, Kind kind, uint64_t index) {
  Primitive prim;
  prim.kind = kind;
  prim.index = index;
  util::CounterRng rng(seed, stream_of(kind), index);
  for (int i = 0; i < vertex_count(kind); ++i) {
    // Rejection from the cube [-1, 1]^3 keeps the points uniform in the ball (paper, 3.3).
    Vec3 p;
    do {
      p = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    } while (dot(p, p) > 1.0);
    prim.v[i] = p;
  }
  return prim;
}

}  // namespace ra::geometry
