// Declares into another folder's namespace: a finding.
#pragma once
#include "low/upward.h"

namespace ra::mid {
namespace detail {}  // nested under the folder's namespace: fine
}  // namespace ra::mid

namespace ra::low {
int from_mid();
}  // namespace ra::low
