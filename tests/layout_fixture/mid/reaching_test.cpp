// A test of mid/ that includes high/: a finding (it belongs in high/). The test-support header
// of high/ is allowed from any folder.
#include "mid/wrong_namespace.h"
#include "high/helpers_testing.h"
#include "high/long_function.h"

namespace ra::mid {}
