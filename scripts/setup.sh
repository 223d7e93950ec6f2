#!/usr/bin/env bash
# Idempotent set-up for a fresh machine: Debian packages, the .venv with pinned Python
# packages, and the pinned npm tools. Each step does nothing when it is already current.
# Usage: scripts/setup.sh [system|venv|node|blender|all] (blender: for `make test` only, not in all)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

setup_system() {
  local missing=()
  while read -r pkg; do
    [[ -z "$pkg" || "$pkg" == \#* ]] && continue
    # Node.js may come from another source than Debian's package: accept any working one.
    if [[ "$pkg" == nodejs ]] && command -v node >/dev/null; then continue; fi
    if [[ "$pkg" == npm ]] && command -v npm >/dev/null; then continue; fi
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
  done < scripts/apt-packages.txt
  if ((${#missing[@]})); then
    echo "setup: installing Debian packages: ${missing[*]}"
    local sudo=""; [[ $(id -u) -ne 0 ]] && sudo=sudo
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
  fi
}

setup_venv() {
  local stamp=.venv/.requirements.sha256
  local want; want=$(sha256sum requirements.txt | cut -d' ' -f1)
  if [[ -f $stamp && "$(cat $stamp)" == "$want" ]]; then return; fi
  echo "setup: creating .venv with the pinned Python packages"
  [[ -x .venv/bin/python ]] || python3 -m venv .venv
  .venv/bin/python -m pip install -q --disable-pip-version-check -r requirements.txt
  # Development install: `pipeline/` on sys.path (the extension module is built into it)
  # and the `meshik` command.
  local site; site=$(.venv/bin/python -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')
  echo "$root/pipeline" > "$site/meshik-dev.pth"
  # The guard keeps processes started by multiprocessing's spawn (Dask's workers) from running it again.
  cat > .venv/bin/meshik <<PY
#!$root/.venv/bin/python
import sys
from meshik.cli import main
if __name__ == "__main__":
    sys.exit(main())
PY
  chmod +x .venv/bin/meshik
  echo "$want" > $stamp
}

setup_node() {
  [[ -f package.json ]] || return 0
  local stamp=node_modules/.package-lock.sha256
  local want; want=$(sha256sum package-lock.json | cut -d' ' -f1)
  if [[ -f $stamp && "$(cat $stamp)" == "$want" ]]; then return; fi
  echo "setup: installing pinned npm tools"
  npm ci --silent --no-audit --no-fund >/dev/null
  echo "$want" > $stamp
}

# Blender's Python module (bpy, about 1 GB, built for Python 3.11) in a venv of its own, for the tests
# that import our .glb files with Blender's own glTF importer (tests/python/test_glb_blender.py).
BPY_VERSION=5.0.1
setup_blender() {
  local stamp=.venv-blender/.bpy-version
  if [[ -f $stamp && "$(cat $stamp)" == "$BPY_VERSION" ]]; then return; fi
  echo "setup: creating .venv-blender with bpy $BPY_VERSION (about 1 GB)"
  [[ -x .venv-blender/bin/python ]] || python3.11 -m venv .venv-blender
  .venv-blender/bin/python -m pip install -q --disable-pip-version-check "bpy==$BPY_VERSION"
  echo "$BPY_VERSION" > $stamp
}

case "${1:-all}" in
  system) setup_system ;;
  venv) setup_venv ;;
  node) setup_node ;;
  blender) setup_blender ;;
  all) setup_system; setup_venv; setup_node ;;
  *) echo "usage: $0 [system|venv|node|blender|all]" >&2; exit 2 ;;
esac
