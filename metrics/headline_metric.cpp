// Each kind's headline error (see the header).
#include "metrics/headline_metric.h"

namespace ra::metrics {

const char* headline_column(geometry::Kind kind) {
  switch (kind) {
    case geometry::Kind::kPoint:
      return "pe";
    case geometry::Kind::kLine:
      return "lse_u";
    case geometry::Kind::kTriangle:
      return "te_u";
  }
  return "";
}

double headline_value(const Record& r, geometry::Kind kind) {
  switch (kind) {
    case geometry::Kind::kPoint:
      return r.pe;
    case geometry::Kind::kLine:
      return r.lse_u;
    case geometry::Kind::kTriangle:
      return r.te_u;
  }
  return kNA;
}

}  // namespace ra::metrics
