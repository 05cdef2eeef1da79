#include "runner/vector_math.h"
#include "scenes/scene.h"

namespace ra {

size_t StripMesh::triangle_count() const {
  size_t n = 0;
  for (const TriangleStrip& s : strips)
    if (s.indices.size() > 2) n += s.indices.size() - 2;
  return n;
}

}  // namespace ra
