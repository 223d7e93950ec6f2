#!/usr/bin/env bash
# `make gui-check`: checks the MeshIK plugin inside a real MeshLab 2025.07 GUI under Xvfb.
#
# Builds a minimal MeshLab GUI of the given precision from the same source the plugin compiles
# against (scripts/build_meshlab.sh, reused after the first time), builds the plugin of that
# precision, installs it into a fresh per-user MeshLab plugin folder, opens a sample character
# (rest mesh and example poses as layers, from a MeshLab project file) and drives the GUI with
# xdotool. Fails loudly unless: no "Error while loading plugins." dialog appears, MeshLab keeps
# running, both MeshIK filters open from the Filters menu, and the pose filter runs on the sample
# (handles and targets from a frame of the sample's constraint file) and writes its LOG: lines.
# Screenshots for a person to look at go to gui_check_output/<precision>/.
#
# Usage: scripts/gui_check.sh [float|double]
# Env:   BUILD (CMake build folder, default build), SAMPLE (sample_meshes/<set>, default limb),
#        FRAME (constraint-file frame, default the middle one), JOBS (default 2)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
precision=${1:-float}
build=${BUILD:-$root/build}
sample=${SAMPLE:-limb}
out=$root/gui_check_output/$precision

case $precision in
  float) plugin_target=filter_meshik_float; settings=MeshLab_64bit_fp; version=2025.07 ;;
  double) plugin_target=filter_meshik; settings=MeshLab_64bit_dp; version=2025.07d ;;
  *) echo "gui_check: precision must be float or double, not '$precision'" >&2; exit 2 ;;
esac

fail() { echo "gui-check ($precision): FAILED: $*" >&2; exit 1; }
step() { echo "gui-check ($precision): $*"; }

