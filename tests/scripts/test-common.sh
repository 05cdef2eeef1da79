# Sourced first by the CTest scripts that take the build folder as $1 (api-validation-test.sh,
# gpu-check-test.sh, lean-bundle-test.sh, and through bisect-fixture.sh's tests the bisection and
# watch tests). It sets
#   build     the build folder, absolute;   root   the source tree
#   t         a folder of the test's own (renderaudit-SCRIPT-XXXXXX in $TMPDIR or /tmp), removed at
#             exit unless KEEP is set (KEEP=1 keeps it to look at)
#   pids      the background processes the test starts (pids+=("$!")): killed at exit
#   on_exit   commands run at exit before the folder is removed (a cluster the test started)
# and defines
#   fail MESSAGE            prints "FAIL: MESSAGE" and marks the test failed ($bad), going on
#                           (bisect-fixture.sh's fail stops the test instead)
#   require_built PROG...   stops the test when a program is not built in $build
set -uo pipefail
build=$(cd "${1:?usage: $0 BUILD_DIR}" && pwd)
root=$(cd "$(dirname "$0")/../.." && pwd)
t=$(mktemp -d -t "renderaudit-$(basename "$0" .sh)-XXXXXX")
pids=()
on_exit=
end_test() {
  local p
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  [ -z "$on_exit" ] || eval "$on_exit"
  [ -n "${KEEP:-}" ] || rm -rf "$t"
}
trap end_test EXIT
bad=0
fail() { echo "FAIL: $*"; bad=1; }
require_built() {
  local bin
  for bin in "$@"; do
    [ -x "$build/$bin" ] ||
      { echo "FAIL: $build/$bin not built (cmake --build $build --target test_programs)"; exit 1; }
  done
}
