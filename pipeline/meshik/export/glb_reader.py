"""Reading back any MeshIK animation .glb: the Draco variant (glb_draco) or the quantized and meshopt
ones (glb_quantized), told apart by the primitive's extensions."""
from meshik.export.glb_container import split_glb
from meshik.export.glb_draco import DRACO_EXTENSION, read_draco_glb
from meshik.export.glb_layout import AnimationGlb
from meshik.export.glb_quantized import read_quantized_glb


def read_animation_glb(data: bytes) -> AnimationGlb:
    """Parse a .glb written by animation_glb or quantized_animation_glb (first mesh, first primitive).
    Raises ValueError."""
    document, binary = split_glb(data)
    primitive = document["meshes"][0]["primitives"][0]
    if DRACO_EXTENSION in primitive.get("extensions", {}):
        return read_draco_glb(document, binary)
    return read_quantized_glb(document, binary)
