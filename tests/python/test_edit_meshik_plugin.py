"""The edit plugin edit_meshik ("MeshIK: Drag to Pose") beside the filter plugin in pymeshlab 2025.7:
pymeshlab refuses an edit plugin with a clear error (it runs only IO and filter plugins), without
crashing, and the filters still work after the attempt. The tool itself is checked in the MeshLab
GUI by `make gui-check`; its GL-free logic by the ctest test_edit_meshik_logic."""
import subprocess
import sys

from plugin_helpers import plugin_path


def test_pymeshlab_refuses_the_edit_plugin_cleanly_and_the_filters_still_work(samples_dir):
    edit = plugin_path("double").with_name("libedit_meshik.so")
    assert edit.is_file(), f"{edit} is missing (run `make build`)"
    script = f"""
import pymeshlab
try:
    pymeshlab.load_plugin({str(edit)!r})
    print("loaded")
except pymeshlab.PyMeshLabException as error:
    print("refused:", error)
pymeshlab.load_plugin({str(plugin_path("double"))!r})
ms = pymeshlab.MeshSet()
for name in ["rest", "example_1", "example_2"]:
    ms.load_new_mesh({str(samples_dir / "limb")!r} + "/" + name + ".obj")
ms.set_current_mesh(0)
out = ms.apply_filter("compute_coord_meshik_blend", weights="0.5, 0.5")
print("blend layer", out["layer_id"])
"""
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert "refused: Error while loading plugin: PyMeshLab only supports IO or Filter plugins" in done.stdout
    assert "blend layer 3" in done.stdout
    assert "QAction" not in done.stderr and "QPixmap" not in done.stderr, done.stderr
