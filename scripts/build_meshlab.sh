#!/usr/bin/env bash
# Builds MeshLab 2025.07 from the source scripts/fetch_meshlab_source.sh provides, with the Debian
# -dev packages (Qt5, GLEW, Eigen) and only the plugins a minimal GUI needs (io_base, filter_select,
# edit_select). One build tree per precision under third_party/, reused between runs.
#
# Usage: scripts/build_meshlab.sh PRECISION WHAT
#   PRECISION  float (MeshLab releases and distribution packages) or double (as pymeshlab)
#   WHAT       common: only libmeshlab-common.so (what the float plugin links against);
#              prints its path on the last line
#              gui:    the whole GUI, installed into third_party/meshlab-gui-PRECISION;
#              prints the installed executable on the last line
# Env: JOBS (default 2), MESHLAB_SOURCE_DIR (see fetch_meshlab_source.sh)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
precision=${1:?usage: $0 float|double common|gui}
what=${2:?usage: $0 float|double common|gui}
jobs=${JOBS:-2}

case $precision in
  float) double_scalar=OFF ;;
  double) double_scalar=ON ;;
  *) echo "build_meshlab: precision must be float or double, not '$precision'" >&2; exit 2 ;;
esac

src=$("$root/scripts/fetch_meshlab_source.sh" | tail -n 1)
build=$root/third_party/meshlab-build-$precision
prefix=$root/third_party/meshlab-gui-$precision

if [[ ! -f $build/build.ninja ]]; then
  cmake -S "$src" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_INSTALL_PREFIX="$prefix" \
    -DMESHLAB_BUILD_WITH_DOUBLE_SCALAR=$double_scalar \
    -DMESHLAB_ALLOW_OPTIONAL_EXTERNAL_LIBRARIES=OFF \
    -DMESHLAB_ALLOW_BUNDLED_SOURCE_GLEW=OFF -DMESHLAB_ALLOW_SYSTEM_GLEW=ON \
    -DVCG_ALLOW_BUNDLED_EIGEN=OFF \
    "-DMESHLAB_PLUGINS=meshlabplugins/io_base;meshlabplugins/filter_select;meshlabplugins/edit_select" \
    >"$build.configure.log" 2>&1 || { cat "$build.configure.log" >&2; exit 1; }
fi

case $what in
  common)
    nice -n 10 cmake --build "$build" -j "$jobs" --target meshlab-common >&2
    find "$build" -name 'libmeshlab-common.so' -print -quit
    ;;
  gui)
    nice -n 10 cmake --build "$build" -j "$jobs" >&2
    # --prefix: a build tree copied from another checkout keeps that checkout's prefix in its cache.
    cmake --install "$build" --prefix "$prefix" >/dev/null
    echo "$prefix/bin/meshlab"
    ;;
  *) echo "build_meshlab: WHAT must be common or gui, not '$what'" >&2; exit 2 ;;
esac
