"""The per-worker example-set cache: keyed by the files' contents, bounded, and invisible in the outputs."""
import shutil

import numpy as np

from meshik.posing.example_cache import ExampleSetCache
from meshik.pipeline import pose_job
from pipeline_meshes import bend, tube_constraints, write_constraints, write_obj, write_tube_set


def test_same_contents_are_loaded_and_featured_once(tmp_path):
    tube_set = write_tube_set(tmp_path / "a", rings=8, segments=6)
    shutil.copytree(tmp_path / "a", tmp_path / "b")
    cache = ExampleSetCache(1 << 30)
    meshes_a, features_a = cache.get(tube_set["rest"], tube_set["examples"])
    meshes_b, features_b = cache.get(tmp_path / "b" / "rest.obj", [tmp_path / "b" / p.name for p in tube_set["examples"]])
    assert (cache.hits, cache.misses) == (1, 1)
    assert features_a() is features_b()  # built once
    assert meshes_b.rest_path == tmp_path / "b" / "rest.obj" and np.array_equal(meshes_a.rest, meshes_b.rest)

    # an edited file is read again
    write_obj(tmp_path / "b" / "example_1.obj", bend(tube_set["vertices"], 45, "y"), tube_set["faces"])
    meshes_c, features_c = cache.get(tmp_path / "b" / "rest.obj", [tmp_path / "b" / p.name for p in tube_set["examples"]])
    assert cache.misses == 2 and features_c() is not features_a()
    assert not np.array_equal(meshes_c.examples[0], meshes_a.examples[0])


def test_the_bound_evicts_the_least_recently_used(tmp_path):
    small = write_tube_set(tmp_path / "small", rings=8, segments=6)
    other = write_tube_set(tmp_path / "other", rings=9, segments=6)
    probe = ExampleSetCache(1 << 30)
    probe.get(small["rest"], small["examples"])
    one_entry = probe.bytes_used()
    assert one_entry > 0

    cache = ExampleSetCache(int(one_entry * 1.5))  # room for the small set only
    for tube_set in (small, other, small):
        cache.get(tube_set["rest"], tube_set["examples"])
    assert (cache.hits, cache.misses) == (0, 3) and cache.bytes_used() <= cache.max_bytes

    nothing = ExampleSetCache(0)
    nothing.get(small["rest"], small["examples"])
    nothing.get(small["rest"], small["examples"])
    assert (nothing.hits, nothing.bytes_used()) == (0, 0)


def test_outputs_do_not_depend_on_the_cache(tmp_path):
    tube_set = write_tube_set(tmp_path / "in", rings=10, segments=8)
    shot = write_constraints(tmp_path / "in" / "shot.json", tube_constraints(tube_set, frames=4))
    cache = ExampleSetCache(1 << 30)
    reports = [pose_job(shot, tmp_path / name, quiet=True, formats=("drc", "glb"), example_cache=example_cache)
               for name, example_cache in (("plain", None), ("cold", cache), ("warm", cache))]
    assert cache.hits == 1
    for name in reports[0]["outputs"]:
        plain = (tmp_path / "plain" / name).read_bytes()
        assert (tmp_path / "cold" / name).read_bytes() == plain and (tmp_path / "warm" / name).read_bytes() == plain