# --- What the check needs: X tools, the GUI, the plugin, the sample ---------------------------
install_gui_packages() {
  local packages=(xvfb xauth xdotool imagemagick x11-utils libgl1-mesa-dri) missing=() pkg
  for pkg in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed" || missing+=("$pkg")
  done
  ((${#missing[@]})) || return 0
  step "installing ${missing[*]}"
  local sudo=""; [[ $(id -u) -ne 0 ]] && sudo=sudo
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

install_gui_packages
step "building the MeshLab GUI (about 10 minutes the first time)"
meshlab=$("$root/scripts/build_meshlab.sh" "$precision" gui | tail -n 1)
[[ -x $meshlab ]] || fail "no MeshLab executable at $meshlab"
step "building the plugin ($plugin_target)"
cmake --build "$build" -j "${JOBS:-2}" --target "$plugin_target" >/dev/null || fail "the plugin did not build"
plugin=$build/plugin/$precision/libfilter_meshik.so
[[ -f $plugin ]] || fail "no plugin at $plugin"

sample_dir=$root/sample_meshes/$sample
constraints=$sample_dir/animation.json
[[ -f $sample_dir/rest.obj && -f $constraints ]] || fail "sample $sample_dir (rest.obj, animation.json) not found"
# The middle frame's name (frames without one are named by their 1-based number, "0001" ...).
middle_frame='import json, sys
frames = json.load(open(sys.argv[1]))["frames"]
middle = len(frames) // 2
print(frames[middle].get("name", "%04d" % (middle + 1)))'
frame=${FRAME:-$(python3 -c "$middle_frame" "$constraints")}

# --- A fresh MeshLab user: settings pre-seeded, our plugin in its per-user plugin folder ---------
rm -rf "$out"
mkdir -p "$out/config/VCG" "$out/data/VCG/$settings/MeshLabExtraPlugins/$version" "$out/runtime"
chmod 700 "$out/runtime"
printf '[General]\ninformativeShown=true\n' > "$out/config/VCG/$settings.conf"
cp "$plugin" "$out/data/VCG/$settings/MeshLabExtraPlugins/$version/"

# The project: the example poses as hidden layers, then the rest mesh (visible, the current layer).
project=$out/sample.mlp
{
  echo '<!DOCTYPE MeshLabDocument>'
  echo '<MeshLabProject>'
  echo ' <MeshGroup>'
  for example in "$sample_dir"/example_*.obj; do
    echo "  <MLMesh label=\"$(basename "$example" .obj)\" filename=\"$example\" visible=\"0\"/>"
  done
  echo "  <MLMesh label=\"rest\" filename=\"$sample_dir/rest.obj\" visible=\"1\"/>"
  echo ' </MeshGroup>'
  echo '</MeshLabProject>'
} > "$project"
num_layers=$(grep -c '<MLMesh' "$project")

# --- Xvfb and MeshLab ------------------------------------------------------------------------
display_number=90
while [[ -e /tmp/.X11-unix/X$display_number || -e /tmp/.X$display_number-lock ]]; do
  display_number=$((display_number + 1))
done
export DISPLAY=:$display_number
pids=()
cleanup() { local pid; for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done; }
trap cleanup EXIT
Xvfb "$DISPLAY" -screen 0 1600x1000x24 -nolisten tcp >"$out/xvfb.log" 2>&1 &
xvfb_pid=$!
pids+=("$xvfb_pid")
for _ in $(seq 50); do xdpyinfo >/dev/null 2>&1 && break; sleep 0.1; done
xdpyinfo >/dev/null 2>&1 && kill -0 "$xvfb_pid" 2>/dev/null || fail "Xvfb did not start on $DISPLAY (see $out/xvfb.log)"

step "starting $meshlab with $sample ($num_layers layers)"
LIBGL_ALWAYS_SOFTWARE=1 XDG_CONFIG_HOME=$out/config XDG_DATA_HOME=$out/data XDG_RUNTIME_DIR=$out/runtime \
  "$meshlab" "$project" >"$out/meshlab.log" 2>&1 &
meshlab_pid=$!
pids=("$meshlab_pid" "${pids[@]}")

# Prints the id of the first window whose name matches $1, waiting up to $2 seconds.
wait_window() {
  local deadline=$((SECONDS + $2)) id
  while ((SECONDS < deadline)); do
    id=$(xdotool search --name "$1" 2>/dev/null | head -n 1) && [[ -n $id ]] && { echo "$id"; return 0; }
    sleep 0.25
  done
  return 1
}
alive() {
  kill -0 "$xvfb_pid" 2>/dev/null || fail "Xvfb on $DISPLAY exited (see $out/xvfb.log)"
  kill -0 "$meshlab_pid" 2>/dev/null || fail "MeshLab is no longer running (see $out/meshlab.log)"
}
no_dialog() {
  ! xdotool search --name "$1" >/dev/null 2>&1 || { shot "error_dialog"; fail "MeshLab shows the dialog \"$1\""; }
}
shot() { import -window root "$out/$1.png"; }
shot_window() {  # $1 file name, $2 window
  eval "$(xdotool getwindowgeometry --shell "$2")"
  import -window root -crop "${WIDTH}x${HEIGHT}+${X}+${Y}" "$out/$1.png"
}

# A plugin that fails to load is reported only in a modal dialog, shown before the main window.
deadline=$((SECONDS + 60))
until main_window=$(xdotool search --name "MeshLab $version" 2>/dev/null | head -n 1) && [[ -n $main_window ]]; do
  no_dialog "Error while loading plugins"
  alive
  ((SECONDS < deadline)) || { shot "no_window"; fail "no MeshLab window within 60 s (see $out/meshlab.log)"; }
  sleep 0.25
done
sleep 3
no_dialog "Error while loading plugins"
alive
# Full screen, so that the layer list and the dialogs land where the steps below expect them.
for _ in $(seq 20); do
  xdotool windowmove "$main_window" 0 0 windowsize "$main_window" 1600 1000
  sleep 0.5
  eval "$(xdotool getwindowgeometry --shell "$main_window")"
  [[ $WIDTH == 1600 && $HEIGHT == 1000 ]] && break
done
[[ $WIDTH == 1600 && $HEIGHT == 1000 ]] || fail "could not resize the MeshLab window to 1600x1000"
shot 01_started

# Opens Filters > "Smoothing, Fairing and Deformation" and its item number $1 (1: Blend, 2: Pose);
# saves the menu as screenshot $2 when given. Keyboard navigation skips disabled items.
open_meshik_filter() {
  xdotool mousemove 200 990 click 1  # the status bar: focuses the main window, touches nothing
  sleep 0.3
  xdotool key alt+l
  sleep 0.5
  xdotool key Home  # the first enabled item, "Show current filter script"
  local i
  for i in $(seq 7); do xdotool key Down; sleep 0.05; done
  xdotool key Right
  sleep 0.5
  for ((i = 1; i < $1; i++)); do xdotool key Down; sleep 0.05; done
  [[ -z ${2:-} ]] || shot "$2"
  xdotool key Return
}

# The filter dialog's buttons sit at fixed offsets from its lower corners.
click_dialog_button() {  # $1 dialog window, $2 Default|Close|Apply
  eval "$(xdotool getwindowgeometry --shell "$1")"
  case $2 in
    Default) xdotool mousemove $((X + 115)) $((Y + HEIGHT - 54)) click 1 ;;
    Close) xdotool mousemove $((X + 115)) $((Y + HEIGHT - 23)) click 1 ;;
    Apply) xdotool mousemove $((X + WIDTH - 116)) $((Y + HEIGHT - 23)) click 1 ;;
  esac
  sleep 0.5
}

step "opening MeshIK: Blend Examples from the Filters menu"
open_meshik_filter 1
blend_dialog=$(wait_window "MeshIK: Blend Examples" 10) ||
  { shot "blend_missing"; fail "the Filters menu has no \"MeshIK: Blend Examples\""; }
sleep 0.5
shot_window 02_blend_dialog "$blend_dialog"
click_dialog_button "$blend_dialog" Close
alive

step "opening MeshIK: Pose from Examples from the Filters menu"
open_meshik_filter 2 03_filters_menu
pose_dialog=$(wait_window "MeshIK: Pose from Examples" 10) ||
  { shot "pose_missing"; fail "the Filters menu has no \"MeshIK: Pose from Examples\""; }
sleep 0.5
# From the Default button, Tab walks the parameters from "Example layers" on (6 steps); select
# "Constraint file" in "Handle targets from", then type the file and the frame.
click_dialog_button "$pose_dialog" Default
for _ in $(seq 8); do xdotool key Tab; done
xdotool type --delay 20 "C"
xdotool key Tab Tab
xdotool type --delay 5 "$constraints"
xdotool key Tab Tab ctrl+a
xdotool type --delay 20 "$frame"
sleep 0.5
shot_window 04_pose_dialog "$pose_dialog"

step "applying the pose filter (frame $frame of $(basename "$constraints"))"
click_dialog_button "$pose_dialog" Apply
deadline=$((SECONDS + 120))
until grep -q "LOG: .*MeshIK pose: written to" "$out/meshlab.log"; do
  alive
  no_dialog "Filter Failure"
  ((SECONDS < deadline)) || { shot "pose_timeout"; fail "no MeshIK LOG: lines within 120 s (see $out/meshlab.log)"; }
  sleep 0.5
done
grep -q "LOG: .*MeshIK pose: .* handles from frame \"$frame\"" "$out/meshlab.log" ||
  fail "the pose did not take its targets from frame $frame of the constraint file (see $out/meshlab.log)"
no_dialog "Filter Failure"
alive
click_dialog_button "$pose_dialog" Close

# Hide the rest layer (its eye icon in the layer list) so the pose shows alone.
xdotool mousemove 1160 $((114 + 31 * (num_layers - 1))) click 1
sleep 1
shot 05_posed
alive

step "log lines:"
grep "LOG: .*MeshIK" "$out/meshlab.log" | sed 's/^/  /'
step "PASSED; screenshots in $out"
