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
# Then the edit tool "MeshIK: Drag to Pose" (edit plugin edit_meshik), on the sample and, with
# ../shared/data present, on the horse and the elephant (rest + 4 examples each): started from
# the Edit menu by keyboard, 3 handles added by clicking on the mesh, one dragged in 24 mouse-move
# steps, the constraint file and the posed layer saved through the tool's file dialogs; checked: the drag's last move is
# where the cursor ended (Qt folds moves, none is lost otherwise), a solve logged per move (or folded into a later one), the layer moved, the saved pose equals meshik.Solver on the saved file's
# handles and targets (scripts/gui_check_drag.py), MeshLab answers the Edit menu afterwards, no
# error dialog or warning. The drag latency (mouse-move event to updated GL buffers, median and
# max, solve and overhead medians) is printed. On the sample, scripts/gui_check_artist.sh then drives
# handle groups, undo/redo, Esc, rotation and keyframes, and on the symmetric sample wings the
# mirror (see there), with screenshots named *_group, *_undo, *_rotate, *_keyframes, *_mirror. Screenshots for a person to look at go to
# gui_check_output/<precision>/.
#
# Usage: scripts/gui_check.sh [float|double]
# Env:   BUILD (CMake build folder, default build), SAMPLE (sample_meshes/<set>, default limb),
#        FRAME (constraint-file frame, default the middle one), JOBS (default 2),
#        MESHIK_SHARED_DATA (the real example sets, default ../shared/data)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
precision=${1:-float}
build=${BUILD:-$root/build}
sample=${SAMPLE:-limb}
out=$root/gui_check_output/$precision

case $precision in
  float) plugin_target=filter_meshik_float; edit_target=edit_meshik_float; settings=MeshLab_64bit_fp; version=2025.07 ;;
  double) plugin_target=filter_meshik; edit_target=edit_meshik; settings=MeshLab_64bit_dp; version=2025.07d ;;
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
step "building the plugins ($plugin_target, $edit_target)"
cmake --build "$build" -j "${JOBS:-2}" --target "$plugin_target" "$edit_target" >/dev/null || fail "the plugins did not build"
plugin=$build/plugin/$precision/libfilter_meshik.so
edit_plugin=$build/plugin/$precision/libedit_meshik.so
[[ -f $plugin ]] || fail "no plugin at $plugin"
[[ -f $edit_plugin ]] || fail "no plugin at $edit_plugin"

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
cp "$plugin" "$edit_plugin" "$out/data/VCG/$settings/MeshLabExtraPlugins/$version/"

# Writes the MeshLab project $1: the example poses (files $3 ...) as hidden layers, then the rest
# mesh (file $2; visible, the current layer).
write_project() {
  local project=$1 rest=$2 example
  shift 2
  {
    echo '<!DOCTYPE MeshLabDocument>'
    echo '<MeshLabProject>'
    echo ' <MeshGroup>'
    for example in "$@"; do
      echo "  <MLMesh label=\"$(basename "$example" .obj)\" filename=\"$example\" visible=\"0\"/>"
    done
    echo "  <MLMesh label=\"rest\" filename=\"$rest\" visible=\"1\"/>"
    echo ' </MeshGroup>'
    echo '</MeshLabProject>'
  } > "$project"
}
project=$out/sample.mlp
write_project "$project" "$sample_dir/rest.obj" "$sample_dir"/example_*.obj
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
Xvfb "$DISPLAY" -screen 0 1600x1400x24 -nolisten tcp -noreset >"$out/xvfb.log" 2>&1 &
xvfb_pid=$!
pids+=("$xvfb_pid")
for _ in $(seq 50); do xdpyinfo >/dev/null 2>&1 && break; sleep 0.1; done
xdpyinfo >/dev/null 2>&1 && kill -0 "$xvfb_pid" 2>/dev/null || fail "Xvfb did not start on $DISPLAY (see $out/xvfb.log)"


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
  kill -0 "$meshlab_pid" 2>/dev/null || fail "MeshLab is no longer running (see $meshlab_log)"
}
no_dialog() {
  ! xdotool search --name "$1" >/dev/null 2>&1 || { shot "error_dialog"; fail "MeshLab shows the dialog \"$1\""; }
}
shot() { import -window root "$out/$1.png"; }
shot_window() {  # $1 file name, $2 window
  eval "$(xdotool getwindowgeometry --shell "$2")"
  import -window root -crop "${WIDTH}x${HEIGHT}+${X}+${Y}" "$out/$1.png"
}

