"""The package's layout (issue 25): no import cycle between its modules nor between its subpackages, no
module of the package importing an old (deprecated) module name, and the old names still importable
with a DeprecationWarning that names the new module."""
import ast
import importlib
import sys
import warnings
from pathlib import Path
from typing import Dict, List, Set

import pytest

import meshik
from meshik.moved_modules import MOVED_MODULES

PACKAGE_DIR = Path(meshik.__file__).resolve().parent


def module_files() -> Dict[str, Path]:
    """{dotted module name: file} for every .py file of the package (a package is its __init__.py)."""
    modules = {}
    for path in sorted(PACKAGE_DIR.rglob("*.py")):
        parts = ("meshik",) + path.relative_to(PACKAGE_DIR).with_suffix("").parts
        modules[".".join(parts[:-1] if parts[-1] == "__init__" else parts)] = path
    return modules


def imported_names(module: str, path: Path) -> Set[str]:
    """Every module name `module` imports, at its top or inside a function (`from a import b` names a
    and a.b), relative imports resolved."""
    names = set()
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"), str(path))):
        if isinstance(node, ast.Import):
            names.update(alias.name for alias in node.names)
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                anchor = package.split(".")[:len(package.split(".")) - node.level + 1]
                base = ".".join(anchor + ([base] if base else []))
            names.add(base)
            names.update(f"{base}.{alias.name}" for alias in node.names)
    return names


def import_graph() -> Dict[str, Set[str]]:
    """{module: the package's modules it imports} (only edges between .py modules of the package; the
    implicit import of a module's parent packages is not an edge)."""
    files = module_files()
    return {module: {name for name in imported_names(module, path) if name in files and name != module}
            for module, path in files.items()}


def cycles(graph: Dict[str, Set[str]]) -> List[List[str]]:
    """The strongly connected components of more than one node (Tarjan), each sorted."""
    index: Dict[str, int] = {}
    low: Dict[str, int] = {}
    stack: List[str] = []
    on_stack: Set[str] = set()
    found: List[List[str]] = []

    def visit(node: str) -> None:
        index[node] = low[node] = len(index)
        stack.append(node)
        on_stack.add(node)
        for target in sorted(graph.get(node, ())):
            if target not in index:
                visit(target)
                low[node] = min(low[node], low[target])
            elif target in on_stack:
                low[node] = min(low[node], index[target])
        if low[node] == index[node]:
            component = []
            while True:
                member = stack.pop()
                on_stack.discard(member)
                component.append(member)
                if member == node:
                    break
            if len(component) > 1:
                found.append(sorted(component))

    for node in sorted(graph):
        if node not in index:
            visit(node)
    return found


def room_of(module: str, subpackages: Set[str]) -> str:
    """The subpackage (meshik.<room>) that holds `module`, or the module itself at the top."""
    room = ".".join(module.split(".")[:2])
    return room if room in subpackages else module


def test_no_import_cycle_between_modules():
    graph = import_graph()
    assert len(graph) > 30 and "meshik.export.glb_quantized" in graph
    assert cycles(graph) == []


def test_no_import_cycle_between_subpackages():
    files = module_files()
    subpackages = {module for module, path in files.items() if path.name == "__init__.py" and module != "meshik"}
    assert {"meshik.inputs", "meshik.posing", "meshik.export", "meshik.outputs", "meshik.batch",
            "meshik.preview"} <= subpackages
    rooms: Dict[str, Set[str]] = {}
    for module, targets in import_graph().items():
        room = room_of(module, subpackages)
        rooms.setdefault(room, set()).update(room_of(t, subpackages) for t in targets)
        rooms[room].discard(room)
    assert cycles(rooms) == []


def test_the_cycle_finder_finds_a_cycle():
    assert cycles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert cycles({"a": {"b"}, "b": set()}) == []


def test_the_package_imports_no_old_module_name():
    offenders = {module: sorted(imported_names(module, path) & set(MOVED_MODULES))
                 for module, path in module_files().items()}
    assert {module: names for module, names in offenders.items() if names} == {}


def test_old_module_names_are_free_and_their_replacements_exist():
    files = module_files()
    for old, new_names in MOVED_MODULES.items():
        assert old not in files, f"{old} is a module again: remove it from MOVED_MODULES"
        assert all(name in files for name in new_names), (old, new_names)


@pytest.mark.parametrize("old", sorted(MOVED_MODULES))
def test_an_old_module_name_imports_with_a_deprecation_warning(old):
    sys.modules.pop(old, None)
    with pytest.warns(DeprecationWarning, match=MOVED_MODULES[old][0].replace(".", r"\.")):
        module = importlib.import_module(old)
    new_names = MOVED_MODULES[old]
    if len(new_names) == 1:
        new = importlib.import_module(new_names[0])
        assert module is new and new.__spec__.name == new_names[0]
    else:  # a view over several modules: each name from the first module that has it
        replacements = [importlib.import_module(name) for name in new_names]
        for attribute in {n for new in replacements for n in vars(new) if not n.startswith("_")}:
            owner = next(new for new in replacements if hasattr(new, attribute))
            assert getattr(module, attribute) is getattr(owner, attribute), attribute
        with pytest.raises(AttributeError, match="no attribute 'not_a_name'"):
            module.not_a_name


def test_the_documented_old_api_still_works():
    """The names README.md and pipeline/README.md gave before the subpackages."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        from meshik.constraints import load
        from meshik.export_gltf import read_animation_glb
        from meshik.export_gltf_quantized import quantized_animation_glb
        from meshik.meshio import load_example_set
        from meshik.simplify import simplify
        from meshik.tracking import tracking_document
    from meshik.batch import batch_client, run_batch
    from meshik.export.glb_quantized import quantized_animation_glb as new_quantized
    from meshik.export.glb_reader import read_animation_glb as new_read
    from meshik.inputs.constraints import load as new_load
    from meshik.pipeline import pose_job

    assert (read_animation_glb, quantized_animation_glb, load) == (new_read, new_quantized, new_load)
    assert all(callable(f) for f in (load_example_set, simplify, tracking_document, batch_client, run_batch, pose_job))
    assert meshik.Solver and meshik.ExampleSet and issubclass(meshik.InputError, ValueError)
