#!/usr/bin/env bash
# The layout rules of the source tree (docs/development.md, "Source layout"): includes follow the
# layer order of CMakeLists.txt (RA_LAYERS), no function over 150 lines outside tests, namespaces
# follow folders, and the links between the project's libraries match their includes. The rules
# live in check_layout.py (standard library only). Usage: check-layout.sh [ROOT]
set -euo pipefail
exec python3 "$(dirname "$0")/check_layout.py" "$@"
