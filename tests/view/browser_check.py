#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Loads a local HTML page in headless Debian chromium and checks it.

Drives chromium through the DevTools protocol over a pipe
(--remote-debugging-pipe: NUL-terminated JSON on file descriptors 3 and 4),
with the Python standard library only. The page is loaded from disk with the
network emulated offline (and a dead proxy), the script waits until the page
says it drew a frame (window.subfabStatus.frames > 0), takes a PNG
screenshot (the whole page with --full-page), and collects every error: an
uncaught exception, console.error / console.assert, a log entry of level
error (a blocked or failed load), and the errors the page recorded itself.

Used as a module by browser_test.py; by hand:
    python3 browser_check.py PAGE.html [--hash check] [--png out.png]
Exit 0 when the page drew a frame without errors, 1 otherwise, 77 when no
chromium is installed (ctest's SKIP_RETURN_CODE).
"""
import argparse
import base64
import fcntl
import json
import os
import select
import shutil
import struct
import subprocess
import sys
import tempfile
import time
import zlib

SKIP = 77


class BrowserError(Exception):
    pass


def find_chromium():
    """The browser: $SUBFAB_CHROMIUM when set (only that; e.g. SUBFAB_CHROMIUM=none
    to skip the browser tests), else chromium on the PATH."""
    names = [os.environ["SUBFAB_CHROMIUM"]] if "SUBFAB_CHROMIUM" in os.environ else ["chromium", "chromium-browser"]
    for name in names:
        if shutil.which(name):
            return shutil.which(name)
    return None


class Chromium:
    """A headless chromium driven over --remote-debugging-pipe."""

    def __init__(self, binary, width, height):
        self.profile = tempfile.mkdtemp(prefix="subfab-chromium-")
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()

        def child_fds():
            # The browser reads commands on fd 3 and writes replies on fd 4.
            a = fcntl.fcntl(to_browser_r, fcntl.F_DUPFD, 10)
            b = fcntl.fcntl(from_browser_w, fcntl.F_DUPFD, 10)
            os.dup2(a, 3)
            os.dup2(b, 4)

        args = [binary, "--headless", "--remote-debugging-pipe", "--no-sandbox", "--no-first-run",
                "--no-default-browser-check", "--disable-extensions", "--disable-background-networking",
                "--disable-component-update", "--disable-sync", "--mute-audio",
                "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--ignore-gpu-blocklist",
                "--proxy-server=127.0.0.1:9", "--host-resolver-rules=MAP * ~NOTFOUND",
                "--user-data-dir=" + self.profile, "--window-size=%d,%d" % (width, height), "about:blank"]
        self.stderr = tempfile.TemporaryFile()
        self.process = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                                        stderr=self.stderr, preexec_fn=child_fds, close_fds=False)
        os.close(to_browser_r)
        os.close(from_browser_w)
        self.buffer = b""
        self.next_id = 0
        self.events = []

    def send(self, method, params=None, session=None, timeout=60):
        self.next_id += 1
        message = {"id": self.next_id, "method": method, "params": params or {}}
        if session:
            message["sessionId"] = session
        os.write(self.to_browser, json.dumps(message).encode() + b"\0")
        deadline = time.monotonic() + timeout
        while True:
            reply = self._read(deadline)
            if reply.get("id") == self.next_id:
                if "error" in reply:
                    raise BrowserError("%s failed: %s" % (method, reply["error"]))
                return reply.get("result", {})
            self.events.append(reply)

    def _read(self, deadline):
        while b"\0" not in self.buffer:
            left = deadline - time.monotonic()
            if left <= 0:
                raise BrowserError("chromium did not answer in time")
            ready, _, _ = select.select([self.from_browser], [], [], left)
            if ready:
                chunk = os.read(self.from_browser, 1 << 20)
                if not chunk:
                    raise BrowserError("chromium closed the pipe: " + self._stderr_tail())
                self.buffer += chunk
        text, self.buffer = self.buffer.split(b"\0", 1)
        return json.loads(text)

    def _stderr_tail(self):
        try:
            self.process.wait(timeout=5)
            self.stderr.seek(0)
            return self.stderr.read().decode(errors="replace")[-2000:]
        except Exception:  # noqa: BLE001 -- best effort diagnostics
            return "(no output)"

    def close(self):
        try:
            self.send("Browser.close", timeout=10)
        except Exception:  # noqa: BLE001 -- the browser may already be gone
            pass
        try:
            self.process.wait(timeout=10)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()
        os.close(self.to_browser)
        os.close(self.from_browser)
        self.stderr.close()
        shutil.rmtree(self.profile, ignore_errors=True)


def errors_in(events, session):
    """Error messages among the DevTools events of `session`."""
    out = []
    for e in events:
        if session is not None and e.get("sessionId") != session:
            continue
        method, p = e.get("method"), e.get("params", {})
        if method == "Runtime.exceptionThrown":
            d = p.get("exceptionDetails", {})
            out.append("exception: " + d.get("exception", {}).get("description", d.get("text", "?")))
        elif method == "Runtime.consoleAPICalled" and p.get("type") in ("error", "assert"):
            out.append("console.%s: %s" % (p["type"], " ".join(str(a.get("value", a.get("description", "")))
                                                              for a in p.get("args", []))))
        elif method == "Log.entryAdded" and p.get("entry", {}).get("level") == "error":
            entry = p["entry"]
            out.append("log: %s %s" % (entry.get("text", ""), entry.get("url", "")))
    return out


class Page:
    """One page at a time in one headless chromium: open() loads a file
    (a new tab each time, so a new #hash reloads), then screenshot(),
    click(), evaluate(); errors() lists everything that went wrong so far."""

    def __init__(self, width=1000, height=760):
        binary = find_chromium()
        if not binary:
            raise FileNotFoundError("chromium")
        self.width, self.height = width, height
        self.browser = Chromium(binary, width, height)
        self.session = None
        self.target = None
        self.page_errors = []

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.browser.close()

    def send(self, method, params=None):
        return self.browser.send(method, params, session=self.session)

    def evaluate(self, expression):
        r = self.send("Runtime.evaluate", {"expression": expression, "returnByValue": True})
        return r.get("result", {}).get("value")

    def status(self):
        value = self.evaluate("JSON.stringify(window.subfabStatus || null)")
        return json.loads(value) if value else None

    def open(self, path, hash_part="", timeout=90):
        """Loads `path` with the network off and waits for its first frame;
        returns the page's status."""
        self._collect()
        if self.target:
            self.browser.send("Target.closeTarget", {"targetId": self.target})
        self.target = self.browser.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        self.session = self.browser.send("Target.attachToTarget", {"targetId": self.target, "flatten": True})["sessionId"]
        for method in ("Runtime.enable", "Log.enable", "Page.enable", "Network.enable"):
            self.send(method)
        self.send("Network.emulateNetworkConditions",
                  {"offline": True, "latency": 0, "downloadThroughput": -1, "uploadThroughput": -1})
        self.send("Emulation.setDeviceMetricsOverride",
                  {"width": self.width, "height": self.height, "deviceScaleFactor": 1, "mobile": False})
        url = "file://" + os.path.abspath(path) + (("#" + hash_part) if hash_part else "")
        self.send("Page.navigate", {"url": url})
        deadline = time.monotonic() + timeout
        status = None
        while time.monotonic() < deadline:
            status = self.status()
            if status and (status.get("frames", 0) > 0 or status.get("errors")):
                break
            time.sleep(0.2)
        if not status or status.get("frames", 0) == 0:
            raise BrowserError("%s: the page drew no frame in %d s (status %s; errors %s)"
                               % (path, timeout, status, errors_in(self.browser.events, self.session)))
        return status

    def screenshot(self, png_path, full_page=False):
        params = {"format": "png"}
        if full_page:
            metrics = self.send("Page.getLayoutMetrics")
            size = metrics.get("cssContentSize", metrics.get("contentSize"))
            params["clip"] = {"x": 0, "y": 0, "width": size["width"], "height": size["height"], "scale": 1}
            params["captureBeyondViewport"] = True
        shot = self.send("Page.captureScreenshot", params)
        with open(png_path, "wb") as f:
            f.write(base64.b64decode(shot["data"]))

    def click(self, x, y):
        for kind in ("mouseMoved", "mousePressed", "mouseReleased"):
            self.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": "left",
                                                   "buttons": 0 if kind == "mouseMoved" else 1, "clickCount": 1})

    def _collect(self):
        if self.session:
            status = self.status() or {}
            for e in status.get("errors", []):
                if "page: " + e not in self.page_errors:
                    self.page_errors.append("page: " + e)

    def errors(self):
        """Every error seen so far (DevTools events and the pages' own records)."""
        self._collect()
        found = list(self.page_errors)
        self.page_errors = []
        seen = set()
        for e in errors_in(self.browser.events, None):
            if e not in seen:
                seen.add(e)
                found.append(e)
        return found


