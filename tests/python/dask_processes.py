"""A real Dask cluster for the tests: `python -m dask scheduler` and `python -m dask worker`
processes on 127.0.0.1 (separate processes, as on a studio's machines), and checks that every
process a test started is gone at its end."""
import json
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Dict, List, Optional

import psutil

START_SECONDS = 60


class LoopbackCluster:
    """A scheduler and `workers` worker processes (one thread, 1 GB, --death-timeout 10 each).

    scheduler_env / worker_env: extra environment variables of those processes (e.g. Dask
    settings, the batch's test-only fault). folder: where the scheduler file and the workers'
    scratch space go. Use as a context manager; `address` is the scheduler's.
    """

    def __init__(self, folder: Path, workers: int = 2, scheduler_env: Optional[Dict[str, str]] = None,
                 worker_env: Optional[Dict[str, str]] = None):
        self.folder = Path(folder)
        self.folder.mkdir(parents=True, exist_ok=True)
        self.scheduler_file = self.folder / "scheduler.json"
        self.workers = workers
        self.scheduler_env = dict(os.environ, **(scheduler_env or {}))
        self.worker_env = dict(os.environ, **(worker_env or {}))
        self.processes: List[subprocess.Popen] = []
        self.address = ""

    def __enter__(self) -> "LoopbackCluster":
        self._start([sys.executable, "-m", "dask", "scheduler", "--host", "127.0.0.1", "--port", "0",
                     "--dashboard-address", "127.0.0.1:0", "--scheduler-file", str(self.scheduler_file)],
                    self.scheduler_env, "scheduler")
        deadline = time.monotonic() + START_SECONDS
        while not self.scheduler_file.exists():
            assert time.monotonic() < deadline and self.processes[0].poll() is None, "the scheduler did not start"
            time.sleep(0.05)
        self.address = json.loads(self.scheduler_file.read_text())["address"]
        for index in range(self.workers):
            self._start([sys.executable, "-m", "dask", "worker", self.address, "--nthreads", "1", "--memory-limit", "1GB",
                         "--death-timeout", "10", "--host", "127.0.0.1", "--dashboard-address", "127.0.0.1:0",
                         "--local-directory", str(self.folder / f"worker-{index}")], self.worker_env, f"worker-{index}")
        return self

    def _start(self, command: List[str], env: Dict[str, str], log_name: str) -> None:
        """Start one process, its output in <folder>/<log_name>.log."""
        log = open(self.folder / f"{log_name}.log", "wb")
        self.processes.append(subprocess.Popen(command, env=env, stdin=subprocess.DEVNULL, stdout=log,
                                               stderr=subprocess.STDOUT))
        log.close()

    def descendants(self) -> List[psutil.Process]:
        """Every process started for the cluster, the nannies' worker processes included."""
        found = []
        for process in self.processes:
            try:
                parent = psutil.Process(process.pid)
                found += [parent] + parent.children(recursive=True)
            except psutil.NoSuchProcess:
                pass
        return found

    def __exit__(self, *exc_info) -> None:
        everything = self.descendants()
        for process in reversed(self.processes):  # workers first, then the scheduler
            process.terminate()
            try:
                process.wait(timeout=30)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
        assert_all_gone(everything)


def assert_all_gone(processes: List[psutil.Process], timeout: float = 15.0) -> None:
    """Fail unless every one of these processes has exited (waiting up to `timeout` seconds);
    the stragglers are killed so that no test leaves a process behind."""
    _, alive = psutil.wait_procs(processes, timeout=timeout)
    for process in alive:
        process.kill()
    assert not alive, f"processes still running: {[p.pid for p in alive]}"
