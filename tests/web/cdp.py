"""A headless Chromium for the page tests, driven over the DevTools protocol
(CDP) with Debian's python3-websocket: started by the test in a process
group of its own, with a profile folder of its own, and stopped by it."""
import json
import os
import shutil
import signal
import subprocess
import tempfile
import time
import urllib.request

import websocket  # python3-websocket


class Browser:
    def __init__(self, chromium, width=1280, height=800):
        self.profile = tempfile.mkdtemp(prefix="ball-web-chromium-")
        self.proc = subprocess.Popen(
            [chromium, "--headless=new", "--no-sandbox", "--no-first-run", "--no-default-browser-check",
             "--disable-gpu-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
             "--disable-background-timer-throttling", "--disable-renderer-backgrounding",
             "--remote-debugging-address=127.0.0.1", "--remote-debugging-port=0",
             "--user-data-dir=" + self.profile, "--window-size=%d,%d" % (width, height), "about:blank"],
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
        port_file = os.path.join(self.profile, "DevToolsActivePort")
        deadline = time.time() + 30
        while not os.path.exists(port_file) or os.path.getsize(port_file) == 0:
            if time.time() > deadline or self.proc.poll() is not None:
                self.close()
                raise RuntimeError("chromium did not start")
            time.sleep(0.1)
        with open(port_file) as f:
            port = int(f.readline())
        targets = json.load(urllib.request.urlopen("http://127.0.0.1:%d/json/list" % port))
        page = [t for t in targets if t["type"] == "page"][0]
        self.ws = websocket.create_connection(page["webSocketDebuggerUrl"], timeout=30, suppress_origin=True)
        self.next_id = 0
        self.console = []  # (level, text) of console errors and exceptions
        self.send("Runtime.enable")
        self.send("Log.enable")
        self.send("Page.enable")
        self.send("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=False)

    def _note(self, m):
        method = m.get("method", "")
        if method == "Runtime.exceptionThrown":
            self.console.append(("exception", json.dumps(m["params"]["exceptionDetails"])[:500]))
        elif method == "Runtime.consoleAPICalled" and m["params"]["type"] in ("error", "assert"):
            self.console.append(("console." + m["params"]["type"], json.dumps(m["params"]["args"])[:500]))
        elif method == "Log.entryAdded" and m["params"]["entry"]["level"] == "error":
            self.console.append(("log", m["params"]["entry"].get("text", "")[:500]))

    def send(self, method, **params):
        self.next_id += 1
        me = self.next_id
        self.ws.send(json.dumps({"id": me, "method": method, "params": params}))
        while True:
            m = json.loads(self.ws.recv())
            if m.get("id") == me:
                if "error" in m:
                    raise RuntimeError("%s: %s" % (method, m["error"]))
                return m.get("result", {})
            self._note(m)

    def evaluate(self, expression):
        r = self.send("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=True)
        if "exceptionDetails" in r:
            raise RuntimeError("%s: %s" % (expression, r["exceptionDetails"]))
        return r["result"].get("value")

    def open(self, url):
        self.send("Page.navigate", url=url)

    def wait_for(self, expression, timeout, what):
        deadline = time.time() + timeout
        while time.time() < deadline:
            try:
                v = self.evaluate(expression)
            except RuntimeError:
                v = None
            if v:
                return v
            time.sleep(0.1)
        raise AssertionError("timed out after %g s waiting for %s" % (timeout, what))

    def screenshot(self, clip):
        import base64
        r = self.send("Page.captureScreenshot", format="png",
                      clip={"x": clip["x"], "y": clip["y"], "width": clip["width"], "height": clip["height"], "scale": 1})
        return base64.b64decode(r["data"])

    def close(self):
        try:
            if getattr(self, "ws", None):
                self.ws.close()
        except Exception:
            pass
        if self.proc.poll() is None:
            try:
                os.killpg(self.proc.pid, signal.SIGTERM)
                self.proc.wait(5)
            except Exception:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        shutil.rmtree(self.profile, ignore_errors=True)
