"""`meshik view OUT`: serves an output folder's preview on 127.0.0.1 with Python's http.server.

Served: "/" (the page, made from the folder's jobs at each request), "/viewer/..." (the app and the
fixed list of npm files, meshik.preview.site) and the files inside OUT; nothing else: a path that
leaves OUT (.., a link pointing out) is answered 404. GET and HEAD only.
"""
import mimetypes
from functools import partial
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Optional, Tuple
from urllib.parse import unquote, urlsplit

from meshik.errors import OutputError
from meshik.preview.site import check_vendor_files, index_html, viewer_file

HOST = "127.0.0.1"
_TYPES = {".js": "text/javascript", ".mjs": "text/javascript", ".wasm": "application/wasm",
          ".glb": "model/gltf-binary", ".json": "application/json", ".css": "text/css", ".html": "text/html"}


def preview_server(out_dir, port: int = 8000) -> ThreadingHTTPServer:
    """An HTTP server (not yet serving) for out_dir's preview on HOST:port (0: any free port).
    Raises OutputError when out_dir is not a folder or the npm files are missing."""
    root = Path(out_dir).resolve()
    if not root.is_dir():
        raise OutputError(f"{out_dir}: not a folder")
    check_vendor_files()
    return ThreadingHTTPServer((HOST, port), partial(_PreviewHandler, root))


def resolve_request(root: Path, url: str) -> Optional[Tuple[str, object]]:
    """What URL `url` serves from output folder `root`: ("page", html text), ("file", Path) or None."""
    path = unquote(urlsplit(url).path)
    relative = path.lstrip("/")
    if "\0" in relative or any(part == ".." for part in relative.split("/")):
        return None
    if relative in ("", "index.html"):
        return "page", index_html(root)
    if relative.startswith("viewer/"):
        found = viewer_file(relative)
        return ("file", found) if found is not None and found.is_file() else None
    candidate = (root / relative).resolve()
    return ("file", candidate) if candidate.is_file() and root in candidate.parents else None


class _PreviewHandler(BaseHTTPRequestHandler):
    """GET / HEAD of resolve_request's answers; 404 for everything else. HTTP/1.1 (keep-alive, every
    answer has its Content-Length)."""

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
        """Headers (and body) of the resolved page or file, or 404."""
        found = resolve_request(self.root, self.path)
        if found is None:
            self.send_error(HTTPStatus.NOT_FOUND, "not part of this preview")
            return
        kind, value = found
        data = value.encode("utf-8") if kind == "page" else value.read_bytes()
        suffix = ".html" if kind == "page" else value.suffix
        self.send_response(HTTPStatus.OK)
        self.send_header("Content-Type", _TYPES.get(suffix) or mimetypes.guess_type(str(value))[0] or "application/octet-stream")
        self.send_header("Content-Length", str(len(data)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        if body:
            self.wfile.write(data)

    def log_message(self, format: str, *args) -> None:  # noqa: A002 - the base class's name
        """Quiet: no line per request."""
