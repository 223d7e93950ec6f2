"""pymeshlab for the pipeline, imported on a thread that lives as long as the process.

Why: importing pymeshlab starts Qt and builds MeshLab's plugin manager, a C++ static whose Qt
objects belong to the importing thread. When that thread ends before the process (a Dask worker's
job thread, a thread pool's thread), Qt frees the thread's QThreadData while those objects still
refer to it, and at exit the plugin manager's destructor decrements the freed block's reference
count. The write lands in a freed 120-byte heap chunk and corrupts glibc's free list: the process
then aborts at exit ("malloc_consolidate(): unaligned fastbin chunk detected", SIGABRT), after
its work was done. Imported on the main thread, or on a parked thread that never ends, Qt's data
for it is never freed early.
"""
import importlib
import threading
from types import ModuleType

_lock = threading.Lock()
_imported = False


def pymeshlab_module() -> ModuleType:
    """The pymeshlab module. Its first import (made here) runs on the calling thread when that is
    the main thread, otherwise on a daemon thread parked until the process exits. Raises what the
    import raises."""
    global _imported
    with _lock:
        if not _imported:
            if threading.current_thread() is threading.main_thread():
                _import_pymeshlab()
            else:
                _import_on_parked_thread()
            _imported = True
    return importlib.import_module("pymeshlab")


def _import_on_parked_thread() -> None:
    """Import pymeshlab on a new daemon thread that then waits forever; returns once it is
    imported, raising the import's exception if it failed."""
    imported = threading.Event()
    failure = []

    def import_and_park() -> None:
        try:
            _import_pymeshlab()
        except BaseException as error:  # noqa: BLE001 - handed to the caller
            failure.append(error)
        imported.set()
        threading.Event().wait()  # never set: this thread's Qt data must outlive every Qt object

    threading.Thread(target=import_and_park, name="meshik-pymeshlab-owner", daemon=True).start()
    imported.wait()
    if failure:
        raise failure[0]


def _import_pymeshlab() -> None:
    """Import pymeshlab. A KeyboardInterrupt (Ctrl+C, or SIGTERM through the command line's
    handler) that arrives while its C++ extension initializes comes back from the import as an
    ImportError ("initialization failed") caused by it: that interrupt is raised again as itself, so
    that an interrupted run stops as interrupted (exit status 130) and not as a failed import."""
    try:
        importlib.import_module("pymeshlab")
    except ImportError as error:
        if isinstance(error.__cause__, KeyboardInterrupt):
            raise error.__cause__ from None
        raise
