"""Helpers of scripts/gui_check.sh for the tool "MeshIK: Drag to Pose" (run with the project's .venv).

    gui_check_drag.py points SCREENSHOT.png XMIN XMAX YMIN YMAX
        Prints three screen points "x y" on the mesh drawn in the screenshot, inside the box: near
        both ends and in the middle of the mesh along its longest screen axis (the third one is
        the end to drag). The mesh is what is drawn grey on MeshLab's blue background.
    gui_check_drag.py check CONSTRAINTS.json POSE.ply "W1, W2, ..."
        Checks the pose the tool saved: it moved away from the rest mesh, and it equals
        meshik.Solver on the saved file's handles and targets (warm-started from the tool's
        weights W, as the tool's last solve was) within 1e-6 of the bounding-box diagonal.
        Prints the numbers; exits 1 with the reason when a check fails.
    gui_check_drag.py same A.ply B.ply
        Checks that two saved poses have bit-identical vertices (undo, redo, Esc).
    gui_check_drag.py symmetric POSE.ply AXIS
        Checks that the pose is symmetric about the plane normal to AXIS (0, 1, 2) through its
        bounding-box centre: every vertex of its mirror image lies on a vertex of the pose within
        1e-6 of the diagonal.
    gui_check_drag.py frames CONSTRAINTS.json OUT POSE1.ply POSE2.ply ...
        Runs `meshik pose CONSTRAINTS.json --out OUT --format ply` and checks that frame i equals
        the tool's pose POSEi.ply within 1e-6 of the bounding-box diagonal.
"""
import subprocess
import sys

import numpy as np


def screenshot_pixels(path):
    """(height, width, 3) uint8 pixels of a PNG, through ImageMagick."""
    size = subprocess.run(["identify", "-format", "%w %h", path], check=True, capture_output=True, text=True).stdout
    width, height = map(int, size.split())
    raw = subprocess.run(["convert", path, "-depth", "8", "rgb:-"], check=True, capture_output=True).stdout
    return np.frombuffer(raw, dtype=np.uint8).reshape(height, width, 3)


def mesh_points(path, box):
    """Three (x, y) screen points well inside the grey mesh pixels within box = (x0, x1, y0, y1)."""
    x0, x1, y0, y1 = box
    rgb = screenshot_pixels(path)[y0:y1, x0:x1].astype(int)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    mask = (abs(r - g) < 14) & (abs(g - b) < 14) & (r > 80)
    inner = mask.copy()  # 4 pixels from any edge of the mesh's silhouette
    for shift in range(1, 5):
        inner[shift:, :] &= mask[:-shift, :]
        inner[:-shift, :] &= mask[shift:, :]
        inner[:, shift:] &= mask[:, :-shift]
        inner[:, :-shift] &= mask[:, shift:]
    ys, xs = np.nonzero(inner)
    if len(xs) < 200:
        raise SystemExit(f"gui_check_drag: no mesh found in {path} (only {len(xs)} grey pixels)")
    coords = np.column_stack([xs, ys]).astype(float)
    centre = coords.mean(axis=0)
    axis = np.linalg.svd(coords - centre, full_matrices=False)[2][0]
    along = (coords - centre) @ axis
    points = []
    for q in (0.04, 0.5, 0.96):
        t = np.quantile(along, q)
        near = np.abs(along - t) < 3
        middle = np.median(coords[near], axis=0)
        best = coords[near][np.argmin(np.linalg.norm(coords[near] - middle, axis=1))]
        points.append((int(best[0]) + x0, int(best[1]) + y0))
    return points