# Starts MeshLab on the project $1 with its output in the log $2 (sets meshlab_pid, meshlab_log and
# main_window), and waits until its window is up, full screen, and no plugin failed to load.
start_meshlab() {
  meshlab_log=$2
  LIBGL_ALWAYS_SOFTWARE=1 XDG_CONFIG_HOME=$out/config XDG_DATA_HOME=$out/data XDG_RUNTIME_DIR=$out/runtime \
    "$meshlab" "$1" >"$meshlab_log" 2>&1 &
  meshlab_pid=$!
  pids=("$meshlab_pid" "${pids[@]}")
  # A plugin that fails to load is reported only in a modal dialog, shown before the main window.
  local deadline=$((SECONDS + 60))
  until main_window=$(xdotool search --name "MeshLab $version" 2>/dev/null | head -n 1) && [[ -n $main_window ]]; do
    no_dialog "Error while loading plugins"
    alive
    ((SECONDS < deadline)) || { shot "no_window"; fail "no MeshLab window within 60 s (see $meshlab_log)"; }
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
}

# Ends the running MeshLab (the GUI check's own process).
stop_meshlab() {
  kill "$meshlab_pid" 2>/dev/null || true
  wait "$meshlab_pid" 2>/dev/null || true
}

step "starting $meshlab with $sample ($num_layers layers)"
start_meshlab "$project" "$out/meshlab.log"
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

