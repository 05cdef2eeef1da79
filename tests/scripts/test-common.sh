# Sourced by the CTest scripts that take the build folder as $1 and report every failure before
# they exit (api-validation-test.sh, gpu-check-test.sh, lean-bundle-test.sh). It sets
#   build   the build folder, absolute;   root   the source tree;   tmp   a folder removed at exit
# and defines
#   fail MESSAGE            prints "FAIL: MESSAGE" and marks the test failed ($bad), going on
#   require_built PROG...   stops the test when a program is not built in $build
set -uo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
bad=0
fail() { echo "FAIL: $*"; bad=1; }
require_built() {
  local bin
  for bin in "$@"; do
    [ -x "$build/$bin" ] ||
      { echo "FAIL: $build/$bin not built (cmake --build $build --target test_programs)"; exit 1; }
  done
}
