"""Generates the example sets in sample_meshes/ (deterministic: numpy only, no randomness).

Each set is a folder with the rest mesh `rest.obj`, example poses `example_1.obj` ...
(same vertex order and triangles) and `animation.json`, a constraint file (format
"meshik-constraints", version 1) that animates the set through a sequence of frames.

  bar   132 vertices, 260 triangles, 2 examples: a capped square-ish tube (the paper's "Bar" row),
        bent by 90 degrees and twisted by 120 degrees.
  flag  516 vertices, 924 triangles, 6 examples: a cloth strip on a pole, waving in travelling
        waves of different phase and amplitude (the paper's "Flag" row).
  limb  1,240 vertices, 2,476 triangles, 4 examples: an arm (upper arm, forearm, hand) skinned
        on three bones, with the elbow bent, the shoulder raised, the wrist bent and both.
  wings 656 vertices, 1,308 triangles, 4 examples: a body with two wings along x, exactly
        symmetric about the plane x = 0 (vertices, triangles and every example), the wings raised,
        lowered, swept forward and both (for the Drag to Pose tool's Mirror check).

Usage: python scripts/generate_samples.py [--out sample_meshes]
"""
import argparse
import json
import math
import pathlib

import numpy as np


def write_obj(path: pathlib.Path, vertices: np.ndarray, faces: np.ndarray, comment: str) -> None:
    """Writes #V by 3 `vertices` and #F by 3 0-based `faces` as an OBJ file (1-based indices)."""
    lines = [f"# {comment}"]
    lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in vertices]
    lines += [f"f {a + 1} {b + 1} {c + 1}" for a, b, c in faces]
    path.write_text("\n".join(lines) + "\n")


