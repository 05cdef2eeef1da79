#!/usr/bin/env bash
# The test of scripts/check-build-tree.sh (ctest build_tree_moved): a build folder whose
# CMakeCache.txt names another source tree, or another build folder, is refused by the script and
# by `make`, naming the tree it belongs to and the two ways on; a folder of this tree, and one not
# yet configured, pass.
# Usage: tests/scripts/check-build-tree-test.sh
set -uo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd -P)
t=$(mktemp -d /tmp/renderaudit-build-tree-test-XXXXXX)
t=$(cd "$t" && pwd -P)
trap '[ -n "${KEEP:-}" ] || rm -rf "$t"' EXIT
bad=0
fail() { echo "check-build-tree-test: FAIL: $*" >&2; bad=1; }

# A CMakeCache.txt as CMake writes it, with only the lines the check reads.
fake_cache() {  # FOLDER SOURCE_DIR MADE_IN
  mkdir -p "$1"
  cat > "$1/CMakeCache.txt" <<CACHE
# This is the CMakeCache file.
# For build in directory: $3
CMAKE_BUILD_TYPE:STRING=Release
renderaudit_SOURCE_DIR:STATIC=$2
CMAKE_CACHEFILE_DIR:INTERNAL=$3
CMAKE_HOME_DIRECTORY:INTERNAL=$2
CACHE
}
expect_refusal() {  # WHAT OUTPUT RC NEEDLE...
  local what=$1 out=$2 rc=$3
  shift 3
  [ "$rc" = 2 ] || fail "$what: exit $rc, expected 2"
  for needle in "$@"; do
    grep -qF -- "$needle" <<<"$out" || fail "$what: no '$needle' in: $out"
  done
}

# A checkout copied with its build folder: the cache names the original tree.
fake_cache "$t/copied" "$t/original-tree" "$t/copied"
out=$("$here/scripts/check-build-tree.sh" "$t/copied" 2>&1); rc=$?
expect_refusal "a copied tree" "$out" "$rc" "belongs to the source tree $t/original-tree" \
  "not to this one ($here)" "rm -rf $t/copied" "make BUILD=other-folder"
out=$(make -s -C "$here" check-build-tree BUILD="$t/copied" 2>&1); rc=$?
[ "$rc" != 0 ] || fail "make check-build-tree accepted a copied tree's folder"
grep -qF "belongs to the source tree $t/original-tree" <<<"$out" || fail "make said: $out"

# A build folder moved on its own: the cache names the folder it was made in.
fake_cache "$t/moved" "$here" "$t/first-place"
out=$("$here/scripts/check-build-tree.sh" "$t/moved" 2>&1); rc=$?
expect_refusal "a moved build folder" "$out" "$rc" \
  "was configured as the build folder $t/first-place" "rm -rf $t/moved" "make BUILD=other-folder"

# This tree's own folder, reached through a symbolic link, and a folder not configured yet.
fake_cache "$t/mine" "$here" "$t/mine"
ln -s "$t/mine" "$t/link"
for ok in "$t/mine" "$t/link" "$t/empty"; do
  out=$("$here/scripts/check-build-tree.sh" "$ok" 2>&1); rc=$?
  [ "$rc" = 0 ] && [ -z "$out" ] || fail "$ok refused (exit $rc): $out"
done
[ "$bad" = 0 ] || exit 1
echo "check-build-tree-test: a copied tree and a moved build folder refused, naming where they belong"
