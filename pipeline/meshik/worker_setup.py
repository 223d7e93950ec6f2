"""Setting up each Dask worker process before it runs a job: pymeshlab is imported on the worker's
main thread.

Why: importing pymeshlab starts Qt and builds MeshLab's plugin manager, a C++ static whose Qt
objects belong to the importing thread. Imported on a job's executor thread, those objects outlive
it: when that thread exits (the worker closing its executor), Qt frees the thread's QThreadData
while the plugin manager's QObjects still refer to it, and at process exit the plugin manager's
destructor decrements the freed block's reference count. That write lands in a freed 120-byte
heap chunk and corrupts glibc's free list: the worker then aborts at exit with
"malloc_consolidate(): unaligned fastbin chunk detected". The main thread lives until exit, so
Qt's data for it is never freed early.
"""
from distributed.diagnostics.plugin import WorkerPlugin

PLUGIN_NAME = "meshik-pymeshlab-on-main-thread"


class ImportPymeshlabOnMainThread(WorkerPlugin):
    """A worker plugin whose setup (run by the worker's event loop, on its main thread, when the
    plugin is registered and on every worker that joins later) imports pymeshlab."""

    def setup(self, worker) -> None:
        """Import pymeshlab in this worker process (worker: the distributed.Worker; returns None)."""
        import pymeshlab  # noqa: F401 - imported for its side effect: Qt started on this thread


def prepare_workers(client) -> None:
    """Register ImportPymeshlabOnMainThread on every worker of `client`'s cluster (a
    distributed.Client), current and future; registering it again replaces it."""
    client.register_plugin(ImportPymeshlabOnMainThread(), name=PLUGIN_NAME)
