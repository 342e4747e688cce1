"""The web view's HTTP server: the standard library's ThreadingHTTPServer, on 127.0.0.1 only.

    GET /                  the page (static/: index.html, view.js, panel.js, world.js, view.css;
                           no CDN)
    GET /events            server-sent events: "frame" (newest cycle, at most `FRAME_HZ` a second)
                           and "status" (processes, rates, goal history; once a second)
    GET /api/frame?cycle=N one past cycle (the timeline), /api/frame for the newest
    GET /api/status        as the "status" event
    GET /api/map           the world's static map (tools/view/scene.py)
    GET /api/render.png?cycle=N&agent=A   the domain's own picture (A's path), for domains the
                           page cannot draw
    GET /api/graph.svg?agent=A   A's program as a graph of goals, skills and concepts (`teleo
                           graph PROGRAM`, tools/records/program_graph.py); the header links it
    POST /api/control      {"op": "pause"|"resume"|"step"[, "cycles": N]} (Content-Type
                           application/json): the timeline's buttons, asked of the world of the
                           live launch followed, the way `teleo pause`, `step-run` and
                           `resume` ask it (tools/runs/control.py); answers {"ok", "text",
                           "outcome"} with the world's verdict, or {"ok": false, "error"}
"""

from __future__ import annotations

import json
import logging
import time
from collections.abc import Callable
from http import HTTPStatus
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer
from pathlib import Path
from typing import Any
from urllib.parse import parse_qs, urlparse

from tools.records.drawing import to_svg
from tools.records.program_graph import program_graph
from tools.runs.control import ControlError, verdict_line
from tools.view import scene
from tools.view.model import ViewModel

log = logging.getLogger(__name__)
STATIC = Path(__file__).with_name("static")
FILES = {"/": ("index.html", "text/html; charset=utf-8"),
         "/view.js": ("view.js", "text/javascript; charset=utf-8"),
         "/panel.js": ("panel.js", "text/javascript; charset=utf-8"),
         "/world.js": ("world.js", "text/javascript; charset=utf-8"),
         "/view.css": ("view.css", "text/css; charset=utf-8")}
CONTROL_OPS = ("pause", "resume", "step")
MAX_BODY = 4096     # [bytes] of a control request
FRAME_HZ = 10.0     # frames pushed per second at most (the page cannot use more)
STATUS_S = 1.0      # [s] between status events


class ViewServer(ThreadingHTTPServer):
    """Serves one model; `daemon_threads` so an open event stream never blocks shutdown."""

    daemon_threads = True

    def __init__(self, model: ViewModel, port: int = 0,
                 control: Callable[[dict], tuple[dict, str]] | None = None) -> None:
        super().__init__(("127.0.0.1", port), _Handler)
        self.model = model
        self.closing = False
        self.control = control   # asks the world of a live launch (None: no buttons)

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.server_address[1]}/"