def load_page(path, png_path, hash_part="", full_page=False):
    """Loads `path`, waits for its first frame, writes a screenshot to
    `png_path`; returns (status of the page, list of errors)."""
    with Page() as page:
        page.open(path, hash_part)
        page.screenshot(png_path, full_page)
        status = page.status()
        return status, page.errors()


def read_png(path):
    """(width, height, rows) of an 8-bit RGB or RGBA PNG; rows[y] is a bytes
    object of width * 3 RGB values."""
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError(path + ": not a PNG")
    pos, idat, width, height, channels = 8, b"", 0, 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, ctype = struct.unpack(">IIBB", body[:10])
            if depth != 8 or ctype not in (2, 6) or body[12] != 0:
                raise ValueError(path + ": only 8-bit non-interlaced RGB(A) PNGs are read")
            channels = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        previous = line
        if channels == 4:
            rgb = bytearray(width * 3)
            rgb[0::3], rgb[1::3], rgb[2::3] = line[0::4], line[1::4], line[2::4]
            rows.append(bytes(rgb))
        else:
            rows.append(bytes(line))
    return width, height, rows


def color_counts(rows):
    """{(r, g, b): number of pixels}."""
    counts = {}
    for row in rows:
        for i in range(0, len(row), 3):
            key = (row[i], row[i + 1], row[i + 2])
            counts[key] = counts.get(key, 0) + 1
    return counts


