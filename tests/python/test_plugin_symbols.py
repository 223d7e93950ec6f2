"""The plugin's dynamic imports (no GUI needed): every Qt symbol it imports is exported by the Qt
that pymeshlab 2025.7 bundles, and no import is bound to a Qt-versioned copy of a C++ runtime
symbol (the `_ZdlPvm@Qt_5` trap: linked against the wheel's Qt, operator delete(void*, size_t)
binds to Qt_5, and a MeshLab built on a distribution's Qt exits with "symbol lookup error")."""
import pathlib
import subprocess

import pymeshlab
import pytest

from plugin_helpers import plugin_path

WHEEL_LIB = pathlib.Path(pymeshlab.__file__).parent / "lib"
LIBSTDCXX = pathlib.Path("/usr/lib/x86_64-linux-gnu/libstdc++.so.6")


def dynamic_symbols(library: pathlib.Path, undefined: bool):
    """{(name, version)} of a shared library's undefined (imported) or defined (exported) dynamic symbols."""
    flag = "--undefined-only" if undefined else "--defined-only"
    listing = subprocess.run(["nm", "-D", flag, str(library)], check=True, capture_output=True, text=True).stdout
    symbols = set()
    for line in listing.splitlines():
        token = line.split()[-1]
        name, _, version = token.replace("@@", "@").partition("@")
        symbols.add((name, version))
    return symbols


def built_plugins():
    """The plugin builds present: double always (make build), float when `make plugin` ran; filter and edit plugin."""
    double = plugin_path("double")
    if not double.is_file():
        pytest.fail(f"the MeshLab plugin is not built: {double} is missing (run `make build`)")
    edit = [p.with_name("libedit_meshik.so") for p in (double, plugin_path("float"))]
    return [p for p in [double, plugin_path("float"), *edit] if p.is_file()]


@pytest.fixture(scope="module")
def wheel_qt_exports():
    """{(name, version)} exported by the Qt libraries bundled in the pymeshlab wheel."""
    exports = set()
    for library in WHEEL_LIB.glob("libQt5*.so.5"):
        exports |= dynamic_symbols(library, undefined=False)
    assert exports, f"no Qt library in {WHEEL_LIB}"
    return exports


@pytest.mark.parametrize("plugin", built_plugins(), ids=lambda p: f"{p.parent.name}-{p.stem[3:]}")
def test_every_qt_import_is_exported_by_the_wheels_qt(plugin, wheel_qt_exports):
    qt_imports = {symbol for symbol in dynamic_symbols(plugin, undefined=True) if symbol[1].startswith("Qt_")}
    assert qt_imports, "the plugin imports no Qt symbol: is it linked against Qt?"
    missing = sorted(qt_imports - wheel_qt_exports)
    assert not missing, f"Qt symbols pymeshlab's Qt 5.15.2 lacks: {missing[:20]}"


@pytest.mark.parametrize("plugin", built_plugins(), ids=lambda p: f"{p.parent.name}-{p.stem[3:]}")
def test_no_cxx_runtime_symbol_is_bound_to_qt(plugin):
    runtime = {name for name, _ in dynamic_symbols(LIBSTDCXX, undefined=False)}
    imports = dynamic_symbols(plugin, undefined=True)
    bound_to_qt = sorted(name for name, version in imports if version.startswith("Qt_") and name in runtime)
    assert not bound_to_qt, f"C++ runtime symbols bound to Qt's version: {bound_to_qt}"
    # The one that bit us, where the plugin uses it: sized operator delete comes from libstdc++.
    versions = {version for name, version in imports if name == "_ZdlPvm"}
    assert versions <= {"CXXABI_1.3.9"}, versions


@pytest.mark.parametrize("plugin", built_plugins(), ids=lambda p: f"{p.parent.name}-{p.stem[3:]}")
def test_plugin_needs_meshlab_common_and_no_rpath(plugin):
    dynamic = subprocess.run(["readelf", "-d", str(plugin)], check=True, capture_output=True, text=True).stdout
    assert "[libmeshlab-common.so]" in dynamic
    assert "RPATH" not in dynamic and "RUNPATH" not in dynamic  # the host has its libraries loaded
