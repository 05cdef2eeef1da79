#include "audit/audit_summary.h"

namespace ra::audit {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::kUnchanged: return "unchanged";
    case Verdict::kChanged: return "changed";
    case Verdict::kFailed: return "failed";
    case Verdict::kBaseline: return "baseline";
  }
  return "failed";
}

std::string verdict_text(Verdict v) {
  return v == Verdict::kBaseline ? "baseline established: nothing compared" : verdict_name(v);
}

int verdict_exit_code(Verdict v) { return v == Verdict::kBaseline ? 0 : int(v); }

bool parse_verdict(const std::string& s, Verdict* out) {
  for (Verdict v :
       {Verdict::kUnchanged, Verdict::kChanged, Verdict::kFailed, Verdict::kBaseline}) {
    if (s == verdict_name(v)) {
      *out = v;
      return true;
    }
  }
  return false;
}

}  // namespace ra::audit
