#!/usr/bin/env bash
# The numbers and names the README and docs/ quote that a command can regenerate: the test count
# against `ctest -N`, README's command table against `renderaudit --help`, and with RUN_DIR the
# quick experiment's figure count against `renderaudit plot RUN_DIR --list`. Fails naming file and
# line. The rules live in docs_check.py (standard library only).
# Usage: docs-check.sh BUILD_DIR [RUN_DIR]   (`make docs-check`; ctest docs_check without RUN_DIR)
set -euo pipefail
exec python3 "$(dirname "$0")/docs_check.py" "$@"
