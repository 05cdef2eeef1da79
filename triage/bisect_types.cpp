// The plain records of the bisection (bisect_types.h).
#include "triage/bisect_types.h"

namespace ra::triage {

std::string BisectPrimitive::label() const {
  return std::string(geometry::kind_name(kind)) + " " + std::to_string(index) + " of view " +
         std::to_string(view);
}

}  // namespace ra::triage
