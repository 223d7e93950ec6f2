# Sourced by scripts/gui_check.sh (uses its start_meshlab, wait_log, shot, step, fail, ...): drives
# what artists reach for in "MeshIK: Drag to Pose" on the sample, with one screenshot per feature
# (<name>_group, _undo, _rotate, _keyframes, _mirror, _mirror_view), and checks:
#   undo returns the exact earlier pose (bit for bit) and redo the exact later one;
#   a turned group (R, typed 30 degrees, Return) is saved as a "rotate" target that reproduces the
#   tool's pose in meshik.Solver (within 1e-6 of the diagonal);
#   two keyframes (F) posed by `meshik pose` equal the tool's poses frame by frame;
#   Esc during a drag puts the pose back exactly (and leaves the tool running);
#   on the wings (drive_mirror_check): with Mirror X, a handle on the plane, a wing's group and its
#   mirrored group, dragged and turned, give a pose symmetric about x = 0 within 1e-6 of the
#   diagonal; the plane through a picked vertex goes through the clicked vertex; the view's vertical
#   plane of the front view is x = 0 and gives a symmetric pose too (drive_mirror_view_check).

# Saves the posed layer through the tool's dialog (key P) to $1; prints the logged weights.
artist_save_pose() {
  xdotool mousemove 300 120 key p
  wait_window "Save pose" 10 >/dev/null || { shot "${artist}_no_pose_dialog"; fail "$artist: no \"Save pose\" dialog"; }
  sleep 0.5
  xdotool key ctrl+a
  xdotool type --delay 5 "$1"
  xdotool key Return
  local line
  line=$(wait_log "MeshIK drag: saved the pose to $1 " 30) || fail "$artist: the pose was not saved to $1"
  sed -E 's/.*\(weights \[(.*)\]\).*/\1/' <<<"$line"
}

# Saves the constraint file through the tool's dialog (key S) to $1.
artist_save_constraints() {
  xdotool mousemove 300 120 key s
  wait_window "Save constraint file" 10 >/dev/null || fail "$artist: no \"Save constraint file\" dialog"
  sleep 0.5
  xdotool key ctrl+a
  xdotool type --delay 5 "$1"
  xdotool key Return
  wait_log "MeshIK drag: saved [0-9]+ handles in [0-9]+ groups, [0-9]+ frames to $1" 10 >/dev/null ||
    fail "$artist: the constraint file $1 was not saved (see $meshlab_log)"
}

# Presses the keys $2... with the mouse at $artist_cursor (default: an empty spot of the 3D view)
# and waits for a log line matching $1 (prints it).
artist_keys() {
  local pattern=$1
  shift
  xdotool mousemove ${artist_cursor:-560 520}
  sleep 0.2
  xdotool key "$@"
  wait_log "$pattern" 20 || { shot "${artist}_no_$(date +%s)"; fail "$artist: keys $* gave no log line \"$pattern\" (see $meshlab_log)"; }
}

# Turns group 2 by typed degrees about the view axis: R with the cursor at screen point $1 $2 (over
# the group), then the digit keys $3... and Return; waits for each step's log line.
artist_turn_group_2() {
  artist_cursor="$1 $2"
  artist_keys "MeshIK drag: turning group 2" r >/dev/null
  artist_cursor=
  xdotool key "${@:3}"
  sleep 0.5
  artist_keys "MeshIK drag: turn group 2 about the view axis" Return >/dev/null
  sleep 0.5
}

# Drags from screen point $1 $2 in $3 moves of $4 $5 pixels each; $6: "release" or "escape" (Esc before
# the button goes up).
artist_drag() {
  local i
  xdotool mousemove "$1" "$2"
  sleep 0.3
  xdotool mousedown 1
  sleep 0.3
  for i in $(seq "$3"); do
    xdotool mousemove_relative -- "$4" "$5"
    sleep 0.05
  done
  sleep 0.3
  if [[ $6 == escape ]]; then xdotool key Escape; sleep 0.5; fi
  xdotool mouseup 1
}

