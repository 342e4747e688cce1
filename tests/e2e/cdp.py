"""A headless Chromium driven over the DevTools protocol (one websocket, websocket-client): the
lightest way to test the web view in a real browser offline. Chromium comes from Debian's
package (`make browser` installs it); it is started with the flags this machine needs
(no sandbox as root, nothing fetched from the internet) and a fresh profile."""

from __future__ import annotations

import base64
import itertools
import json
import shutil
import subprocess
import time
import urllib.request
from pathlib import Path
from typing import Any

import websocket

FLAGS = ("--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync",
         "--remote-debugging-port=0", "--window-size=1400,1000")


def chromium_path() -> str:
    """The chromium on PATH; an AssertionError saying how to install it when there is none."""
    path = shutil.which("chromium") or shutil.which("chromium-browser")
    assert path, "no chromium on PATH: run `make browser` (apt-get install -y chromium)"
    return path


class Chromium:
    """One headless browser with one page; `evaluate` runs JavaScript in it."""

    def __init__(self, profile: Path) -> None:
        profile.mkdir(parents=True, exist_ok=True)
        port_file = profile / "DevToolsActivePort"
        port_file.unlink(missing_ok=True)  # a profile used before names a port long closed
        self.proc = subprocess.Popen([chromium_path(), *FLAGS, f"--user-data-dir={profile}",
                                      "about:blank"], stdout=subprocess.DEVNULL,
                                     stderr=subprocess.DEVNULL)
        try:
            self.ws = self._connect(port_file)
        except BaseException:
            self._stop()  # a browser that did not start is not left running
            raise
        self._ids = itertools.count(1)

    def _connect(self, port_file: Path) -> websocket.WebSocket:
        end = time.monotonic() + 60
        while not port_file.exists() or not port_file.read_text().strip():
            assert self.proc.poll() is None, f"chromium exited with {self.proc.returncode}"
            assert time.monotonic() < end, "chromium did not open its DevTools port in 60 s"
            time.sleep(0.1)
        port = port_file.read_text().split()[0]
        pages = json.load(urllib.request.urlopen(f"http://127.0.0.1:{port}/json/list"))
        page = next(p for p in pages if p.get("type") == "page")
        return websocket.create_connection(page["webSocketDebuggerUrl"], timeout=60,
                                           suppress_origin=True)

    def send(self, method: str, **params: Any) -> dict[str, Any]:
        """Call a DevTools method and return its result (events in between are skipped)."""
        ident = next(self._ids)
        self.ws.send(json.dumps({"id": ident, "method": method, "params": params}))
        while True:
            reply = json.loads(self.ws.recv())
            if reply.get("id") == ident:
                assert "error" not in reply, f"{method}: {reply['error']}"
                return reply["result"]

    def goto(self, url: str, timeout: float = 60) -> None:
        """Open `url` and wait until the page (its scripts included) has loaded."""
        self.send("Page.navigate", url=url)
        end = time.monotonic() + timeout
        while self.evaluate("[location.href, document.readyState]") != [url, "complete"]:
            assert time.monotonic() < end, f"{url} did not load in {timeout:g} s"
            time.sleep(0.05)

    def viewport(self, width: int, height: int) -> None:
        """Make the page's viewport exactly `width` x `height` CSS pixels (the window of
        --window-size loses some height to the browser's own frame)."""
        self.send("Emulation.setDeviceMetricsOverride", width=width, height=height,
                  deviceScaleFactor=1, mobile=False)

    def evaluate(self, expression: str) -> Any:
        """The value of a JavaScript expression in the page (JSON-able)."""
        result = self.send("Runtime.evaluate", expression=expression, returnByValue=True)
        assert "exceptionDetails" not in result, result["exceptionDetails"]
        return result["result"].get("value")

    def screenshot(self, path: Path) -> None:
        data = self.send("Page.captureScreenshot", format="png")["data"]
        path.write_bytes(base64.b64decode(data))

    def close(self) -> None:
        try:
            self.ws.close()
        finally:
            self._stop()

    def _stop(self) -> None:
        self.proc.terminate()
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
            self.proc.wait(10)

    def __enter__(self) -> Chromium:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
