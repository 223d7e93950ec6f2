"""Which readers open each .glb variant, as measured by the project's tests with the real readers
(Blender 5.0.1's importer through bpy, Babylon.js and three.js in Node, glTF-Transform, the Khronos
validator): the CLI help, report.json and `meshik info` say it from here.

Every variant's morph weights lie in [0, 1], so readers that clamp them to shape-key sliders
(Blender) play the same poses as those that do not.
"""
from typing import Any, Dict, Sequence

_QUANTIZATION, _MESHOPT, _DRACO = "KHR_mesh_quantization", "EXT_meshopt_compression", "KHR_draco_mesh_compression"

# variant -> the extensions it requires, the readers that play it right, the readers that refuse it
GLB_READERS: Dict[str, Dict[str, Any]] = {
    "quantized": {"needs": [_QUANTIZATION],
                  "opens_in": ["Blender 5.0.1", "three.js", "Babylon.js", "glTF-Transform",
                               "Khronos validator (every accessor checked)"],
                  "refused_by": []},
    "meshopt": {"needs": [_QUANTIZATION, _MESHOPT],
                "opens_in": ["three.js with MeshoptDecoder", "Babylon.js with a meshopt decoder", "glTF-Transform",
                             "Khronos validator (compressed data not checked)"],
                "refused_by": ["Blender 5.0.1 (its importer reads EXT_meshopt_compression from 5.2 on)"]},
    "draco": {"needs": [_DRACO],
              "opens_in": ["Blender 5.0.1", "three.js with DRACOLoader", "Babylon.js with a Draco decoder",
                           "glTF-Transform", "Khronos validator (compressed data not checked)"],
              "refused_by": []},
}


def variant_of(extensions_required: Sequence[str]) -> str:
    """The .glb variant ("quantized", "meshopt", "draco") of a MeshIK file's extensionsRequired;
    ValueError for another list."""
    for variant, readers in GLB_READERS.items():
        if sorted(readers["needs"]) == sorted(extensions_required):
            return variant
    raise ValueError(f"extensionsRequired {list(extensions_required)} is not a MeshIK .glb variant's")


def readers_of(variant: str) -> Dict[str, Any]:
    """{"needs": [extensions], "opens_in": [readers], "refused_by": [readers]} of a .glb variant (a copy)."""
    return {key: list(value) for key, value in GLB_READERS[variant].items()}