# Starts MeshLab on the project $1 and the tool; the three mesh points go to artist_points.
artist_start() {
  start_meshlab "$1" "$out/meshlab_$artist.log"
  xdotool mousemove 200 990 click 1
  sleep 0.3
  xdotool key alt+e
  sleep 0.7
  xdotool key Up Return
  wait_window "MeshIK: Drag to Pose" 20 >/dev/null || fail "$artist: the tool's dock did not open"
  wait_log "MeshIK drag: rest layer .* [0-9]+ example layers" 60 >/dev/null || fail "$artist: the tool did not start"
  sleep 1
  shot "${artist}_started"
  artist_points=$("$root/.venv/bin/python" "$root/scripts/gui_check_drag.py" points "$out/${artist}_started.png" 5 1120 70 870) ||
    fail "$artist: could not find the mesh in the screenshot"
}

# Clicks screen point $1 $2 (with modifier $3 when given) and waits for handle number $4.
artist_click() {
  if [[ -n $3 ]]; then xdotool mousemove "$1" "$2" keydown "$3" click 1 keyup "$3"; else xdotool mousemove "$1" "$2" click 1; fi
  wait_log "MeshIK drag: $4 handles, the new one vertex" 5
}

drive_artist_features() {
  artist=$1
  local check=("$root/.venv/bin/python" "$root/scripts/gui_check_drag.py") p1 p3 line x y dx weights
  step "$artist: groups, undo/redo, Esc, rotation, keyframes (the tool in MeshLab)"
  artist_start "$2"
  p1=$(sed -n 1p <<<"$artist_points")
  p3=$(sed -n 3p <<<"$artist_points")
  artist_save_pose "$out/${artist}_rest.ply" >/dev/null
  # Group 1: one handle at one end; group 2: two handles at the other end (ctrl+click beside).
  line=$(artist_click $p1 "" 1) || fail "$artist: clicking $p1 added no handle"
  read -r x y < <(sed -E 's/.* at screen ([0-9-]+) ([0-9-]+).*/\1 \2/' <<<"$line")
  line=$(artist_click $p3 "" 2) || fail "$artist: clicking $p3 added no handle"
  local second
  second=$(sed -E 's/.* at screen ([0-9-]+) ([0-9-]+).*/\1 \2/' <<<"$line")
  read -r px py <<<"$p3"
  for dx in 14 -14 24 -24 34; do
    artist_click $((px + dx)) "$py" ctrl 3 >/dev/null && break
  done
  grep -qE "MeshIK drag: 3 handles, .*\(group 2\)" "$meshlab_log" || fail "$artist: ctrl+click did not add a handle to group 2"
  shot "${artist}_group"

  # A drag of group 1 (36 pixels: a small one, so that `meshik pose`, which starts each file from
  # the rest weights, finds the tool's local minimum below), undone and redone: the exact poses.
  artist_drag "$x" "$y" 12 0 -3 release
  wait_log "MeshIK drag: drag group 1 " 30 >/dev/null || fail "$artist: the drag was not recorded as an undo step"
  artist_save_pose "$out/${artist}_drag.ply" >/dev/null
  artist_keys "MeshIK drag: undo drag group 1" ctrl+z >/dev/null
  shot "${artist}_undo"
  artist_save_pose "$out/${artist}_undo.ply" >/dev/null
  "${check[@]}" same "$out/${artist}_undo.ply" "$out/${artist}_rest.ply" || fail "$artist: undo did not restore the exact pose"
  artist_keys "MeshIK drag: redo drag group 1" ctrl+shift+z >/dev/null
  artist_save_pose "$out/${artist}_redo.ply" >/dev/null
  "${check[@]}" same "$out/${artist}_redo.ply" "$out/${artist}_drag.ply" || fail "$artist: redo did not restore the exact pose"

  # Esc in the middle of a drag: back to the pose before it, the tool still running.
  artist_drag "$x" "$((y - 36))" 10 6 0 escape
  wait_log "MeshIK drag: drag cancelled" 20 >/dev/null || fail "$artist: Esc did not cancel the drag"
  artist_save_pose "$out/${artist}_escape.ply" >/dev/null
  "${check[@]}" same "$out/${artist}_escape.ply" "$out/${artist}_drag.ply" || fail "$artist: Esc did not restore the pose"

  # Turn group 2 (R over its handle) by 30 degrees about the view axis (typed), saved as a "rotate" target.
  artist_turn_group_2 $second 3 0
  shot "${artist}_rotate"
  weights=$(artist_save_pose "$out/${artist}_rotate.ply")
  artist_save_constraints "$out/${artist}_rotate.json"
  grep -q '"rotate"' "$out/${artist}_rotate.json" || fail "$artist: the turned group is not saved as a rotate target"
  "${check[@]}" check "$out/${artist}_rotate.json" "$out/${artist}_rotate.ply" "$weights" >"$out/${artist}_rotate_check.txt" 2>&1 ||
    { cat "$out/${artist}_rotate_check.txt" >&2; fail "$artist: the rotate target does not reproduce the tool's pose"; }
  step "$artist: rotate: $(tail -n 1 "$out/${artist}_rotate_check.txt")"

  # Two keyframes: the turned pose, then 25 degrees more about Z; `meshik pose` replays them.
  artist_keys "MeshIK drag: frame 0001 added" f >/dev/null
  artist_keys "MeshIK drag: turning group 2" r >/dev/null  # the last group turned
  xdotool key z 2 5
  sleep 0.5
  artist_keys "MeshIK drag: turn group 2 about Z" Return >/dev/null
  artist_keys "MeshIK drag: frame 0002 added" f >/dev/null
  sleep 0.5
  shot "${artist}_keyframes"
  artist_save_pose "$out/${artist}_frame2.ply" >/dev/null
  artist_save_constraints "$out/${artist}_keyframes.json"
  "${check[@]}" frames "$out/${artist}_keyframes.json" "$out/${artist}_replay" "$out/${artist}_rotate.ply" \
    "$out/${artist}_frame2.ply" >"$out/${artist}_frames_check.txt" 2>&1 ||
    { cat "$out/${artist}_frames_check.txt" >&2; fail "$artist: meshik pose does not replay the keyframes"; }
  step "$artist: keyframes: $(tail -n 1 "$out/${artist}_frames_check.txt")"
  ! grep -q "LOG: 1 MeshIK drag" "$meshlab_log" || fail "$artist: the tool warned: $(grep "LOG: 1 MeshIK drag" "$meshlab_log" | head -n 1)"
  stop_meshlab
}

