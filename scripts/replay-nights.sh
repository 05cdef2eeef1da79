#!/usr/bin/env bash
# Replays `renderaudit watch` night by night along a stretch of Mesa's history: NIGHTS commits
# evenly spaced on the first-parent line FIRST..LAST are, one after the other, the head of the
# branch `replay` of MESA (a git clone of Mesa), which a second clone follows as its upstream;
# each night runs `renderaudit watch` on that clone, as cron would. No person chooses anything
# after the stretch: the loop flags the night a change enters and names its commit.
#
#   scripts/replay-nights.sh MESA FIRST LAST NIGHTS EXPERIMENT STATE [watch options...]
#   e.g. scripts/replay-nights.sh ~/mesa a07fa6516b0~150 a07fa6516b0~-150 10 \
#          experiments/watch-llvmpipe.toml outputs/replay
# (REV~-N is not git syntax: FIRST and LAST are commits; docs/nightly-audit.md shows the run.)
set -euo pipefail
mesa=$(cd "${1:?MESA}" && pwd)
first=${2:?FIRST}
last=${3:?LAST}
nights=${4:?NIGHTS}
experiment=${5:?EXPERIMENT}
state=${6:?STATE}
shift 6
ra=${RENDERAUDIT:-$(dirname "$0")/../build/renderaudit}

mapfile -t line < <(git -C "$mesa" rev-list --first-parent --reverse "$first..$last")
[ ${#line[@]} -ge "$nights" ] || { echo "replay: only ${#line[@]} commits in $first..$last" >&2; exit 2; }
watched="$state/mesa"
mkdir -p "$state"
git -C "$mesa" branch -f replay "${line[0]}"
if [ ! -d "$watched/.git" ]; then
  git clone -q --no-checkout --branch replay "$mesa" "$watched"
  # A clone lacking a few large blobs (docs/driver-builds.md) is read through the same sparse
  # checkout as MESA.
  if [ -f "$mesa/.git/info/sparse-checkout" ]; then
    git -C "$watched" sparse-checkout init --no-cone
    cp "$mesa/.git/info/sparse-checkout" "$watched/.git/info/sparse-checkout"
  fi
  git -C "$watched" checkout -q replay 2>/dev/null || true
fi
# A replay run again goes on after the last night its state folder watched.
last=$(sed -n 's/.*"commit": "\([0-9a-f]*\)".*/\1/p' "$state/watch.json" 2>/dev/null || true)
for ((n = 0; n < nights; n++)); do
  i=$(( (${#line[@]} - 1) * n / (nights - 1) ))
  if [ -n "$last" ] && git -C "$mesa" merge-base --is-ancestor "${line[$i]}" "$last"; then
    echo "replay: night $((n + 1)) of $nights: $(git -C "$mesa" log -1 --format=%h "${line[$i]}") watched before"
    continue
  fi
  git -C "$mesa" branch -f replay "${line[$i]}"
  echo "replay: night $((n + 1)) of $nights: $(git -C "$mesa" log -1 --format='%h %s' "${line[$i]}")"
  set +e
  "$ra" watch "$watched" --experiment "$experiment" --state "$state" "$@"
  echo "replay: night $((n + 1)) exit $?"
  set -e
done
"$ra" history --db "$state/history.sqlite" --last "$nights" | sed -n '1,/audits, the last/p'
