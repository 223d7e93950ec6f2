"""pyproject.toml is the one list of dependencies (issue 25): every library the package imports at run
time is one of its dependencies, and requirements.txt (the development venv's pins) pins exactly the
dependencies, the dev extra and the build requirements, each at a version they accept."""
import ast
import sys
import tomllib
from importlib.metadata import packages_distributions, version
from pathlib import Path
from typing import Dict, Set

from packaging.requirements import Requirement
from packaging.utils import canonicalize_name

ROOT = Path(__file__).resolve().parents[2]


def pyproject() -> dict:
    """pyproject.toml as a dict."""
    return tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))


def declared(section: str) -> Dict[str, Requirement]:
    """{canonical name: requirement} of one list: "dependencies", "dev" (the extra) or "build"."""
    project = pyproject()
    lists = {"dependencies": project["project"]["dependencies"],
             "dev": project["project"]["optional-dependencies"]["dev"],
             "build": project["build-system"]["requires"]}
    return {canonicalize_name(Requirement(text).name): Requirement(text) for text in lists[section]}


def pins() -> Dict[str, str]:
    """{canonical name: pinned version} of requirements.txt (every line `name==version`)."""
    found = {}
    for line in (ROOT / "requirements.txt").read_text(encoding="utf-8").splitlines():
        line = line.split("#")[0].strip()
        if line:
            requirement = Requirement(line)
            specifiers = list(requirement.specifier)
            assert len(specifiers) == 1 and specifiers[0].operator == "==", f"requirements.txt: {line} is not a pin"
            found[canonicalize_name(requirement.name)] = specifiers[0].version
    return found


def third_party_imports() -> Set[str]:
    """Top-level names of the modules the package imports (anywhere in a file, importlib.import_module
    of a literal name too) that are neither the standard library nor meshik itself."""
    names = set()
    for path in (ROOT / "pipeline" / "meshik").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                names.update(alias.name.split(".")[0] for alias in node.names)
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names.add(node.module.split(".")[0])
            elif (isinstance(node, ast.Call) and getattr(node.func, "attr", None) == "import_module"
                  and node.args and isinstance(node.args[0], ast.Constant)):  # importlib.import_module("x")
                names.add(node.args[0].value.split(".")[0])
    return {name for name in names if name not in sys.stdlib_module_names and name != "meshik"}


def test_every_library_imported_at_run_time_is_a_dependency():
    imports = third_party_imports()
    assert {"numpy", "pymeshlab", "DracoPy", "threadpoolctl", "dask", "distributed", "rich", "PIL"} <= imports
    distributions = packages_distributions()
    dependencies = set(declared("dependencies"))
    missing = {name: distributions.get(name) for name in imports
               if not {canonicalize_name(d) for d in distributions.get(name, [])} & dependencies}
    assert missing == {}, "imported by meshik but not in pyproject.toml's dependencies"


def test_requirements_pin_every_declared_package_at_an_accepted_version():
    pinned = pins()
    for section in ("dependencies", "dev", "build"):
        for name, requirement in declared(section).items():
            assert name in pinned, f"requirements.txt does not pin {name} ({section} in pyproject.toml)"
            assert requirement.specifier.contains(pinned[name], prereleases=True), \
                f"requirements.txt pins {name}=={pinned[name]}, outside pyproject.toml's {requirement}"


def test_requirements_pin_nothing_pyproject_does_not_declare():
    known = set(declared("dependencies")) | set(declared("dev")) | set(declared("build"))
    assert set(pins()) - known == set()


def test_the_development_venv_has_the_pinned_versions():
    assert {name: version(name) for name in pins()} == pins()
