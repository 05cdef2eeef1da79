#!/usr/bin/env bash
# Under pipefail: one pipe into an early reader (reported), and the forms the rule allows.
set -euo pipefail
ldd /bin/sh | grep -q libc
out=$(ldd /bin/sh)
grep -q libc <<<"$out" || true
ldd /bin/sh | grep -c libc
# ldd /bin/sh | head -1 (a comment)
