#include "audit/audit_summary.h"

namespace ra::audit {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::kUnchanged: return "unchanged";
    case Verdict::kChanged: return "changed";
    case Verdict::kFailed: return "failed";
  }
  return "failed";
}

bool parse_verdict(const std::string& s, Verdict* out) {
  for (Verdict v : {Verdict::kUnchanged, Verdict::kChanged, Verdict::kFailed}) {
    if (s == verdict_name(v)) {
      *out = v;
      return true;
    }
  }
  return false;
}

}  // namespace ra::audit
