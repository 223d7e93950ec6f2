"""`meshik view` against a hostile browser page, local process and command line (issue 23).

Families:
- the command line: ports outside 0..65535 (70000 gave an OverflowError traceback), not numbers,
  a folder that is missing or a file: exit 2 (1 for the folder), one line;
- Host headers: anything but 127.0.0.1 or localhost with the server's port is answered 421 (a
  DNS-rebinding page could otherwise read the folder);
- a served file swapped between a real file and a link to an outside file while a client reads
  it (before: 329 of 3,000 answers carried the outside file);
- a large file is streamed (the server's memory does not grow by its size), and a folder that
  disappears is answered 404 without a traceback.
"""
import http.client
import os
import shutil
import signal
import subprocess
import sys
import threading

import psutil
import pytest

from hostile_checks import CLI, assert_refused, run_forked
from meshik.preview.server import preview_server


@pytest.fixture()
def served(tmp_path):
    """(folder, port) of a preview server on tmp_path/out serving in a thread."""
    folder = tmp_path / "out"
    folder.mkdir()
    (folder / "inside.txt").write_text("inside")
    server = preview_server(folder, port=0)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        yield folder, server.server_address[1]
    finally:
        server.shutdown()
        server.server_close()


def _get(port, path, host=None):
    """(status, body) of GET path with Host `host` (default 127.0.0.1:port; "" sends none)."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
    try:
        connection.putrequest("GET", path, skip_host=True)
        if host != "":
            connection.putheader("Host", host if host is not None else f"127.0.0.1:{port}")
        connection.endheaders()
        response = connection.getresponse()
        return response.status, response.read()
    finally:
        connection.close()


@pytest.mark.parametrize("args, expected", [
    (["--port", "70000"], "expected a port from 0 to 65535"), (["--port", "-1"], "expected an integer >= 0"),
    (["--port", "65536"], "expected a port"), (["--port", "eighty"], "--port"), (["--port", str(2 ** 64)], "expected a port")])
def test_ports_outside_the_range(tmp_path, args, expected):
    assert_refused(run_forked(["view", tmp_path, *args], timeout=30), expected, work=tmp_path, allowed=())


@pytest.mark.parametrize("make", ["missing", "a file"])
def test_folders_that_cannot_be_served(tmp_path, make):
    target = tmp_path / "target"
    if make == "a file":
        target.write_text("x")
    outcome = run_forked(["view", target, "--port", "0"], timeout=30)
    assert_refused(outcome, str(target), work=tmp_path, allowed=("target",))


HOSTS = {"evil.example": 421, "127.0.0.1:1": 421, "": 421, "localhost.evil.example:{port}": 421, "[::1]:{port}": 421,
         "127.0.0.1.nip.io:{port}": 421, "localhost:{port}": 200, "127.0.0.1:{port}": 200, "LOCALHOST:{port}": 200}


@pytest.mark.parametrize("host", sorted(HOSTS))
def test_host_header(served, host):
    folder, port = served
    status, body = _get(port, "/inside.txt", host.format(port=port))
    assert status == HOSTS[host]
    assert (body == b"inside") == (status == 200)


def test_a_file_swapped_for_an_outside_link_mid_read_is_never_served(served, tmp_path):
    folder, port = served
    secret = tmp_path / "secret.txt"
    secret.write_bytes(b"SECRET" * 1000)
    real, link, served_name = folder / ".real", folder / ".link", folder / "swap.txt"
    stop = threading.Event()

    def swapper():
        while not stop.is_set():
            real.write_bytes(b"public" * 1000)
            os.replace(real, served_name)
            link.unlink(missing_ok=True)
            link.symlink_to(secret)
            os.replace(link, served_name)

    thread = threading.Thread(target=swapper, daemon=True)
    thread.start()
    try:
        answers = [_get(port, "/swap.txt") for _ in range(600)]
    finally:
        stop.set()
        thread.join()
    assert not [body for _, body in answers if b"SECRET" in body]
    assert {status for status, _ in answers} <= {200, 404} and any(status == 200 for status, _ in answers)


def test_large_files_are_streamed_and_a_vanished_folder_is_404(tmp_path):
    folder = tmp_path / "out"
    folder.mkdir()
    with open(folder / "big.bin", "wb") as stream:
        stream.truncate(1 << 30)  # 1 GiB, sparse
    process = subprocess.Popen([sys.executable, "-c", CLI, "view", str(folder), "--port", "0"], stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True, start_new_session=True)
    try:
        line = process.stdout.readline()
        port = int(line.rsplit(":", 1)[1].split("/")[0])
        baseline = psutil.Process(process.pid).memory_info().rss
        connection = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
        connection.request("GET", "/big.bin")
        response = connection.getresponse()
        received, peak = 0, baseline
        while chunk := response.read(1 << 22):
            received += len(chunk)
            peak = max(peak, psutil.Process(process.pid).memory_info().rss)
        connection.close()
        assert received == 1 << 30
        assert peak - baseline < 128 << 20, f"the server grew by {(peak - baseline) >> 20} MB for a 1 GiB file"
        shutil.rmtree(folder)
        assert _get(port, "/")[0] == 404 and _get(port, "/big.bin")[0] == 404
    finally:
        process.send_signal(signal.SIGINT)
        _, error = process.communicate(timeout=30)
    assert process.returncode == 0 and error.strip() == "", error
