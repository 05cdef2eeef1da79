// Includes a folder after its own: a finding.
#include "low/upward.h"
#include "high/long_function.h"

namespace ra::low {}