def hue_of(rgb):
    """(hue in degrees, saturation) of an RGB triple."""
    r, g, b = rgb
    hi, lo = max(rgb), min(rgb)
    if hi == 0 or hi == lo:
        return 0.0, 0.0
    d = float(hi - lo)
    if hi == r:
        h = ((g - b) / d) % 6
    elif hi == g:
        h = (b - r) / d + 2
    else:
        h = (r - g) / d + 4
    return 60.0 * h, d / hi


def pixels_of_hue(counts, hue, tolerance=6.0, min_saturation=0.3):
    """Pixels whose hue is within `tolerance` degrees of `hue`."""
    n = 0
    for rgb, k in counts.items():
        h, s = hue_of(rgb)
        if s >= min_saturation and min(abs(h - hue), 360 - abs(h - hue)) <= tolerance:
            n += k
    return n


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("page")
    parser.add_argument("--hash", default="")
    parser.add_argument("--png", default="page.png")
    parser.add_argument("--full-page", action="store_true")
    args = parser.parse_args()
    try:
        status, errors = load_page(args.page, args.png, args.hash, full_page=args.full_page)
    except FileNotFoundError:
        print("SKIPPED: no chromium installed (scripts/setup.sh installs it)")
        return SKIP
    print("status:", status)
    for e in errors:
        print("ERROR:", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
