#!/usr/bin/env bash
# Under pipefail: pipes into an early reader (reported: on one line, and continued on the next
# after | or \), and the forms the rule allows.
set -euo pipefail
ldd /bin/sh | grep -q libc
out=$(ldd /bin/sh)
grep -q libc <<<"$out" || true
ldd /bin/sh | grep -c libc
# ldd /bin/sh | head -1 (a comment)
ldd /bin/sh |
  grep -qF libc
ldd /bin/sh \
  | head -1
ldd /bin/sh ||
  grep -q libc /dev/null