def rotation(axis, degrees: float) -> np.ndarray:
    """3 by 3 rotation matrix about the unit `axis` by `degrees` (Rodrigues)."""
    a = np.asarray(axis, dtype=float)
    a = a / np.linalg.norm(a)
    t = math.radians(degrees)
    k = np.array([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return np.eye(3) + math.sin(t) * k + (1 - math.cos(t)) * (k @ k)


def capped_tube(rings: int, sides: int, length: float, radius_of) -> tuple:
    """A closed tube along +x: `rings` rings of `sides` vertices from x=0 to x=length, with
    radius radius_of(t) at t in [0, 1], and fan-triangulated caps (no extra vertices).
    Returns (#V by 3 vertices, #F by 3 faces), #V = rings*sides, #F = 2*sides*(rings-1) + 2*(sides-2)."""
    vertices = []
    for r in range(rings):
        t = r / (rings - 1)
        rad = radius_of(t)
        for s in range(sides):
            a = 2 * math.pi * s / sides
            vertices.append((t * length, rad * math.cos(a), rad * math.sin(a)))
    faces = []
    for r in range(rings - 1):
        for s in range(sides):
            a, b = r * sides + s, r * sides + (s + 1) % sides
            c, d = a + sides, b + sides
            faces += [(a, b, d), (a, d, c)]
    last = (rings - 1) * sides
    for s in range(1, sides - 1):
        faces.append((0, s + 1, s))                  # cap at x = 0, facing -x
        faces.append((last, last + s, last + s + 1))  # cap at x = length, facing +x
    return np.array(vertices), np.array(faces, dtype=np.int64)


def bend(vertices: np.ndarray, degrees: float, length: float) -> np.ndarray:
    """Bends a bar lying along +x into a circular arc in the xy-plane turning by `degrees`."""
    theta = math.radians(degrees)
    radius = length / theta
    x, y, z = vertices.T
    phi = x / length * theta
    r = radius - y
    return np.column_stack([r * np.sin(phi), radius - r * np.cos(phi), z])


def twist(vertices: np.ndarray, degrees: float, length: float) -> np.ndarray:
    """Twists a bar lying along +x about the x axis, linearly up to `degrees` at x = length."""
    x, y, z = vertices.T
    phi = np.radians(degrees) * x / length
    return np.column_stack([x, y * np.cos(phi) - z * np.sin(phi), y * np.sin(phi) + z * np.cos(phi)])


def make_bar() -> dict:
    """The paper's Bar: 11 rings of 12 vertices (132), 260 triangles, examples bent and twisted."""
    length = 4.0
    rest, faces = capped_tube(11, 12, length, lambda t: 0.5)
    return {
        "rest": rest, "faces": faces,
        "examples": [bend(rest, 90.0, length), twist(rest, 120.0, length)],
        "handles": {"base": list(range(12)), "tip": list(range(120, 132))},
        "frames": [{"name": f"{i:04d}", "targets": {"tip": {"rotate": {
            "axis": [0, 0, 1], "degrees": 75.0 * math.sin(math.pi * i / 23), "center": [0.0, 0.0, 0.0]}}}}
            for i in range(24)],
    }


def flag_wave(rest: np.ndarray, width: float, amplitude: float, wavelength: float, phase: float) -> np.ndarray:
    """A travelling wave across the flag (out of its plane, growing away from the pole at x=0),
    with the cloth pulled towards the pole so its length along the surface is roughly kept."""
    x, y, z = rest.T
    u = x / width
    k = 2 * math.pi / wavelength
    out = amplitude * u * np.sin(k * x - phase)
    slope = amplitude * k * u
    shrink = 1.0 / np.sqrt(1.0 + 0.5 * slope ** 2)
    return np.column_stack([x * shrink, y - 0.08 * amplitude * u ** 2, z + out])


def make_flag() -> dict:
    """The paper's Flag: a 43 by 12 grid (516 vertices, 924 triangles) waving, 6 examples."""
    cols, rows, width, height = 43, 12, 3.0, 0.8
    xs, ys = np.linspace(0, width, cols), np.linspace(0, height, rows)
    rest = np.array([(x, y, 0.0) for y in ys for x in xs])
    faces = []
    for r in range(rows - 1):
        for c in range(cols - 1):
            a, b = r * cols + c, r * cols + c + 1
            faces += [(a, b, b + cols), (a, b + cols, a + cols)]
    faces = np.array(faces, dtype=np.int64)
    examples = [flag_wave(rest, width, amp, wl, ph) for amp, wl, ph in
                [(0.25, 1.5, 0.0), (0.25, 1.5, math.pi / 2), (0.25, 1.5, math.pi),
                 (0.35, 2.2, 0.5), (0.15, 1.0, 2.0), (0.4, 3.0, 4.0)]]
    pole = [r * cols for r in range(rows)]
    corner = [rows * cols - 1, rows * cols - 2, (rows - 1) * cols - 1]
    frames = []
    for i in range(32):
        s = 2 * math.pi * i / 32
        frames.append({"name": f"{i:04d}", "targets": {"corner": {"translate": [
            -0.25 - 0.1 * math.cos(s), -0.03, 0.35 * math.sin(s)]}}})
    return {"rest": rest, "faces": faces, "examples": examples,
            "handles": {"pole": pole, "corner": corner}, "frames": frames}


def smoothstep(t: np.ndarray) -> np.ndarray:
    """0 below 0, 1 above 1, smooth in between."""
    t = np.clip(t, 0.0, 1.0)
    return t * t * (3 - 2 * t)


def skin_arm(rest: np.ndarray, shoulder_deg: float, elbow_deg: float, wrist_deg: float) -> np.ndarray:
    """Poses the arm (along +x: shoulder x=0, elbow x=1.8, wrist x=3.4) by linear blend skinning
    on three bones with smooth weights across each joint; rotations about the z axis."""
    elbow, wrist = np.array([1.8, 0.0, 0.0]), np.array([3.4, 0.0, 0.0])
    r0 = rotation([0, 0, 1], shoulder_deg)
    r1 = r0 @ rotation([0, 0, 1], elbow_deg)
    r2 = r1 @ rotation([0, 0, 1], wrist_deg)
    elbow_posed = r0 @ elbow
    wrist_posed = elbow_posed + r1 @ (wrist - elbow)
    bones = [rest @ r0.T,
             (rest - elbow) @ r1.T + elbow_posed,
             (rest - wrist) @ r2.T + wrist_posed]
    x = rest[:, 0]
    w_fore = smoothstep((x - 1.6) / 0.4)
    w_hand = smoothstep((x - 3.25) / 0.3)
    w = np.column_stack([1 - w_fore, w_fore * (1 - w_hand), w_hand])
    return sum(w[:, [i]] * bones[i] for i in range(3))


def symmetric_tube(rings: int, sides: int, half_length: float, radius_of) -> tuple:
    """A closed tube along x from -half_length to half_length, exactly symmetric about x = 0:
    `rings` (odd) rings of `sides` vertices, radius radius_of(|x|), ring r the mirror image of ring
    rings-1-r (x negated exactly), and the quads of the half x > 0 split along the mirror images of
    the other half's diagonals; caps fanned from each end ring's first vertex.
    Returns (#V by 3 vertices, #F by 3 faces), #V = rings*sides, #F = 2*sides*(rings-1) + 2*(sides-2)."""
    last_ring = rings - 1
    vertices = []
    for r in range(rings):
        x = half_length * (2 * r - last_ring) / last_ring
        rad = radius_of(abs(x))
        for s in range(sides):
            a = 2 * math.pi * s / sides
            vertices.append((x, rad * math.cos(a), rad * math.sin(a)))
    faces = []
    for r in range(last_ring):
        for s in range(sides):
            a, b = r * sides + s, r * sides + (s + 1) % sides
            c, d = a + sides, b + sides
            faces += [(a, b, d), (a, d, c)] if 2 * r < last_ring else [(a, b, c), (b, d, c)]
    last = last_ring * sides
    for s in range(1, sides - 1):
        faces.append((0, s + 1, s))
        faces.append((last, last + s, last + s + 1))
    return np.array(vertices), np.array(faces, dtype=np.int64)


def pose_wings(rest: np.ndarray, raise_deg: float, sweep_deg: float) -> np.ndarray:
    """Both wings turned about their shoulder (x = +-0.6): raised by raise_deg (tips up, +y) and
    swept forward by sweep_deg (tips towards +z), blended smoothly from the body; the left wing is
    the exact mirror image of the right one."""
    shoulder = np.array([0.6, 0.0, 0.0])
    turn = rotation([0, 0, 1], raise_deg) @ rotation([0, 1, 0], -sweep_deg)
    mirror = np.array([-1.0, 1.0, 1.0])
    side = np.abs(rest) * [1, 0, 0] + rest * [0, 1, 1]  # every vertex as if on the right wing
    weight = smoothstep((side[:, 0] - 0.3) / 0.6)[:, None]
    posed = (1 - weight) * side + weight * ((side - shoulder) @ turn.T + shoulder)
    return np.where(rest[:, [0]] < 0, posed * mirror, posed)


def make_wings() -> dict:
    """A body (radius 0.45) with two wings (radius 0.2) along x, 41 rings of 16 vertices."""
    rest, faces = symmetric_tube(41, 16, 2.5, lambda x: 0.2 + 0.25 * math.exp(-(x / 0.5) ** 2))
    examples = [pose_wings(rest, *p) for p in [(50, 0), (-40, 0), (0, 45), (30, 30)]]
    frames = []
    for i in range(12):
        flap = 40.0 * math.sin(2 * math.pi * i / 12)
        frames.append({"name": f"{i:04d}", "targets": {
            "left": {"rotate": {"axis": [0, 0, 1], "degrees": -flap, "center": [-0.6, 0.0, 0.0]}},
            "right": {"rotate": {"axis": [0, 0, 1], "degrees": flap, "center": [0.6, 0.0, 0.0]}}}})
    return {"rest": rest, "faces": faces, "examples": examples,
            "handles": {"body": {"near": [0.0, 0.0, 0.0], "radius": 0.46},
                        "left": {"near": [-2.5, 0.0, 0.0], "radius": 0.25},
                        "right": {"near": [2.5, 0.0, 0.0], "radius": 0.25}},
            "frames": frames}


def make_limb() -> dict:
    """An arm: 62 rings of 20 vertices (1,240), bulging at the biceps and forearm, flat hand."""
    length = 4.2

    def radius(t: float) -> float:
        x = t * length
        return (0.32 + 0.07 * math.exp(-((x - 0.9) / 0.35) ** 2) + 0.05 * math.exp(-((x - 2.3) / 0.4) ** 2)
                - 0.08 * smoothstep(np.array((x - 3.0) / 0.6)).item())

    rest, faces = capped_tube(62, 20, length, radius)
    hand = rest[:, 0] > 3.4
    rest[hand, 2] *= 0.45  # flatten the hand
    poses = [(0, 100, 0), (60, 0, 0), (0, 0, 70), (40, 80, -40)]
    examples = [skin_arm(rest, *p) for p in poses]
    shoulder = list(range(20))
    frames = []
    for i in range(30):
        s = math.sin(math.pi * i / 29)
        frames.append({"name": f"{i:04d}", "targets": {"hand": {"rotate": {
            "axis": [0, 0, 1], "degrees": 95.0 * s, "center": [0.0, 0.0, 0.0]}},
            "elbow": {"rotate": {"axis": [0, 0, 1], "degrees": 35.0 * s, "center": [0.0, 0.0, 0.0]}}}})
    return {"rest": rest, "faces": faces, "examples": examples,
            "handles": {"shoulder": shoulder,
                        "elbow": {"near": [1.8, 0.4, 0.0], "radius": 0.15},
                        "hand": {"near": [4.2, 0.0, 0.0], "radius": 0.2}},
            "frames": frames}


def write_set(out: pathlib.Path, name: str, data: dict, feature_space: str = "nonlinear") -> None:
    """Writes one example set folder: rest.obj, example_<i>.obj, animation.json."""
    folder = out / name
    folder.mkdir(parents=True, exist_ok=True)
    write_obj(folder / "rest.obj", data["rest"], data["faces"], f"MeshIK sample '{name}': rest pose")
    names = []
    for i, example in enumerate(data["examples"], start=1):
        names.append(f"example_{i}.obj")
        write_obj(folder / names[-1], example, data["faces"], f"MeshIK sample '{name}': example {i}")
    # "$schema" lets editors check and complete the file (the path is relative to the set's folder).
    constraints = {"$schema": "../../pipeline/meshik/schema/meshik-constraints-1.schema.json",
                   "format": "meshik-constraints", "version": 1, "rest": "rest.obj", "examples": names,
                   "feature_space": feature_space, "handles": data["handles"], "frames": data["frames"]}
    (folder / "animation.json").write_text(json.dumps(constraints, indent=1) + "\n")
    print(f"{name}: {len(data['rest'])} vertices, {len(data['faces'])} triangles, "
          f"{len(data['examples'])} examples, {len(data['frames'])} frames")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default=str(pathlib.Path(__file__).resolve().parent.parent / "sample_meshes"))
    out = pathlib.Path(parser.parse_args().out)
    write_set(out, "bar", make_bar())
    write_set(out, "flag", make_flag())
    write_set(out, "limb", make_limb())
    write_set(out, "wings", make_wings())


if __name__ == "__main__":
    main()
