"""Processes that ran the pipeline on a thread other than the main one leave with an intact heap:
importing pymeshlab on a thread that ends first (a batch worker's job thread) used to make the
process corrupt glibc's heap at exit ("malloc_consolidate(): unaligned fastbin chunk detected",
SIGABRT) after its work was done (see meshik.inputs.meshlab_module).

The corruption happens after Python has finished (in C++ static destructors), and glibc notices it
only when something consolidates that heap afterwards, so by chance. To see it every time, the
processes of these tests preload a tiny library whose destructor (run after every other exit
handler) makes glibc check all its heaps (malloc_trim) and then prints HEAP_OK."""
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

HEAP_OK = "meshik-test: heap intact at exit"
MESHIK = Path(sys.executable).parent / "meshik"

_CHECK_SOURCE = r"""
#include <malloc.h>
#include <string.h>
#include <unistd.h>
/* Runs after every exit handler: malloc_trim(0) walks every heap's free lists and aborts on a
   corrupted one; a process that gets past it says so on stderr. */
__attribute__((destructor)) static void check_heap_at_exit(void) {
  static const char ok[] = "%s\n";
  malloc_trim(0);
  (void)!write(2, ok, sizeof(ok) - 1);
}
"""


@pytest.fixture(scope="module")
def heap_check_library(tmp_path_factory) -> Path:
    """A shared library to LD_PRELOAD: checks the heap at exit and prints HEAP_OK (needs a C compiler)."""
    compiler = shutil.which("cc") or shutil.which("gcc")
    if compiler is None:
        pytest.skip("no C compiler to build the heap check with")
    folder = tmp_path_factory.mktemp("heap_check")
    (folder / "heap_check.c").write_text(_CHECK_SOURCE % HEAP_OK)
    library = folder / "libheap_check.so"
    subprocess.run([compiler, "-shared", "-fPIC", "-O1", "-o", str(library), str(folder / "heap_check.c")], check=True)
    return library


def run_checked(command, library: Path, cwd: Path) -> subprocess.CompletedProcess:
    """Run `command` (and every process it starts) with the heap check preloaded; its output as text."""
    env = dict(os.environ, LD_PRELOAD=str(library), PYTHONFAULTHANDLER="1")
    return subprocess.run(command, cwd=cwd, env=env, capture_output=True, text=True, timeout=120)


def test_the_heap_check_sees_pymeshlab_imported_on_a_finished_thread(heap_check_library, tmp_path):
    # The mistake the batch avoids, made on purpose: the check must catch it (else the test below
    # proves nothing). If a pymeshlab release stops corrupting its heap here, this test says so.
    script = "import threading\nt = threading.Thread(target=lambda: __import__('pymeshlab'))\nt.start(); t.join()\n"
    result = run_checked([sys.executable, "-c", script], heap_check_library, tmp_path)
    assert result.returncode == -6 and "malloc" in result.stderr, (result.returncode, result.stderr[-2000:])


def test_pose_job_on_a_finished_thread_leaves_an_intact_heap(heap_check_library, samples_dir, tmp_path):
    script = (f"import threading\nfrom meshik.pipeline import pose_job\n"
              f"job = threading.Thread(target=pose_job, args=({str(samples_dir / 'bar' / 'animation.json')!r}, "
              f"{str(tmp_path / 'out')!r}), kwargs=dict(quiet=True))\njob.start(); job.join()\n")
    result = run_checked([sys.executable, "-c", script], heap_check_library, tmp_path)
    assert result.returncode == 0 and "malloc" not in result.stderr, (result.returncode, result.stderr[-2000:])
    assert HEAP_OK in result.stderr
    assert (tmp_path / "out" / "report.json").is_file()


def test_pymeshlab_is_imported_on_a_thread_that_outlives_the_caller():
    script = ("import threading\nfrom meshik.inputs.meshlab_module import pymeshlab_module\n"
              "found = []\nworker = threading.Thread(target=lambda: found.append(pymeshlab_module()))\n"
              "worker.start(); worker.join()\n"
              "owners = [t for t in threading.enumerate() if t.name == 'meshik-pymeshlab-owner']\n"
              "print(found[0].__name__, len(owners), owners[0].is_alive(), owners[0].daemon)\n")
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert result.stdout.split() == ["pymeshlab", "1", "True", "True"], result.stderr[-2000:]


def test_batch_workers_exit_with_an_intact_heap(heap_check_library, samples_dir, tmp_path):
    for sample in ("bar", "flag"):
        shutil.copytree(samples_dir / sample, tmp_path / sample)
    for run, bits in enumerate((11, 12)):  # two batches: two fresh clusters, workers started and stopped
        result = run_checked([str(MESHIK), "batch", str(tmp_path / "bar" / "animation.json"),
                              str(tmp_path / "flag" / "animation.json"), "--out", str(tmp_path / "out"),
                              "--jobs", "2", "--quiet", "--quantization-bits", str(bits)],
                             heap_check_library, tmp_path)
        assert result.returncode == 0, result.stderr[-3000:]
        assert "malloc" not in result.stderr and "Fatal Python error" not in result.stderr, result.stderr[-3000:]
        # the batch's own process and its two workers (the nannies live in the batch's process)
        assert result.stderr.count(HEAP_OK) >= 3, (run, result.stderr[-3000:])
