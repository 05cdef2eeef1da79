# Sourced by the bisection and watch tests: stand-in driver builds and git histories whose commits name
# them, so that `renderaudit bisect` runs with real drawing and no compiler. The drivers are the
# `faulty` test platform over the installed Mesa llvmpipe (osmesa-llvmpipe): `faulty@BUILD` draws
# with BUILD/faults.toml, so
#   good:    llvmpipe as it is;
#   bad:     llvmpipe with one wild pixel far from every primitive (wild_pixel);
#   neither: the wild pixels of even primitives only (half like each side);
#   broken:  the build command fails.
# Sourced after test-common.sh (or with $build, the build folder, and $t, a temporary folder, set);
# defines $ra, $cmd, forty_lines_toml, make_run, make_history HISTORY WORD..., c HISTORY N (the
# commit "cN"), make_upstream CLONE WORD... and commit WORD... (a branch a watch follows). A test
# that sources it stops at its first failure: set -e, and fail MESSAGE says it and exits 1.
set -e
ra="$build/renderaudit"
fail() { echo "$(basename "$0"): FAIL: $*" >&2; exit 1; }
# A failed build keeps its log in the temporary folder: the test's own, removed with it.
mkdir -p "$t/tmp"
export TMPDIR="$t/tmp"

mkdir -p "$t/drivers"/{good,bad,neither}
printf '[faults]\nbase = "osmesa-llvmpipe"\n' > "$t/drivers/good/faults.toml"
printf '[faults]\nbase = "osmesa-llvmpipe"\nwild_pixel = [%s]\n' "$(seq -s, 0 39)" > "$t/drivers/bad/faults.toml"
printf '[faults]\nbase = "osmesa-llvmpipe"\nwild_pixel = [%s]\n' "$(seq -s, 0 2 39)" > "$t/drivers/neither/faults.toml"

# forty_lines_toml NAME PLATFORMS [MORE]: the tests' experiment (40 lines of one 128 x 128 view,
# seed 7) on stdout, PLATFORMS the TOML list's inside, MORE TOML lines after it.
forty_lines_toml() {
  printf 'name = "%s"\nseed = 7\nplatforms = [%s]\n' "$1" "$2"
  printf '[views]\norientations = 1\nfov_deg = [30]\nwindows = [128]\nnear = 0.01\nfar = 10.0\n'
  printf '[primitives]\npoints = 0\nlines = 40\ntriangles = 0\n'
  [ -z "${3:-}" ] || printf '%s\n' "$3"
}

# A run of 40 lines drawn by the good and the bad driver: every line differs by its wild pixel.
make_run() {
  forty_lines_toml bisect-test '"faulty@good", "faulty@bad"' \
    "[builds.good]"$'\n'"dir = \"$t/drivers/good\""$'\n'"[builds.bad]"$'\n'"dir = \"$t/drivers/bad\"" \
    > "$t/exp.toml"
  "$ra" run "$t/exp.toml" --out "$t/run" --jobs 2 >/dev/null 2>"$t/run.log" || { cat "$t/run.log"; fail "run"; }
}

# make_history DIR WORD...: commit cI names the I-th driver word.
make_history() {
  local g=$1 i=0 d
  shift
  mkdir -p "$g"
  git -C "$g" init -q -b main
  git -C "$g" config user.email test@example.invalid
  git -C "$g" config user.name test
  for d in "$@"; do
    echo "$d" > "$g/driver"
    git -C "$g" add driver
    git -C "$g" commit -q --allow-empty -m "c$i: $d"
    i=$((i + 1))
  done
}
c() { git -C "$1" rev-parse ":/^c$2:"; }

# make_upstream CLONE WORD...: $up, a history of WORD... (make_history), and CLONE, a clone whose
# branch follows it as a watched Mesa tree follows upstream; commit WORD... adds the next commits
# upstream (cN: WORD, installing WORD's driver).
make_upstream() {
  local clone=$1
  shift
  up="$t/upstream"
  make_history "$up" "$@"
  git clone -q "$up" "$clone"
}
commit() {
  local d n
  for d in "$@"; do
    n=$(git -C "$up" rev-list --count HEAD)
    echo "$d" > "$up/driver"
    git -C "$up" commit -q --allow-empty -am "c$n: $d"
  done
}
# The build command: installs the checked-out commit's driver (SLEEP seconds first, if set).
cmd='sleep ${RA_TEST_SLEEP:-0}; d=$(cat driver); [ "$d" != broken ] || { echo "cannot build $d" >&2; exit 1; }; cp '"$t"'/drivers/$d/faults.toml "$RENDERAUDIT_BUILD_PREFIX"/'
export RENDERAUDIT_BUILD_CACHE="$t/cache"