# With a Mirror option on the wings: clicks the body (the second mesh point: a handle on the plane,
# its own mirror) and a wing (the first: a handle whose partner, in group 3, lies across the plane);
# $1: the plane's name in the log ("X", "view's vertical"). Sets wing_x, wing_y: the wing handle's
# screen point.
mirror_body_and_wing() {
  local line
  artist_click $(sed -n 2p <<<"$artist_points") "" 1 >/dev/null || fail "$artist: clicking the body added no handle"
  wait_log "MeshIK drag: vertex [0-9]+ lies on the $1 plane: its own mirror" 5 >/dev/null ||
    fail "$artist: the handle on the plane is not its own mirror (see $meshlab_log)"
  line=$(artist_click $(sed -n 1p <<<"$artist_points") "" 2) || fail "$artist: clicking the wing added no handle"
  read -r wing_x wing_y < <(sed -E 's/.* at screen ([0-9-]+) ([0-9-]+).*/\1 \2/' <<<"$line")
  wait_log "MeshIK drag: vertex [0-9]+ mirrors vertex [0-9]+ across the $1 plane \\(group 3\\)" 5 >/dev/null ||
    fail "$artist: no mirror partner for the wing handle (see $meshlab_log)"
}

# Saves the tool's pose to $out/$artist.ply and checks it symmetric about x = 0 (1e-6 of the diagonal).
check_symmetric_pose() {
  artist_save_pose "$out/${artist}.ply" >/dev/null
  "$root/.venv/bin/python" "$root/scripts/gui_check_drag.py" symmetric "$out/${artist}.ply" 0 \
    >"$out/${artist}_check.txt" 2>&1 ||
    { cat "$out/${artist}_check.txt" >&2; fail "$artist: the mirrored pose is not symmetric"; }
  step "$artist: $(tail -n 1 "$out/${artist}_check.txt")"
}

