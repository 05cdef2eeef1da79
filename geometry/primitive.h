// The primitives of the audit and their deterministic generation (NIST paper, section 3.3):
// every vertex is uniform in the unit sphere, drawn by rejection from the cube [-1, 1]^3.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "geometry/vector_math.h"

namespace ra::geometry {

enum class Kind { kPoint = 0, kLine = 1, kTriangle = 2 };

const char* kind_name(Kind k);        // "point", "line", "triangle"
const char* kind_plural(Kind k);      // "points", "lines", "triangles" (experiment-file keys)
// Where a kind is read, how it may be spelled: the name only where kind_name wrote it (records),
// the name or the plural where a person writes it (experiment files, command lines, documents).
enum class KindSpelling { kName, kNameOrPlural };
std::optional<Kind> parse_kind(std::string_view s, KindSpelling spelling);
bool parse_kind(const std::string& s, Kind* out);  // singular or plural, into *out: false if neither
inline int vertex_count(Kind k) { return static_cast<int>(k) + 1; }

struct Primitive {
  Kind kind = Kind::kPoint;
  uint64_t index = 0;
  std::array<Vec3, 3> v{};  // world units; the first vertex_count(kind) are used
};

// Primitive `index` of `kind` under `seed`: a pure function of its arguments.
Primitive make_primitive(uint64_t seed, Kind kind, uint64_t index);

}  // namespace ra::geometry
