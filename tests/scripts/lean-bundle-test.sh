#!/usr/bin/env bash
# The lean program and its bundle (ctest lean_bundle; docs/operations.md): renderaudit-lean and the
# worker load no figure library (VTK, OpenImageIO, cairo, poppler, X11), where the full program
# does; the bundle (scripts/make-bundle.sh), unpacked in another folder, finds every library it
# carries inside itself, runs experiments/quick.toml to records identical to the full program's
# (every column but render_us, batch_size and host_us), audits them as unchanged, and refuses `plot` naming
# the full build.
# Usage: lean-bundle-test.sh BUILD_DIR
source "$(dirname "$0")/test-common.sh"  # build, root, t, fail, require_built
figure_libs='libvtk|libOpenImageIO|libcairo|libpoppler|libX11|libmpi'

require_built renderaudit-lean renderaudit-worker
for bin in "$build/renderaudit-lean" "$build/renderaudit-worker"; do
  needed=$(readelf -d "$bin" | awk '/NEEDED/ {gsub(/[][]/, "", $5); print $5}')
  grep -Eq "$figure_libs" <<<"$needed" && fail "$bin needs a figure library: $(grep -E "$figure_libs" <<<"$needed" | tr '\n' ' ')"
  loaded=$(ldd "$bin")
  grep -Eq "$figure_libs" <<<"$loaded" && fail "$bin loads a figure library: $(grep -Eo "($figure_libs)[^ ]*" <<<"$loaded" | tr '\n' ' ')"
done
# The check can fail: the full program loads them. (ldd's output is read whole before grep looks at
# it: `ldd | grep -q` under pipefail fails when grep stops at its match and ldd dies of SIGPIPE.)
loaded=$(ldd "$build/renderaudit")
grep -Eq "$figure_libs" <<<"$loaded" || fail "the full program loads no figure library: the check above proves nothing"

tarball=$("$root/scripts/make-bundle.sh" "$build/renderaudit-lean" "$build/renderaudit-worker" "$t/dist") ||
  { echo "FAIL: make-bundle.sh"; exit 1; }
mkdir "$t/elsewhere"
tar -C "$t/elsewhere" -xzf "$tarball"
bundle=$(echo "$t"/elsewhere/renderaudit-lean-*)
lean="$bundle/bin/renderaudit"
# Every library the bundle carries is the one loaded (relocatable: found through $ORIGIN).
for lib in "$bundle"/lib/*.so*; do
  name=$(basename "$lib")
  where=$(env -u LD_LIBRARY_PATH ldd "$bundle/libexec/renderaudit" "$bundle/libexec/renderaudit-worker" |
    awk -v n="$name" '$1 == n {print $3}' | xargs -r realpath | sort -u)
  [ -n "$where" ] && [ "$where" = "$lib" ] || fail "$name resolves to '$where', not the bundle's $lib"
done
loaded=$(env -u LD_LIBRARY_PATH ldd "$bundle/libexec/renderaudit")
grep -q "not found" <<<"$loaded" && fail "a library is not found"

# The same records as the full program.
"$build/renderaudit" run "$root/experiments/quick.toml" --out "$t/full" --quiet > /dev/null ||
  fail "the full program's run"
(cd "$t" && env -u LD_LIBRARY_PATH "$lean" run "$bundle/experiments/quick.toml" --out "$t/lean" --quiet > /dev/null) ||
  fail "the bundle's run"
n=0
for f in "$t"/full/records/*.csv.zst; do
  g="$t/lean/records/$(basename "$f")"
  [ -f "$g" ] || { fail "the bundle wrote no $(basename "$g")"; continue; }
  header=$(zstdcat "$f" | sed -n 1p)
  cols=$(tr ',' '\n' <<<"$header" | grep -nvx 'render_us\|batch_size\|host_us' | cut -d: -f1 | paste -sd,)
  cmp -s <(zstdcat "$f" | grep -v '^#' | cut -d, -f"$cols") <(zstdcat "$g" | grep -v '^#' | cut -d, -f"$cols") ||
    fail "$(basename "$f") differs between the full program and the bundle"
  n=$((n + 1))
done
[ "$n" -gt 0 ] || fail "no records compared"
rows=$(for f in "$t"/lean/records/*.csv.zst; do zstdcat "$f" | grep -vc '^#'; done | awk '{s += $1 - 1} END {print s}')
[ "$rows" = 64000 ] || fail "the bundle's run holds $rows records, not 64000"

"$lean" audit "$t/full" "$t/lean" --out "$t/audit" --no-history > "$t/audit.txt" 2>&1 ||
  fail "the bundle's audit of its run against the full program's: exit $? ($(tail -2 "$t/audit.txt"))"
"$lean" plot "$t/lean" > "$t/plot.txt" 2>&1
rc=$?
[ $rc = 2 ] || fail "lean plot: exit $rc, not 2"
grep -q "lean build" "$t/plot.txt" && grep -q "full build" "$t/plot.txt" ||
  fail "lean plot does not say which build has it: $(cat "$t/plot.txt")"

if [ $bad -ne 0 ]; then exit 1; fi
echo "lean bundle: no figure library loaded; $(basename "$tarball") relocatable; $n shard files of quick identical to the full program's; audit unchanged; plot refused"
