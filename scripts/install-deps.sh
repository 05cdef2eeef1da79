#!/usr/bin/env bash
# Installs the Debian 12 packages renderaudit needs, or says exactly which are missing.
# Usage: scripts/install-deps.sh            (build + run + test dependencies)
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libgl-dev             # GL headers (the GL functions are fetched from each platform's driver)
  libosmesa6            # OSMesa, loaded at run time: the osmesa-* platforms (the embedded default)
  libegl-dev            # EGL headers and libEGL (glvnd), loaded at run time: the egl-* platforms
  libopengl-dev         # libOpenGL (glvnd): the C reproducers of `renderaudit reproduce` link it
  libegl-mesa0          # Mesa's EGL: surfaceless egl-llvmpipe, egl-softpipe (and egl-zink with
                        #   the Vulkan packages below)
  libvulkan1            # the Vulkan loader, opened at run time: the vk-* platforms (and egl-zink)
  mesa-vulkan-drivers   # lavapipe, Mesa's Vulkan driver on llvmpipe: vk-lavapipe (and egl-zink)
  libvulkan-dev         # Vulkan headers (the loader's functions are fetched at run time)
  libvulkan-volk-dev    # volk: fetches the Vulkan functions from the loader it opens
  vulkan-validationlayers  # tests: Khronos validation over the Vulkan paths (api_validation)
  glslang-tools         # glslangValidator: the shaders compiled to SPIR-V at build time, embedded
  libvtk9-dev           # VTK: figures (charts to PNG and PDF)
  libopenimageio-dev    # OpenImageIO: PNG of single primitives (renderaudit show)
  fonts-dejavu-core     # DejaVu Sans: the legend text of those PNGs
  libboost-math-dev     # Boost.Math: t, F, normal distributions for the statistics
  libtomlplusplus-dev   # toml++: experiment files
  libcli11-dev          # CLI11: the command line
  nlohmann-json3-dev    # nlohmann/json: manifest and JSON output
  libmeshoptimizer-dev  # meshoptimizer: vertex-cache analysis and simplification
  libeigen3-dev         # Eigen: QR / SVD least squares (stats regress, timing models)
  libsqlite3-dev        # SQLite: audit history database
  libzstd-dev           # zstd: compressed records files (records/*.csv.zst)
  libgtest-dev          # GoogleTest: the test suite
  meson ninja-build     # tests: the incremental build folder of Mesa builds, on a tiny project
  xvfb                  # a private X server for VTK on machines with no display
  libgl1-mesa-dri       # Mesa's GLX driver inside Xvfb (VTK's OpenGL context for figures)
  libx11-dev            # Xlib: checking that a DISPLAY answers before VTK opens it
  libcairo2-dev         # cairo: the report's text and table pages (PDF surface)
  fonts-dejavu-core     # DejaVu Sans / Mono: the report's fonts (embedded in the PDF)
  fonts-urw-base35      # Nimbus Sans: Helvetica metrics, so poppler shows the figure PDFs' text right
  poppler-utils         # pdfunite / pdftotext: assembling and checking the PDF report
  python3-scipy         # independent reference values in tests (/usr/bin/python3)
  python3-pandas        # tests: pandas reads a compressed records file (/usr/bin/python3)
  python3-zstandard     #   ... through python3-zstandard, as a user's notebook would
  libopenmpi-dev        # Debian's VTK CMake config requires MPI's C bindings to resolve
)

missing=()
for p in "${packages[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$p" 2>/dev/null || true)
  [[ $status == *"install ok installed"* ]] || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "renderaudit: installing missing Debian packages: ${missing[*]}" >&2
if [ "$(id -u)" -eq 0 ]; then
  SUDO=""
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  SUDO="sudo"
else
  echo "renderaudit: cannot install as a normal user. Run as root:" >&2
  echo "  apt-get update && apt-get install -y ${missing[*]}" >&2
  exit 1
fi
export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq
if ! $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null; then
  echo "renderaudit: apt-get failed. Install by hand: apt-get install ${missing[*]}" >&2
  exit 1
fi
