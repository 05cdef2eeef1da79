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

const char* headline_norm_column(geometry::Kind kind) {
  switch (kind) {
    case geometry::Kind::kPoint:
      return "pe_norm";
    case geometry::Kind::kLine:
      return "lse_u_norm";
    case geometry::Kind::kTriangle:
      return "te_u_norm";
  }
  return "";
}

double headline_norm_value(const Record& r, geometry::Kind kind) {
  switch (kind) {
    case geometry::Kind::kPoint:
      return r.pe_norm;
    case geometry::Kind::kLine:
      return r.lse_u_norm;
    case geometry::Kind::kTriangle:
      return r.te_u_norm;
  }
  return kNA;
}

const char* summary_metric_label(geometry::Kind kind) {
  switch (kind) {
    case geometry::Kind::kPoint:
      return "PE (px)";
    case geometry::Kind::kLine:
      return "LSEu-norm";
    case geometry::Kind::kTriangle:
      return "TEu-norm";
  }
  return "";
}

double summary_metric_value(const Record& r, geometry::Kind kind) {
  return kind == geometry::Kind::kPoint ? headline_value(r, kind) : headline_norm_value(r, kind);
}

}  // namespace ra::metrics
