"""The package's modules before it was grouped into subpackages (0.1), still importable under their old
names with a DeprecationWarning that names the new module.

`import meshik.meshio` (or `from meshik import meshio`) gives the module meshik.inputs.meshio itself,
so attributes set on it (a test's monkeypatch) reach the real module. A module whose contents were
split (export_gltf) comes back as a read-only view that finds each name in the new modules.
"""
import importlib
import importlib.abc
import importlib.machinery
import importlib.util
import sys
import types
import warnings
from typing import Dict, Optional, Sequence, Tuple

# old module name -> the module(s) that now hold its contents, searched in order
MOVED_MODULES: Dict[str, Tuple[str, ...]] = {
    "meshik.constraints": ("meshik.inputs.constraints",),
    "meshik.meshio": ("meshik.inputs.meshio",),
    "meshik.isolated_load": ("meshik.inputs.isolated_load",),
    "meshik.meshlab_module": ("meshik.inputs.meshlab_module",),
    "meshik.obj_text": ("meshik.inputs.obj_text",),
    "meshik.validation": ("meshik.inputs.validation",),
    "meshik.file_info": ("meshik.inputs.file_info",),
    "meshik.tracking": ("meshik.inputs.tracking",),
    "meshik.blending": ("meshik.posing.blending",),
    "meshik.simplify": ("meshik.posing.simplify",),
    "meshik.surface_distance": ("meshik.posing.surface_distance",),
    "meshik.example_cache": ("meshik.posing.example_cache",),
    "meshik.export_draco": ("meshik.export.draco",),
    "meshik.export_gltf": ("meshik.export.glb_reader", "meshik.export.glb_draco", "meshik.export.glb_layout"),
    "meshik.export_gltf_quantized": ("meshik.export.glb_quantized",),
    "meshik.gltf_container": ("meshik.export.glb_container",),
    "meshik.morph_basis": ("meshik.export.morph_basis",),
    "meshik.output_errors": ("meshik.export.output_errors",),
    "meshik.staging": ("meshik.outputs.staging",),
    "meshik.folder_swap": ("meshik.outputs.folder_swap",),
    "meshik.safe_paths": ("meshik.outputs.safe_paths",),
    "meshik.batch_job": ("meshik.batch.job",),
    "meshik.batch_display": ("meshik.batch.display",),
    "meshik.view_server": ("meshik.preview.server",),
    "meshik.viewer_site": ("meshik.preview.site",),
    "meshik.contact_sheet": ("meshik.preview.contact_sheet",),
}


def _split_module_view(old_name: str, modules: Sequence[types.ModuleType]) -> types.ModuleType:
    """A module named old_name whose attributes are looked up in `modules`, first one first."""
    view = types.ModuleType(old_name, f"Deprecated: the contents of {old_name} now live in "
                                      f"{', '.join(module.__name__ for module in modules)}.")

    def find(name: str):
        for module in modules:
            if hasattr(module, name):
                return getattr(module, name)
        raise AttributeError(f"module {old_name!r} has no attribute {name!r}")

    view.__getattr__ = find
    return view


class _MovedModuleLoader(importlib.abc.Loader):
    """Loads an old module name as the module(s) that replaced it, warning once per import."""

    def __init__(self) -> None:
        self.own_spec: Optional[importlib.machinery.ModuleSpec] = None   # the replacement's, when one

    def create_module(self, spec) -> types.ModuleType:
        """The new module itself (one replacement) or a view over the replacements (several)."""
        new_names = MOVED_MODULES[spec.name]
        warnings.warn(f"{spec.name} is deprecated: import {' or '.join(new_names)} instead",
                      DeprecationWarning, stacklevel=2)
        modules = [importlib.import_module(name) for name in new_names]
        if len(modules) > 1:
            return _split_module_view(spec.name, modules)
        self.own_spec = modules[0].__spec__
        return modules[0]

    def exec_module(self, module: types.ModuleType) -> None:
        """Nothing to run; gives the real module back its own __spec__, which the import system
        replaced with the old name's."""
        if self.own_spec is not None and module.__name__ == self.own_spec.name:
            module.__spec__ = self.own_spec


class _MovedModuleFinder(importlib.abc.MetaPathFinder):
    """Finds the old module names of MOVED_MODULES (and nothing else)."""

    def find_spec(self, fullname: str, path, target=None) -> Optional[importlib.machinery.ModuleSpec]:
        """A spec for an old name, or None so that the other finders go on."""
        if fullname not in MOVED_MODULES:
            return None
        return importlib.util.spec_from_loader(fullname, _MovedModuleLoader())


def install() -> None:
    """Adds the finder of old module names to sys.meta_path once (after the standard finders)."""
    if not any(isinstance(finder, _MovedModuleFinder) for finder in sys.meta_path):
        sys.meta_path.append(_MovedModuleFinder())