def check_pose(constraints_path, pose_path, weights_text):
    import meshik
    import pymeshlab
    from meshik.inputs import constraints

    def load(path):
        ms = pymeshlab.MeshSet()
        ms.load_new_mesh(str(path))
        return ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()

    loaded = constraints.load(constraints_path)
    rest, faces = load(loaded.rest)
    examples = [load(path)[0] for path in loaded.examples]
    resolved = constraints.resolve(loaded, rest)
    weights = np.array([float(w) for w in weights_text.split(",")])
    solver = meshik.Solver(rest, faces, examples, resolved.handles, **loaded.solver_options())
    expected = solver.solve(resolved.targets[0], weights)
    pose, pose_faces = load(pose_path)
    diagonal = np.linalg.norm(rest.max(axis=0) - rest.min(axis=0))
    moved = np.linalg.norm(pose - rest, axis=1).max() / diagonal
    error = np.abs(pose - expected.vertices).max() / diagonal
    print(f"{len(resolved.handles)} handles; the pose moved up to {moved:.4f} of the diagonal; "
          f"it differs from meshik.Solver's by {error:.3g} of the diagonal (weights {np.round(expected.weights, 4)})")
    if not np.array_equal(pose_faces, faces):
        raise SystemExit("gui_check_drag: the saved pose has other triangles than the rest mesh")
    if moved < 1e-3:
        raise SystemExit("gui_check_drag: the posed layer did not move")
    if error > 1e-6:
        raise SystemExit(f"gui_check_drag: the saved pose differs from meshik.Solver's by {error:.3g} of the diagonal")


def load_vertices(path):
    """(#V, 3) vertices and (#F, 3) faces of a mesh file, through pymeshlab."""
    import pymeshlab

    ms = pymeshlab.MeshSet()
    ms.load_new_mesh(str(path))
    return ms.current_mesh().vertex_matrix(), ms.current_mesh().face_matrix()


def check_same(a_path, b_path):
    a, b = load_vertices(a_path)[0], load_vertices(b_path)[0]
    if a.shape != b.shape or not np.array_equal(a, b):
        difference = np.abs(a - b).max() if a.shape == b.shape else "other shapes"
        raise SystemExit(f"gui_check_drag: {a_path} and {b_path} differ (largest difference {difference})")
    print(f"{a_path} and {b_path}: {len(a)} vertices, bit-identical")


def check_symmetric(pose_path, axis_text):
    axis = int(axis_text)
    pose = load_vertices(pose_path)[0]
    diagonal = np.linalg.norm(pose.max(axis=0) - pose.min(axis=0))
    centre = 0.5 * (pose.max(axis=0) + pose.min(axis=0))[axis]
    image = pose.copy()
    image[:, axis] = 2.0 * centre - image[:, axis]
    error = max(np.sqrt(((chunk[:, None, :] - pose[None, :, :]) ** 2).sum(axis=2)).min(axis=1).max()
                for chunk in np.array_split(image, max(1, len(image) // 256))) / diagonal
    print(f"the pose's mirror image across axis {axis} lies within {error:.3g} of the diagonal of the pose")
    if error > 1e-6:
        raise SystemExit(f"gui_check_drag: the pose is not symmetric ({error:.3g} of the diagonal)")


def check_frames(constraints_path, out, *poses):
    import pathlib

    meshik_command = pathlib.Path(sys.executable).parent / "meshik"
    subprocess.run([str(meshik_command), "pose", constraints_path, "--out", out, "--format", "ply"],
                   check=True, capture_output=True)
    replayed = sorted(pathlib.Path(out).rglob("*.ply"))
    if len(replayed) != len(poses):
        raise SystemExit(f"gui_check_drag: meshik pose wrote {len(replayed)} frames, the tool posed {len(poses)}")
    worst = 0.0
    for frame, pose in zip(replayed, poses):
        a, b = load_vertices(frame)[0], load_vertices(pose)[0]
        diagonal = np.linalg.norm(b.max(axis=0) - b.min(axis=0))
        worst = max(worst, np.abs(a - b).max() / diagonal)
    print(f"{len(poses)} frames replayed by meshik pose; largest difference {worst:.3g} of the diagonal")
    if worst > 1e-6:
        raise SystemExit(f"gui_check_drag: a replayed frame differs by {worst:.3g} of the diagonal")


def main(argv):
    if len(argv) == 6 and argv[0] == "points":
        for x, y in mesh_points(argv[1], tuple(int(v) for v in argv[2:6])):
            print(x, y)
    elif len(argv) == 4 and argv[0] == "check":
        check_pose(*argv[1:])
    elif len(argv) == 3 and argv[0] == "same":
        check_same(*argv[1:])
    elif len(argv) == 3 and argv[0] == "symmetric":
        check_symmetric(*argv[1:])
    elif len(argv) >= 4 and argv[0] == "frames":
        check_frames(*argv[1:])
    else:
        raise SystemExit(__doc__)


if __name__ == "__main__":
    main(sys.argv[1:])
