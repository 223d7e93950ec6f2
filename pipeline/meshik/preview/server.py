"""`meshik view OUT`: serves an output folder's preview on 127.0.0.1 with Python's http.server.

Served: "/" (the page, made from the folder's jobs at each request), "/viewer/..." (the app and the
fixed list of npm files, meshik.preview.site) and the regular files inside OUT; nothing else: a path
that leaves OUT (.., any symbolic link on the way) is answered 404. A file is opened once, one path
component at a time from OUT's own descriptor without following links (open_inside), and what was
opened is checked to be a regular file before its bytes are streamed: another process swapping a
served file for a link between a check and the read cannot make the server send an outside file.
A request whose Host header is not 127.0.0.1 or localhost with the server's port is answered 421
(a DNS-rebinding page in a browser could otherwise read the folder). GET and HEAD only.
"""
import mimetypes
import os
import shutil
import stat
import sys
from functools import partial
from io import BytesIO
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import BinaryIO, Optional, Tuple
from urllib.parse import unquote, urlsplit

from meshik.errors import OutputError
from meshik.terminal_text import one_line
from meshik.preview.site import check_vendor_files, index_html, viewer_file

HOST = "127.0.0.1"
_TYPES = {".js": "text/javascript", ".mjs": "text/javascript", ".wasm": "application/wasm",
          ".glb": "model/gltf-binary", ".json": "application/json", ".css": "text/css", ".html": "text/html"}
_CHUNK = 1 << 20


def preview_server(out_dir, port: int = 8000) -> ThreadingHTTPServer:
    """An HTTP server (not yet serving) for out_dir's preview on HOST:port (0: any free port).
    Raises OutputError when out_dir is not a folder, the port is outside 0..65535 or the npm files
    are missing."""
    root = Path(out_dir).resolve()
    if not root.is_dir():
        raise OutputError(f"{out_dir}: not a folder")
    if isinstance(port, bool) or not isinstance(port, int) or not 0 <= port <= 65535:
        raise OutputError(f"port {port!r} is not a TCP port (0 to 65535)")
    check_vendor_files()
    return _PreviewServer((HOST, port), partial(_PreviewHandler, root))


class _PreviewServer(ThreadingHTTPServer):
    """ThreadingHTTPServer that drops a connection the client closed mid-answer silently and reports
    any other failure of one request as one line on stderr (not a traceback)."""

    def handle_error(self, request, client_address) -> None:
        """Called by socketserver inside its except block for the failed request."""
        error = sys.exc_info()[1]
        if not isinstance(error, ConnectionError):
            print(one_line(f"meshik view: a request failed: {type(error).__name__}: {error}"), file=sys.stderr)


def open_request(root: Path, url: str) -> Optional[Tuple[BinaryIO, int, str]]:
    """(binary stream, byte size, suffix such as ".glb") of what URL `url` serves from output folder
    `root` (the page, a viewer file, or a regular file inside `root` opened by open_inside), or None.
    Raises OSError when `root` itself cannot be read (e.g. it was removed)."""
    relative = unquote(urlsplit(url).path).lstrip("/")
    if "\0" in relative or any(part == ".." for part in relative.split("/")):
        return None
    if relative in ("", "index.html"):
        data = index_html(root).encode("utf-8")
        return BytesIO(data), len(data), ".html"
    if relative.startswith("viewer/"):
        found = viewer_file(relative)
        if found is None or not found.is_file():
            return None
        stream = open(found, "rb")
    else:
        stream = open_inside(root, relative)
        if stream is None:
            return None
    return stream, os.fstat(stream.fileno()).st_size, Path(relative).suffix


def open_inside(root: Path, relative: str) -> Optional[BinaryIO]:
    """The regular file `root/relative` opened for reading, or None when any component of
    `relative` is missing, a symbolic link, or not a folder (the last: not a regular file).

    Each component is opened relative to its parent's descriptor with O_NOFOLLOW, so what is
    returned lies inside `root` whatever other processes do to the names meanwhile."""
    parts = [part for part in relative.split("/") if part]
    if not parts or any(part in (".", "..") for part in parts):
        return None
    descriptors = []
    try:
        descriptors.append(os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC))
        for part in parts[:-1]:
            descriptors.append(os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC,
                                       dir_fd=descriptors[-1]))
        # O_NONBLOCK: opening a FIFO must not wait for a writer (it is refused below anyway)
        fd = os.open(parts[-1], os.O_RDONLY | os.O_NOFOLLOW | os.O_NONBLOCK | os.O_CLOEXEC, dir_fd=descriptors[-1])
    except (OSError, ValueError):
        return None
    finally:
        for descriptor in descriptors:
            os.close(descriptor)
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        return None
    os.set_blocking(fd, True)
    return os.fdopen(fd, "rb")


class _PreviewHandler(BaseHTTPRequestHandler):
    """GET / HEAD of open_request's answers; 404 for everything else, 421 for a foreign Host.
    HTTP/1.1 (keep-alive, every answer has its Content-Length)."""

    protocol_version = "HTTP/1.1"

    def __init__(self, root: Path, *args, **kwargs):
        self.root = root
        super().__init__(*args, **kwargs)

    def do_GET(self) -> None:
        """Send the answer with its body."""
        self._answer(body=True)

    def do_HEAD(self) -> None:
        """Send the answer's headers only."""
        self._answer(body=False)

    def _answer(self, body: bool) -> None:
        """Headers (and body, streamed) of the page or file, 421 for a foreign Host header, or 404
        (the folder or file gone, a link, anything outside the folder)."""
        port = self.server.server_address[1]
        allowed = {f"{HOST}:{port}", f"localhost:{port}"} | ({HOST, "localhost"} if port == 80 else set())
        if (self.headers.get("Host") or "").strip().lower() not in allowed:
            self.send_error(HTTPStatus.MISDIRECTED_REQUEST, "this server answers only to 127.0.0.1 and localhost")
            return
        try:
            found = open_request(self.root, self.path)
        except OSError:  # the served folder disappeared or cannot be read any more
            found = None
        if found is None:
            self.send_error(HTTPStatus.NOT_FOUND, "not part of this preview")
            return
        stream, size, suffix = found
        with stream:
            self.send_response(HTTPStatus.OK)
            self.send_header("Content-Type", _TYPES.get(suffix) or mimetypes.guess_type(f"x{suffix}")[0]
                             or "application/octet-stream")
            self.send_header("Content-Length", str(size))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            if body:
                shutil.copyfileobj(stream, self.wfile, _CHUNK)

    def log_message(self, format: str, *args) -> None:  # noqa: A002 - the base class's name
        """Quiet: no line per request."""
