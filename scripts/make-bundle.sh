#!/usr/bin/env bash
# The lean runner as a relocatable bundle for GPU and cluster nodes (docs/operations.md): the lean
# program and the worker, the shared libraries they need that are not part of every Linux (glibc
# is taken from the node; libstdc++ and libgcc_s ride along in lib/compat/ for nodes whose own are
# older), the Vulkan loader and GLVND's libEGL as fallbacks, the default experiments, and a
# launcher. The node's own GL and Vulkan drivers are used: the program opens them at run time, so
# no driver is bundled.
#
# Usage: make-bundle.sh PROGRAM WORKER OUT_DIR   (make bundle: build-lean/renderaudit-lean ...)
# Writes OUT_DIR/renderaudit-lean-VERSION-ARCH.tar.gz and prints its path.
set -euo pipefail
if [ $# -ne 3 ]; then
  echo "usage: $0 PROGRAM WORKER OUT_DIR" >&2
  exit 2
fi
program=$1 worker=$2 out=$3
root=$(cd "$(dirname "$0")/.." && pwd)
for f in "$program" "$worker"; do
  [ -x "$f" ] || { echo "make-bundle: $f: no such program (build it: make lean)" >&2; exit 2; }
done
version=$("$program" --version | awk '{print $2}')
name=renderaudit-lean-$version-$(uname -m)
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
dir=$stage/$name
mkdir -p "$dir/bin" "$dir/libexec" "$dir/lib/compat" "$dir/experiments/papers"
install -m 755 "$program" "$dir/libexec/renderaudit"
install -m 755 "$worker" "$dir/libexec/renderaudit-worker"

# glibc's own libraries come from the node (they must match its loader); the C++ runtime is kept
# apart, used only where the node's is older than the one the program was built with.
is_glibc() {
  case $1 in
    linux-vdso.so.*|ld-linux*|libc.so.*|libm.so.*|libdl.so.*|libpthread.so.*|librt.so.*|libresolv.so.*) return 0;;
  esac
  return 1
}
for bin in "$dir/libexec/renderaudit" "$dir/libexec/renderaudit-worker"; do
  ldd "$bin" | awk '/=> \// {print $1, $3}' | while read -r soname path; do
    is_glibc "$soname" && continue
    [ -e "$dir/lib/$soname" ] || [ -e "$dir/lib/compat/$soname" ] && continue  # the other binary's
    case $soname in
      libstdc++.so.*|libgcc_s.so.*) cp -L "$path" "$dir/lib/compat/$soname";;
      *) cp -L "$path" "$dir/lib/$soname";;
    esac
  done
done

# The vendor-neutral loaders the program opens at run time (libvulkan.so.1, GLVND's libEGL.so.1):
# a GPU node often has the vendor's driver (its Vulkan ICD and EGL vendor library, e.g. mounted
# into a container) without them. The launcher uses them only where the node has none.
mkdir -p "$dir/lib/loaders/vulkan" "$dir/lib/loaders/egl"
find_lib() { /sbin/ldconfig -p | awk -v n="$1" '$1 == n && /x86-64|64bit|AArch64/ {print $NF; exit}'; }
for pair in libvulkan.so.1:vulkan libEGL.so.1:egl libGLdispatch.so.0:egl; do
  so=${pair%%:*}
  path=$(find_lib "$so" || true)  # awk leaves ldconfig early (SIGPIPE)
  if [ -n "$path" ]; then cp -L "$path" "$dir/lib/loaders/${pair#*:}/$so"
  else echo "make-bundle: $so not on this machine: the bundle carries no fallback for it" >&2; fi
done

cat > "$dir/bin/renderaudit" <<'LAUNCHER'
#!/bin/sh
# renderaudit (lean build). Uses the node's C++ runtime when it is new enough, else the bundled
# one; and the bundled Vulkan loader and GLVND libEGL only where the node has none of its own.
here=$(cd "$(dirname "$0")/.." && pwd)
has_lib() {  # the node's dynamic linker finds this library
  grep -q "^[[:space:]]*$1 " <<LIBS && return 0
$(/sbin/ldconfig -p 2>/dev/null || ldconfig -p 2>/dev/null)
LIBS
  for d in $(echo "${LD_LIBRARY_PATH:-}" | tr ':' ' '); do [ -e "$d/$1" ] && return 0; done
  return 1
}
if ! "$here/libexec/renderaudit" --version > /dev/null 2>&1; then
  LD_LIBRARY_PATH="$here/lib/compat${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}"
fi
has_lib libvulkan.so.1 || LD_LIBRARY_PATH="${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$here/lib/loaders/vulkan"
has_lib libEGL.so.1 || LD_LIBRARY_PATH="${LD_LIBRARY_PATH:+$LD_LIBRARY_PATH:}$here/lib/loaders/egl"
export LD_LIBRARY_PATH
exec "$here/libexec/renderaudit" "$@"
LAUNCHER
chmod 755 "$dir/bin/renderaudit"
cp "$root"/experiments/quick*.toml "$root"/experiments/nist2008.toml "$root"/experiments/nightly.toml \
  "$dir/experiments/"
cp "$root"/experiments/papers/*.toml "$dir/experiments/papers/"
cat > "$dir/README.txt" <<README
renderaudit $version, the lean build (no VTK, OpenImageIO, cairo or poppler), for GPU and cluster
nodes. Unpack anywhere and run bin/renderaudit; it draws with the node's own GL and Vulkan drivers.

  bin/renderaudit platforms                    what this node can draw with
  bin/renderaudit run experiments/quick-vk-device.toml --out RUN
  bin/renderaudit status RUN; bin/renderaudit audit RUN --baseline BASE

Figures and the report need the full build: copy RUN to a machine with it and run
renderaudit report RUN there. Needs glibc @GLIBC@ or newer. See docs/operations.md of the project.
README
# The newest glibc symbol version any of it needs: the oldest glibc it runs on.
glibc=$(objdump -T "$dir"/libexec/* "$dir"/lib/*.so* 2>/dev/null | grep -o 'GLIBC_[0-9.]*' |
  sort -t_ -k2 -V | tail -1 | sed 's/GLIBC_//')
sed -i "s/@GLIBC@/${glibc:-2.36}/" "$dir/README.txt"
mkdir -p "$out"
tarball=$(cd "$out" && pwd)/$name.tar.gz
tar -C "$stage" -czf "$tarball" "$name"
echo "$tarball"