# The filter dialog's buttons sit at fixed offsets from its lower corners. The pose filter's dialog
# is taller than the main window (centred on it, its buttons fell below the screen): it is moved
# to the top of the screen, which is taller than the main window for it.
click_dialog_button() {  # $1 dialog window, $2 Default|Close|Apply
  eval "$(xdotool getwindowgeometry --shell "$1")"
  if ((Y < 0 || Y + HEIGHT > 1400)); then
    xdotool windowmove "$1" "$X" 0
    sleep 0.5
    eval "$(xdotool getwindowgeometry --shell "$1")"
  fi
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
stop_meshlab

# --- The edit tool "MeshIK: Drag to Pose" -------------------------------------------------------
# Waits up to $2 seconds for a line of the MeshLab log matching the extended regex $1; prints the last.
wait_log() {
  local deadline=$((SECONDS + $2))
  until grep -qE "$1" "$meshlab_log"; do
    alive
    ((SECONDS < deadline)) || return 1
    sleep 0.2
  done
  grep -E "$1" "$meshlab_log" | tail -n 1
}

# Drives the tool on the project $2 (screenshots and files named after $1).
drive_drag_tool() {
  local name=$1 line i
  step "$name: starting MeshLab and MeshIK: Drag to Pose from the Edit menu"
  start_meshlab "$2" "$out/meshlab_$name.log"
  xdotool mousemove 200 990 click 1  # the status bar: focuses the main window
  sleep 0.3
  xdotool key alt+e
  sleep 0.7
  shot "${name}_1_edit_menu"
  xdotool key Up Return  # up from the first item wraps to the last one: ours (the last plugin loaded)
  wait_window "MeshIK: Drag to Pose" 20 >/dev/null || { shot "${name}_no_dock"; fail "$name: the tool's dock did not open"; }
  wait_log "MeshIK drag: rest layer .* [0-9]+ example layers" 60 >/dev/null ||
    fail "$name: the tool did not read the example layers (see $meshlab_log)"
  sleep 1
  shot "${name}_2_tool_started"

  # Three points on the mesh (both ends and the middle of its longest screen axis), clicked one by one.
  local points
  points=$("$root/.venv/bin/python" "$root/scripts/gui_check_drag.py" points "$out/${name}_2_tool_started.png" 5 1120 70 870) ||
    fail "$name: could not find the mesh in the screenshot"
  local count=0 grab_x grab_y
  while read -r x y; do
    count=$((count + 1))
    xdotool mousemove "$x" "$y" click 1
    line=$(wait_log "MeshIK drag: $count handles, the new one vertex" 20) ||
      { shot "${name}_click_$count"; fail "$name: clicking the mesh at $x $y added no handle $count (see $meshlab_log)"; }
    read -r grab_x grab_y < <(sed -E 's/.* at screen ([0-9-]+) ([0-9-]+).*/\1 \2/' <<<"$line")
  done <<<"$points"
  shot "${name}_3_handles"

  step "$name: dragging the last handle (at $grab_x $grab_y) in 24 mouse moves"
  xdotool mousemove "$grab_x" "$grab_y"
  sleep 0.3
  xdotool mousedown 1
  sleep 0.3
  for i in $(seq 24); do
    xdotool mousemove_relative -- 0 -8
    if ((i == 12)); then shot "${name}_4_during_drag"; fi
    sleep 0.05
  done
  sleep 0.2
  xdotool mouseup 1
  local summary
  summary=$(wait_log "MeshIK drag: [0-9]+ moves, [0-9]+ solves" 30) || fail "$name: the drag logged no summary (see $meshlab_log)"
  sleep 0.5
  shot "${name}_5_after_drag"
  # No move is lost except by coalescing: Qt folds the moves queued while the GUI thread is busy
  # into the newest one (how many arrive depends on the load), so the tool's last move must be
  # where the cursor ended, 24 x 8 pixels above the grab; every move that reached the tool is
  # solved, or folded into a later request (coalesced); every solve is shown and logged, or
  # replaced by a newer one while the GUI thread was busy (superseded).
  local moves solves coalesced superseded last_x last_y logged
  read -r moves solves coalesced superseded last_x last_y < <(sed -E \
    's/.*: ([0-9]+) moves, ([0-9]+) solves \(([0-9]+) coalesced, ([0-9]+) superseded\), the last move at screen ([0-9-]+) ([0-9-]+);.*/\1 \2 \3 \4 \5 \6/' <<<"$summary")
  logged=$(grep -cE "MeshIK drag: solve [0-9]+ " "$meshlab_log")
  ((moves >= 1)) || fail "$name: no mouse move reached the tool"
  ((last_x == grab_x && last_y == grab_y - 192)) ||
    fail "$name: the drag's last move was at $last_x $last_y, the cursor ended at $grab_x $((grab_y - 192))"
  ((solves + coalesced == moves)) || fail "$name: $moves moves but $solves solves and $coalesced coalesced"
  ((logged + superseded == solves)) || fail "$name: $solves solves, $superseded superseded, but $logged solve lines logged"

  # Save the constraint file and the posed layer through the tool's dialogs (keys S and P).
  local constraints_out=$out/${name}_drag.json pose_out=$out/${name}_pose.ply dialog
  xdotool mousemove 300 120 key s
  dialog=$(wait_window "Save constraint file" 10) || { shot "${name}_no_save_dialog"; fail "$name: no \"Save constraint file\" dialog"; }
  sleep 0.5
  xdotool key ctrl+a
  xdotool type --delay 5 "$constraints_out"
  xdotool key Return
  wait_log "MeshIK drag: saved [0-9]+ handles in [0-9]+ groups, [0-9]+ frames to $constraints_out" 10 >/dev/null || fail "$name: the constraint file was not saved"
  xdotool mousemove 300 120 key p
  dialog=$(wait_window "Save pose" 10) || { shot "${name}_no_pose_dialog"; fail "$name: no \"Save pose\" dialog"; }
  sleep 0.5
  xdotool key ctrl+a
  xdotool type --delay 5 "$pose_out"
  xdotool key Return
  line=$(wait_log "MeshIK drag: saved the pose to $pose_out" 30) || fail "$name: the pose was not saved"
  local weights
  weights=$(sed -E 's/.*\(weights \[(.*)\]\).*/\1/' <<<"$line")

  # MeshLab still answers: the Edit menu opens and ends the tool (its dock closes).
  xdotool mousemove 200 990 click 1
  sleep 0.3
  xdotool key alt+e
  sleep 0.7
  shot "${name}_6_edit_menu_after"
  xdotool key Up Return
  local deadline=$((SECONDS + 10))
  while xdotool search --name "MeshIK: Drag to Pose" >/dev/null 2>&1; do
    ((SECONDS < deadline)) || fail "$name: the Edit menu did not end the tool"
    sleep 0.25
  done
  no_dialog "Filter Failure"
  alive
  ! grep -q "LOG: 1 MeshIK drag" "$meshlab_log" || fail "$name: the tool warned: $(grep "LOG: 1 MeshIK drag" "$meshlab_log" | head -n 1)"
  "$root/.venv/bin/python" "$root/scripts/gui_check_drag.py" check "$constraints_out" "$pose_out" "$weights" \
    >"$out/${name}_check.txt" 2>&1 || { cat "$out/${name}_check.txt" >&2; fail "$name: the saved pose is wrong"; }
  step "$name: $(tail -n 1 "$out/${name}_check.txt")"
  step "$name: $moves moves, $solves solves ($coalesced coalesced, $superseded superseded); latency (mouse move to updated GL buffers) $(sed -E 's/.*latency //' <<<"$summary")"
  stop_meshlab
}

drive_drag_tool "$sample" "$project"
source "$root/scripts/gui_check_artist.sh"
drive_artist_features "${sample}_artist" "$project"
wings=$root/sample_meshes/wings  # exactly symmetric about x = 0
write_project "$out/wings.mlp" "$wings/rest.obj" "$wings"/example_*.obj
drive_mirror_check wings_mirror "$out/wings.mlp"
shared_data=${MESHIK_SHARED_DATA:-$root/../shared/data}
for set in horse elephant; do  # the rest pose and 4 examples of each real set
  if [[ -f $shared_data/$set-poses/reference.obj ]]; then
    write_project "$out/$set.mlp" "$shared_data/$set-poses/reference.obj" "$shared_data/$set-poses"/{1,2,3,4}.obj
    drive_drag_tool "$set" "$out/$set.mlp"
  else
    step "no $set at $shared_data/$set-poses: skipped"
  fi
done
step "PASSED; screenshots in $out"
