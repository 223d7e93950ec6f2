"""Every field of a .glb's JSON that MeshIK's readers use, checked before anything is decoded.

A hostile .glb must end in one ValueError naming the field, not in a traceback (a primitive that is
a list, a count that is a string) nor in a decoder's abort (a meshopt view of byteStride 3, a
TRIANGLES count that is no multiple of 3, a length past the binary chunk). check_document() walks
the parts MeshIK reads: buffer views (plain and EXT_meshopt_compression), accessors (with sparse
parts) and their bounds in their views, the first mesh's first primitive, the first node and the
first animation's first sampler.
"""
from typing import Any, Dict, List

# The most bytes one decoded view or accessor may take (far above any animation MeshIK writes).
MAX_DECODED_BYTES = 1 << 31
_COMPONENT_SIZES = {5120: 1, 5121: 1, 5122: 2, 5123: 2, 5125: 4, 5126: 4}
_COMPONENT_COUNTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
_MESHOPT = "EXT_meshopt_compression"
_DRACO = "KHR_draco_mesh_compression"


def check_document(document: Any, binary_length: int) -> None:
    """ValueError naming the first field of `document` (a .glb's parsed JSON) that MeshIK's readers
    would trip on; binary_length: bytes in the .glb's binary chunk."""
    _check(isinstance(document, dict), "the JSON chunk is not an object")
    views = _list(document, "bufferViews", "bufferViews")
    for index, view in enumerate(views):
        _check_view(view, f"bufferViews[{index}]", binary_length)
    accessors = _list(document, "accessors", "accessors")
    for index, entry in enumerate(accessors):
        _check_accessor(entry, f"accessors[{index}]", views)
    meshes = _list(document, "meshes", "meshes", non_empty=True)
    mesh = _object(meshes[0], "meshes[0]")
    primitive = _object(_list(mesh, "primitives", "meshes[0].primitives", non_empty=True)[0], "meshes[0].primitives[0]")
    where = "meshes[0].primitives[0]"
    for name, value in _object(primitive.get("attributes", {}), f"{where}.attributes").items():
        _index(value, len(accessors), f"{where}.attributes.{name}")
    if "indices" in primitive:
        _index(primitive["indices"], len(accessors), f"{where}.indices")
    for number, target in enumerate(_list(primitive, "targets", f"{where}.targets", required=False)):
        for name, value in _object(target, f"{where}.targets[{number}]").items():
            _index(value, len(accessors), f"{where}.targets[{number}].{name}")
    extensions = _object(primitive.get("extensions", {}), f"{where}.extensions")
    if _DRACO in extensions:
        _index(_object(extensions[_DRACO], f"{where}.extensions.{_DRACO}").get("bufferView"), len(views),
               f"{where}.extensions.{_DRACO}.bufferView")
    extras = _object(mesh.get("extras", {}), "meshes[0].extras")
    for key in ("frameNames", "targetNames"):
        names = _list(extras, key, f"meshes[0].extras.{key}", required=False)
        _check(all(isinstance(n, str) for n in names), f"meshes[0].extras.{key}: expected a list of strings")
    nodes = _list(document, "nodes", "nodes", required=False)
    if nodes:
        node = _object(nodes[0], "nodes[0]")
        for key in ("translation", "scale"):
            if key in node:
                value = node[key]
                _check(isinstance(value, list) and len(value) == 3 and all(_is_number(v) for v in value),
                       f"nodes[0].{key}: expected 3 numbers")
    animations = _list(document, "animations", "animations", required=False)
    if animations:
        samplers = _list(_object(animations[0], "animations[0]"), "samplers", "animations[0].samplers", non_empty=True)
        sampler = _object(samplers[0], "animations[0].samplers[0]")
        for key in ("input", "output"):
            _index(sampler.get(key), len(accessors), f"animations[0].samplers[0].{key}")


def _check_view(view: Any, where: str, binary_length: int) -> None:
    """A buffer view: lengths and offsets inside the binary chunk; a meshopt view's stream fields."""
    view = _object(view, where)
    length = _count(view.get("byteLength"), f"{where}.byteLength")
    offset = _count(view.get("byteOffset", 0), f"{where}.byteOffset")
    if "byteStride" in view:
        stride = _count(view["byteStride"], f"{where}.byteStride")
        _check(4 <= stride <= 252 and stride % 4 == 0, f"{where}.byteStride: {stride} is not a multiple of 4 from 4 to 252")
    extensions = _object(view.get("extensions", {}), f"{where}.extensions")
    if _MESHOPT not in extensions:
        if view.get("buffer", 0) == 0:
            _check(offset + length <= binary_length, f"{where}: bytes {offset} to {offset + length} lie past the "
                                                     f"binary chunk's {binary_length}")
        return
    where = f"{where}.extensions.{_MESHOPT}"
    stream = _object(extensions[_MESHOPT], where)
    start = _count(stream.get("byteOffset", 0), f"{where}.byteOffset")
    encoded = _count(stream.get("byteLength"), f"{where}.byteLength")
    _check(start + encoded <= binary_length, f"{where}: bytes {start} to {start + encoded} lie past the binary "
                                             f"chunk's {binary_length}")
    count = _count(stream.get("count"), f"{where}.count")
    stride = _count(stream.get("byteStride"), f"{where}.byteStride")
    mode = stream.get("mode") if isinstance(stream.get("mode"), str) else None
    if mode == "ATTRIBUTES":
        _check(4 <= stride <= 256 and stride % 4 == 0, f"{where}.byteStride: {stride} is not a multiple of 4 from 4 to 256")
    elif mode in ("TRIANGLES", "INDICES"):
        _check(stride in (2, 4), f"{where}.byteStride: {stride} is not 2 or 4 (index bytes)")
        _check(mode == "INDICES" or count % 3 == 0, f"{where}.count: {count} indices are not whole triangles")
    else:
        raise ValueError(f"{where}.mode: expected ATTRIBUTES, TRIANGLES or INDICES, got {str(stream.get('mode'))[:40]!r}")
    _check(count * stride == length, f"{where}: count {count} by byteStride {stride} is not the view's byteLength {length}")
    _check(length <= MAX_DECODED_BYTES, f"{where}: {length} decoded bytes is more than the {MAX_DECODED_BYTES} accepted")


