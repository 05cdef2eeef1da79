#!/usr/bin/env bash
# Installs the Debian 12 packages that `renderaudit builds build` and `renderaudit bisect` need to
# compile Mesa from source (software drivers only), or says exactly which are missing.
# Not part of `make`: only driver developers building Mesa need it (docs/driver-builds.md).
# Usage: scripts/install-mesa-build-deps.sh [--check]   (--check: say what is missing, install nothing)
set -euo pipefail

check_only=0
[ "${1:-}" = "--check" ] && check_only=1

# Debian 12's meson is 1.0; Mesa since 2024 needs >= 1.4 (main of 2025-12 needs 1.7): meson comes
# from bookworm-backports, the only package taken from there (backports are never preferred).
backports_packages=(meson)
packages=(
  ninja-build pkg-config git
  llvm-15-dev           # LLVM 15: llvmpipe's JIT; one LLVM for every build, so the compiler is no cause
  bison flex            # Mesa's GLSL and other parsers
  python3-mako          # Mesa's code generators (run with /usr/bin/python3)
  python3-yaml python3-packaging python3-ply
  libelf-dev libdrm-dev zlib1g-dev libexpat1-dev libzstd-dev libudev-dev
  glslang-tools         # lavapipe's shaders (Debian 12's 12.0 is too old for Mesa >= 24: said)
  ccache                # rebuilds of the same sources in seconds (bisection steps, retries)
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ $status == *"install ok installed"* ]] || missing+=("$p")
done
meson_ok=0
if command -v meson >/dev/null 2>&1; then
  v=$(meson --version 2>/dev/null || echo 0)
  dpkg --compare-versions "$v" ge 1.4 && meson_ok=1
fi

if [ ${#missing[@]} -eq 0 ] && [ $meson_ok -eq 1 ]; then
  echo "renderaudit: the Mesa build packages are installed (meson $(meson --version))"
  exit 0
fi
if [ $check_only -eq 1 ]; then
  echo "renderaudit: missing for building Mesa: ${missing[*]} $([ $meson_ok -eq 0 ] && echo 'meson>=1.4 (bookworm-backports)')" >&2
  exit 1
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "renderaudit: cannot install as a normal user. Run as root:" >&2
  echo "  scripts/install-mesa-build-deps.sh" >&2
  exit 1
fi

export DEBIAN_FRONTEND=noninteractive
sources=/etc/apt/sources.list.d/renderaudit-bookworm-backports.sources
if [ $meson_ok -eq 0 ] && ! grep -rqs 'bookworm-backports' /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "renderaudit: adding Debian's bookworm-backports suite ($sources) for meson" >&2
  cat > "$sources" <<'EOF'
Types: deb
URIs: http://deb.debian.org/debian
Suites: bookworm-backports
Components: main
Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg
EOF
fi
apt-get update -qq
if [ ${#missing[@]} -gt 0 ]; then
  echo "renderaudit: installing ${missing[*]}" >&2
  apt-get install -y -qq "${missing[@]}" >/dev/null
fi
if [ $meson_ok -eq 0 ]; then
  echo "renderaudit: installing meson from bookworm-backports" >&2
  apt-get install -y -qq -t bookworm-backports "${backports_packages[@]}" >/dev/null
fi
echo "renderaudit: the Mesa build packages are installed (meson $(meson --version), $(llvm-config-15 --version | sed 's/^/LLVM /'))"
