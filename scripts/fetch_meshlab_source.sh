#!/usr/bin/env bash
# Fetches MeshLab 2025.07's source (Debian's orig tarball of the `meshlab` source package, which
# still contains vcglib), verifies its pinned sha256 and unpacks it under third_party/.
# Idempotent: does nothing when the unpacked tree is already there.
#
# The tarball is fetched with apt itself from the Debian mirror this machine's apt already uses:
# a private apt configuration (its own sources list with one `deb-src ... sid main` entry and its
# own lists folder) so the system's sources never see sid. The mirror's URI is read from the
# system's apt sources, so no host name is written here.
#
# Usage: scripts/fetch_meshlab_source.sh        prints the source folder on its last line
# Env:   MESHLAB_SOURCE_DIR  a MeshLab checkout to use instead (must contain src/common)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

readonly VERSION=2025.07
readonly DEB_VERSION=2025.07~dfsg-4
readonly TARBALL=meshlab_2025.07~dfsg.orig.tar.xz
readonly SHA256=d22c98d362f2a284e481af8dbfc272b2222f5b9c67b3cf8bec57d1c3161886f4
readonly dest=$root/third_party/meshlab-$VERSION

# Prints the URI of the first Debian (non-security) mirror in the system's apt sources,
# in either the one-line (sources.list) or the deb822 (*.sources) format.
debian_mirror_uri() {
  local files=(/etc/apt/sources.list /etc/apt/sources.list.d/*.list /etc/apt/sources.list.d/*.sources)
  local f
  for f in "${files[@]}"; do
    [[ -r $f ]] || continue
    awk '
      /^[[:space:]]*#/ { next }
      /^deb(-src)?[[:space:]]/ { for (i = 2; i <= NF; i++) if ($i ~ /^[a-z+]+:\/\//) { print $i; break } }
      /^URIs:/ { for (i = 2; i <= NF; i++) print $i }
    ' "$f"
  done | grep -E '/debian/?$' | head -n 1
}

# Downloads the orig tarball into $1 with apt's ordinary client and a private configuration.
download_tarball() {
  local work=$1 mirror
  mirror=$(debian_mirror_uri)
  if [[ -z $mirror ]]; then
    echo "fetch_meshlab_source: no Debian mirror found in the apt sources; set MESHLAB_SOURCE_DIR" >&2
    return 1
  fi
  mkdir -p "$work/lists/partial" "$work/cache/archives/partial"
  echo "deb-src ${mirror%/} sid main" > "$work/sources.list"
  # Everything apt writes (lists, caches) stays in $work: the system's apt state is untouched.
  local opts=(-o "Dir::Etc::SourceList=$work/sources.list" -o Dir::Etc::SourceParts=/dev/null
              -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache" -o Debug::NoLocking=1
              -o APT::Sandbox::User=root)
  apt-get "${opts[@]}" update -qq
  # apt downloads and checks the orig tarball against the Sources index, then fails on the
  # .dsc / .debian.tar.xz the mirror no longer has: the tarball alone is what we need.
  (cd "$work" && apt-get "${opts[@]}" source --download-only "meshlab=$DEB_VERSION" >/dev/null 2>&1) || true
  [[ -f "$work/$TARBALL" ]] || { echo "fetch_meshlab_source: apt did not download $TARBALL" >&2; return 1; }
}

main() {
  if [[ -n ${MESHLAB_SOURCE_DIR:-} ]]; then
    [[ -d $MESHLAB_SOURCE_DIR/src/common ]] || {
      echo "fetch_meshlab_source: MESHLAB_SOURCE_DIR=$MESHLAB_SOURCE_DIR has no src/common" >&2; exit 1; }
    echo "$MESHLAB_SOURCE_DIR"; return
  fi
  if [[ -f $dest/.complete ]]; then echo "$dest"; return; fi

  local work=$root/third_party/download
  mkdir -p "$work"
  [[ -f "$work/$TARBALL" ]] && echo "$SHA256  $work/$TARBALL" | sha256sum -c --quiet - 2>/dev/null \
    || { rm -f "$work/$TARBALL"; download_tarball "$work"; }
  echo "$SHA256  $work/$TARBALL" | sha256sum -c --quiet - || {
    echo "fetch_meshlab_source: $TARBALL does not have the pinned sha256 $SHA256" >&2; exit 1; }

  rm -rf "$dest" "$dest.tmp"
  mkdir -p "$dest.tmp"
  tar -xJf "$work/$TARBALL" -C "$dest.tmp" --strip-components=1
  [[ -d $dest.tmp/src/common && -d $dest.tmp/src/vcglib/vcg ]] || {
    echo "fetch_meshlab_source: unexpected tarball layout (no src/common or src/vcglib)" >&2; exit 1; }
  touch "$dest.tmp/.complete"
  mv "$dest.tmp" "$dest"
  echo "$dest"
}

main "$@"
