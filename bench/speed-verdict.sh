#!/usr/bin/env bash
# How honest is `audit --speed` on this machine? A/A comparisons (one driver drawn as two
# platforms of one run; one experiment run twice) counted for false "faster" / "slower" verdicts,
# and llvmpipe made slower on purpose (the faulty platform on osmesa-llvmpipe with [faults]
# slowdown = F) counted for how often each kind and view group is found "slower".
#
# Usage: bench/speed-verdict.sh BUILD_DIR OUT_DIR [AUDITS (20)] [SLOWDOWNS ("0.05 0.1 0.2")]
#        [SIZES ("25 100")]
# Prints markdown tables; every audit's audit.json stays in OUT_DIR. About 40 minutes on the
# 2-core build machine at the defaults.
set -euo pipefail
build=${1:?usage: bench/speed-verdict.sh BUILD_DIR OUT_DIR [AUDITS] [SLOWDOWNS] [SIZES]}
out=${2:?usage: bench/speed-verdict.sh BUILD_DIR OUT_DIR [AUDITS] [SLOWDOWNS] [SIZES]}
audits=${3:-20}
slowdowns=${4:-0.05 0.1 0.2}
sizes=${5:-25 100}
bin=$(realpath "$build")/renderaudit
mkdir -p "$out"
out=$(realpath "$out")

# One build folder per slowdown (s0: timed, not slowed), all drawing with osmesa-llvmpipe.
platforms='"faulty", "faulty@s0"'
builds=""
for f in 0 $slowdowns; do
  mkdir -p "$out/s$f"
  printf '[faults]\nbase = "osmesa-llvmpipe"\nslowdown = %s\n' "$f" > "$out/s$f/faults.toml"
  [[ $f == 0 ]] || platforms+=", \"faulty@s$f\""
  builds+="[builds.\"s$f\"]"$'\n'"dir = \"$out/s$f\""$'\n'
done
# The nist2008 views with one orientation: four view groups of one view each.
views=$'[views]\norientations = 1\nfov_deg = [30, 150]\nwindows = [128, 907]\nnear = 0.01\nfar = 10.0\n'
prims=$'[primitives]\npoints = 100\nlines = 100\ntriangles = 100\n'
faults=$'[faults]\nbase = "osmesa-llvmpipe"\nslowdown = 0\n'
printf 'seed = 2008\nplatforms = [%s]\n%s%s%s%s' "$platforms" "$views" "$prims" "$faults" \
  "$builds" > "$out/between.toml"
printf 'seed = 2008\nplatforms = ["osmesa-llvmpipe"]\n%s%s' "$views" "$prims" > "$out/runs.toml"

echo "speed-verdict: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), $(date -u +%FT%TZ)"
"$bin" run "$out/between.toml" --out "$out/between" --jobs 2 --quiet > /dev/null

audit() {  # audit ARGS... : one audit, its audit.json kept under the name given by --out
  "$bin" audit "$@" --speed --no-history --brief > /dev/null 2>&1 || true
}
started=$(date +%s)
for ((i = 1; i <= audits; i++)); do
  audit "$out/between" --between faulty faulty@s0 --out "$out/aa-between/$i"
  for n in $sizes; do
    for f in $slowdowns; do
      audit "$out/between" --between faulty "faulty@s$f" --speed-primitives "$n" \
        --out "$out/slow-$f-n$n/$i"
    done
  done
  # A/A of separate runs: this round's run against the previous round's.
  "$bin" run "$out/runs.toml" --out "$out/runs/$i" --jobs 2 --quiet > /dev/null
  ((i == 1)) || audit "$out/runs/$((i - 1))" "$out/runs/$i" --out "$out/aa-runs/$i"
  echo "speed-verdict: round $i of $audits done ($(( $(date +%s) - started )) s)" >&2
done
# One more run so that the separate-run A/A also has AUDITS audits.
"$bin" run "$out/runs.toml" --out "$out/runs/$((audits + 1))" --jobs 2 --quiet > /dev/null
audit "$out/runs/$audits" "$out/runs/$((audits + 1))" --out "$out/aa-runs/$((audits + 1))"

/usr/bin/python3 - "$out" "$slowdowns" "$sizes" <<'EOF'
import glob, json, os, sys
out, slowdowns, sizes = sys.argv[1], sys.argv[2].split(), sys.argv[3].split()

def load(name):
    rows = []
    for path in sorted(glob.glob(os.path.join(out, name, "*", "audit.json"))):
        rows.append(json.load(open(path))["speed"])
    return rows

print("\n| A/A comparison | audits | group verdicts | faster | slower | unknown | audits with any faster or slower |")
print("| --- | ---: | ---: | ---: | ---: | ---: | ---: |")
for name, label in (("aa-between", "one build as two platforms (--between)"), ("aa-runs", "two runs of one experiment")):
    audits = load(name)
    groups = [g for a in audits for g in a]
    count = lambda v: sum(g["verdict"] == v for g in groups)
    bad = sum(any(g["verdict"] in ("faster", "slower") for g in a) for a in audits)
    print(f"| {label} | {len(audits)} | {len(groups)} | {count('faster')} | {count('slower')} | {count('unknown')} | {bad} |")

print("\n| slowdown | primitives per group | audits | groups found slower in >= 95% of audits | least often found (group: share) | faster (wrong way) |")
print("| ---: | ---: | ---: | ---: | --- | ---: |")
for n in sizes:
    for f in slowdowns:
        audits = load(f"slow-{f}-n{n}")
        if not audits:
            continue
        share = {}
        wrong = 0
        for a in audits:
            for g in a:
                key = f"{g['kind']} {g['group']}"
                share.setdefault(key, 0)
                share[key] += g["verdict"] == "slower"
                wrong += g["verdict"] == "faster"
        ok = sum(v >= 0.95 * len(audits) for v in share.values())
        worst = min(share, key=share.get)
        print(f"| {float(f):.0%} | {n} | {len(audits)} | {ok} of {len(share)} | {worst}: {share[worst]}/{len(audits)} | {wrong} |")
EOF