class _Handler(BaseHTTPRequestHandler):
    server: ViewServer

    def log_message(self, fmt: str, *args: Any) -> None:  # requests go to debug logging
        log.debug("%s " + fmt, self.address_string(), *args)

    def do_GET(self) -> None:  # noqa: N802 (the name http.server calls)
        url = urlparse(self.path)
        query = {k: v[-1] for k, v in parse_qs(url.query).items()}
        model = self.server.model
        if url.path in FILES:
            name, ctype = FILES[url.path]
            self._send(HTTPStatus.OK, (STATIC / name).read_bytes(), ctype)
        elif url.path == "/events":
            self._events(model)
        elif url.path == "/api/status":
            self._json(self._status(model))
        elif url.path == "/api/map":
            self._json(model.map or {})
        elif url.path == "/api/frame":
            self._frame(model, query.get("cycle"))
        elif url.path == "/api/render.png":
            self._render(model, query.get("cycle"), query.get("agent"))
        elif url.path == "/api/graph.svg":
            self._graph(model, query.get("agent"))
        else:
            self._send(HTTPStatus.NOT_FOUND, f"no page {url.path}\n".encode(), "text/plain")

    def do_POST(self) -> None:  # noqa: N802 (the name http.server calls)
        if urlparse(self.path).path != "/api/control":
            return self._send(HTTPStatus.NOT_FOUND, f"no page {self.path}\n".encode(),
                              "text/plain")
        # application/json only: a page of another site cannot send it without asking first
        if self.headers.get("Content-Type", "").split(";")[0].strip() != "application/json":
            return self._refuse(HTTPStatus.UNSUPPORTED_MEDIA_TYPE,
                                "expected Content-Type: application/json")
        if self.server.control is None:
            return self._refuse(HTTPStatus.CONFLICT, "this view follows no live launch: "
                                "pause, step and resume are for a live lockstep launch")
        length = int(self.headers.get("Content-Length") or 0)
        try:
            event = json.loads(self.rfile.read(min(length, MAX_BODY)) or b"null")
        except ValueError:
            event = None
        op = event.get("op") if isinstance(event, dict) else None
        if op not in CONTROL_OPS:
            return self._refuse(HTTPStatus.BAD_REQUEST, f"expected {{\"op\": one of "
                                f"{list(CONTROL_OPS)}}}, got {event!r:.80}")
        ask = {"op": op, "cycles": event.get("cycles", 1)} if op == "step" else {"op": op}
        try:
            outcome, note = self.server.control(ask)
        except ControlError as exc:
            return self._refuse(HTTPStatus.CONFLICT, str(exc))
        self._json({"ok": True, "text": verdict_line(outcome, note), "outcome": outcome})

    def _status(self, model: ViewModel) -> dict[str, Any]:
        """The model's status, and whether the timeline's pause, step and resume work."""
        return {**model.status(time.time_ns()), "control": self.server.control is not None}

    def _refuse(self, status: HTTPStatus, error: str) -> None:
        self._send(status, json.dumps({"ok": False, "error": error}).encode(),
                   "application/json")

    def _frame(self, model: ViewModel, cycle: str | None) -> None:
        try:
            frame = model.frame(None if cycle is None else int(cycle))
        except ValueError:
            return self._send(HTTPStatus.BAD_REQUEST, b"cycle: expected an integer\n",
                              "text/plain")
        if frame is None:
            return self._send(HTTPStatus.NOT_FOUND, f"no cycle {cycle} held\n".encode(),
                              "text/plain")
        self._json(frame)

    def _render(self, model: ViewModel, cycle: str | None, agent: str | None) -> None:
        try:
            shown = int(cycle) if cycle else (model.newest() or 0)
        except ValueError:
            return self._send(HTTPStatus.BAD_REQUEST, b"cycle: expected an integer\n",
                              "text/plain")
        snaps = model.snapshots_for_render(shown)
        if not snaps:
            return self._send(HTTPStatus.NOT_FOUND, b"no snapshot yet\n", "text/plain")
        if agent not in model.agents:
            agent = next(iter(sorted(model.agents)), None)
        self._send(HTTPStatus.OK, scene.render_png(snaps, agent), "image/png")

    def _graph(self, model: ViewModel, agent: str | None) -> None:
        """The program of ``agent`` (default: the first) drawn as `teleo graph` draws it."""
        agent = agent if agent in model.agents else next(iter(sorted(model.agents)), None)
        program, source = model.programs.get(agent) if agent else (None, "no agent yet")
        if program is None:
            return self._send(HTTPStatus.NOT_FOUND, f"{source}\n".encode(), "text/plain")
        svg = to_svg(program_graph(program, f"{agent}: {source}"))
        self._send(HTTPStatus.OK, svg.encode(), "image/svg+xml")

    def _events(self, model: ViewModel) -> None:
        """Push frames and status until the page goes away (or the server closes)."""
        self.send_response(HTTPStatus.OK)
        self.send_header("Content-Type", "text/event-stream")
        self.send_header("Cache-Control", "no-cache")
        self.end_headers()
        seen, next_status = -1, 0.0
        try:
            while not self.server.closing:
                with model.changed:
                    if model.version == seen:
                        model.changed.wait(STATUS_S)
                    version = model.version
                now = time.monotonic()
                if version != seen:
                    seen = version
                    frame = model.frame()
                    if frame is not None:
                        self._event("frame", frame)
                if now >= next_status:
                    next_status = now + STATUS_S
                    self._event("status", self._status(model))
                time.sleep(1.0 / FRAME_HZ)
        except (BrokenPipeError, ConnectionResetError):
            log.debug("event stream closed by the page")

    def _event(self, name: str, data: dict[str, Any]) -> None:
        self.wfile.write(f"event: {name}\ndata: {json.dumps(data)}\n\n".encode())
        self.wfile.flush()

    def _json(self, data: Any) -> None:
        self._send(HTTPStatus.OK, json.dumps(data).encode(), "application/json")

    def _send(self, status: HTTPStatus, body: bytes, ctype: str) -> None:
        self.send_response(status)
        self.send_header("Content-Type", ctype)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Cache-Control", "no-store")
        self.end_headers()
        self.wfile.write(body)