# On the wings sample (exactly symmetric about x = 0; its project $2): Mirror X through the centre,
# a fixed handle on the plane, a group of two handles near one wing tip (click, ctrl+click) whose
# partners form one mirrored group, a drag and a typed turn of that group; the pose is symmetric
# about x = 0 within 1e-6 of the diagonal. Then the plane through a picked vertex: the next click
# places it through that vertex (logged: x = 0 on the body).
drive_mirror_check() {
  artist=$1
  local line px py dx
  step "$artist: mirror (the tool in MeshLab, on the symmetric wings)"
  artist_start "$2"
  artist_keys "MeshIK drag: mirror: X \\(plane x = centre\\)" m >/dev/null
  mirror_body_and_wing X
  read -r px py <<<"$(sed -n 1p <<<"$artist_points")"
  for dx in 30 40 50 -30; do
    artist_click $((px + dx)) "$py" ctrl 4 >/dev/null && break
  done
  sleep 0.5
  (($(grep -cE "MeshIK drag: vertex [0-9]+ mirrors vertex [0-9]+ across the X plane \\(group 3\\)" "$meshlab_log") == 2)) &&
    grep -qE "MeshIK drag: 4 handles, .*\\(group 2\\)" "$meshlab_log" ||
    fail "$artist: ctrl+click did not grow the wing's group and its mirrored group (see $meshlab_log)"
  shot "${artist}_handles"
  artist_drag "$wing_x" "$wing_y" 12 2 -5 release
  wait_log "MeshIK drag: drag group 2 " 30 >/dev/null || fail "$artist: the drag was not recorded"
  artist_turn_group_2 "$wing_x" $((wing_y - 60)) 2 5
  shot "$artist"
  check_symmetric_pose

  # The plane through a picked vertex (M three more times: X through a picked vertex): the click on
  # the body places it (x = 0 there), the next click on a wing gets its partner across it.
  artist_keys "MeshIK drag: mirror: X \\(plane through a picked vertex\\)" m m m >/dev/null
  read -r px py <<<"$(sed -n 2p <<<"$artist_points")"
  xdotool mousemove "$px" $((py + 25)) click 1  # beside the body's handle, on the plane x = 0
  line=$(wait_log "MeshIK drag: mirror plane x = .*, through vertex [0-9]+" 5) ||
    fail "$artist: the click did not place the mirror plane (see $meshlab_log)"
  "$root/.venv/bin/python" -c "import sys; sys.exit(abs(float(sys.argv[1])) > 1e-9)" \
    "$(sed -E 's/.*mirror plane x = ([^,]*),.*/\1/' <<<"$line")" || fail "$artist: the picked plane is not x = 0: $line"
  shot "${artist}_picked_plane"
  ! grep -q "LOG: 1 MeshIK drag" "$meshlab_log" || fail "$artist: the tool warned: $(grep "LOG: 1 MeshIK drag" "$meshlab_log" | head -n 1)"
  stop_meshlab
  drive_mirror_view_check "${artist}_view" "$2"
}

# The view's vertical plane (M seven times from off: through the centre), in a fresh session on the
# wings ($2) seen from the front: the logged plane normal is x (to 1e-9), a handle on the body is its
# own mirror, a wing handle gets its partner, and a drag gives a pose symmetric about x = 0.
drive_mirror_view_check() {
  artist=$1
  local line
  step "$artist: mirror across the view's vertical plane (the tool in MeshLab, on the wings)"
  artist_start "$2"
  artist_keys "MeshIK drag: mirror: View's vertical plane \\(through the centre\\)" m m m m m m m >/dev/null
  line=$(wait_log "MeshIK drag: mirror plane normal \\(.*\\): the view's vertical plane" 5) ||
    fail "$artist: choosing the view's vertical plane logged no plane (see $meshlab_log)"
  "$root/.venv/bin/python" -c "import sys; n = [float(v) for v in sys.argv[1].split(',')]; \
sys.exit(abs(abs(n[0]) - 1) > 1e-9 or abs(n[1]) > 1e-9 or abs(n[2]) > 1e-9)" \
    "$(sed -E 's/.*plane normal \(([^)]*)\).*/\1/' <<<"$line")" || fail "$artist: the front view's plane is not x: $line"
  mirror_body_and_wing "view's vertical"
  artist_drag "$wing_x" "$wing_y" 12 2 -5 release
  wait_log "MeshIK drag: drag group 2 " 30 >/dev/null || fail "$artist: the drag was not recorded"
  sleep 0.5
  shot "$artist"
  check_symmetric_pose
  ! grep -q "LOG: 1 MeshIK drag" "$meshlab_log" || fail "$artist: the tool warned: $(grep "LOG: 1 MeshIK drag" "$meshlab_log" | head -n 1)"
  stop_meshlab
}