def _check_accessor(entry: Any, where: str, views: List[Any]) -> None:
    """An accessor: its kind and component type, and its bytes inside its buffer view."""
    entry = _object(entry, where)
    kind, component = entry.get("type"), entry.get("componentType")
    _check(isinstance(kind, str) and kind in _COMPONENT_COUNTS,
           f"{where}.type: expected SCALAR, VEC2, VEC3 or VEC4, got {str(kind)[:40]!r}")
    _check(type(component) is int and component in _COMPONENT_SIZES,
           f"{where}.componentType: {str(component)[:40]!r} is not a glTF component type")
    count = _count(entry.get("count"), f"{where}.count")
    element = _COMPONENT_SIZES[component] * _COMPONENT_COUNTS[kind]
    if "bufferView" in entry:
        view = views[_index(entry["bufferView"], len(views), f"{where}.bufferView")]
        stride = view.get("byteStride", element)
        end = _count(entry.get("byteOffset", 0), f"{where}.byteOffset") + (stride * (count - 1) + element if count else 0)
        _check(end <= view["byteLength"], f"{where}: its {count} elements end at byte {end}, past its view's "
                                          f"byteLength {view['byteLength']}")
    _check(count * element <= MAX_DECODED_BYTES, f"{where}.count: {count} elements is more than accepted")
    if "sparse" in entry:
        sparse = _object(entry["sparse"], f"{where}.sparse")
        values = _count(sparse.get("count"), f"{where}.sparse.count")
        _check(values <= count, f"{where}.sparse.count: {values} is more than the accessor's {count} elements")
        for part, size in (("indices", None), ("values", 4)):
            block = _object(sparse.get(part), f"{where}.sparse.{part}")
            view = views[_index(block.get("bufferView"), len(views), f"{where}.sparse.{part}.bufferView")]
            if size is None:
                _check(type(block.get("componentType")) is int and block["componentType"] in (5121, 5123, 5125),
                       f"{where}.sparse.indices.componentType: expected an unsigned integer type")
                size = _COMPONENT_SIZES[block["componentType"]]
            end = _count(block.get("byteOffset", 0), f"{where}.sparse.{part}.byteOffset") + values * size
            _check(end <= view["byteLength"], f"{where}.sparse.{part}: ends at byte {end}, past its view")


def _check(condition: bool, message: str) -> None:
    """ValueError(message) unless condition."""
    if not condition:
        raise ValueError(message)


def _is_number(value: Any) -> bool:
    """Whether a JSON value is a number (not a bool)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _count(value: Any, where: str) -> int:
    """`value` when it is an integer from 0 to 2**53; ValueError naming `where` otherwise."""
    _check(isinstance(value, int) and not isinstance(value, bool) and 0 <= value <= 1 << 53,
           f"{where}: expected a non-negative integer, got {str(value)[:40]!r}")
    return value


def _index(value: Any, size: int, where: str) -> int:
    """`value` when it indexes a list of `size` entries; ValueError naming `where` otherwise."""
    _check(isinstance(value, int) and not isinstance(value, bool) and 0 <= value < size,
           f"{where}: {str(value)[:40]!r} is not an index of the {size} entries")
    return value


def _object(value: Any, where: str) -> Dict[str, Any]:
    """`value` when it is a JSON object; ValueError naming `where` otherwise."""
    _check(isinstance(value, dict), f"{where}: expected an object, got {type(value).__name__}")
    return value


def _list(parent: Dict[str, Any], key: str, where: str, required: bool = True, non_empty: bool = False) -> List[Any]:
    """parent[key] when it is a list (non-empty if asked); [] when absent and not required."""
    if key not in parent and not required:
        return []
    value = parent.get(key)
    _check(isinstance(value, list) and (value or not non_empty),
           f"{where}: expected a {'non-empty ' if non_empty else ''}list, got {type(value).__name__}")
    return value
