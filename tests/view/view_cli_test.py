#!/usr/bin/env python3
"""ctest label `view`: `gyrostab run --view` through the CLI, without a browser (tests/browser/ has the browser).

  view_cli_test.py GYROSTAB SOURCE_DIR WORKDIR

1. Lockstep results are bit-identical with the view: the active ship, 100 000 ticks, with and without --view
   (and once with a page connected through a raw WebSocket): signals.csv byte for byte, report.json "figures" equal.
2. Only the user reaches it: the page without the token, with a wrong token or with a foreign Host header is
   refused (403); the WebSocket with a wrong token or a foreign Origin is refused before the upgrade; the right
   token and the page's own origin are accepted, the first message is the meta message with the scene's
   columns, data follows, the end message carries report.json's figures; a message sent by the page closes the
   socket with 1008 (policy): no command is accepted.
3. Bad options are refused before the run: --view with a malformed address, --mcap into a missing directory.
Takes about 0.5 s."""
import base64
import json
import os
import shutil
import signal
import socket
import struct
import subprocess
import sys
import time
import urllib.error
import urllib.request

FAILS = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        FAILS.append(what)


def run(gyrostab, scene, out, *extra, timeout=300):
    env = dict(os.environ, GYROSTAB_PLOT_SCRIPT="")
    return subprocess.run([gyrostab, "run", scene, "--no-progress", "--ticks", "100000", "--out", out, *extra],
                          env=env, capture_output=True, text=True, timeout=timeout)


def start_view(gyrostab, scene, out, *extra):
    env = dict(os.environ, GYROSTAB_PLOT_SCRIPT="")
    p = subprocess.Popen([gyrostab, "run", scene, "--no-progress", "--ticks", "100000", "--out", out, "--view",
                          *extra], env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 30
    while time.time() < deadline:
        line = p.stderr.readline()
        if "live view of" in line:
            return p, line.split(" at ", 1)[1].strip()
    p.kill()
    raise RuntimeError("no view URL printed")


def http_status(url, headers=None):
    req = urllib.request.Request(url, headers=headers or {})
    try:
        with urllib.request.urlopen(req, timeout=10) as r:
            return r.status, r.read().decode()
    except urllib.error.HTTPError as e:
        return e.code, e.read().decode()


class WebSocket:
    """The client side of RFC 6455, enough for a test: handshake, unmasked server frames, masked client frames."""

    def __init__(self, host, port, path, origin):
        self.s = socket.create_connection((host, port), timeout=20)
        key = base64.b64encode(os.urandom(16)).decode()
        req = (f"GET {path} HTTP/1.1\r\nHost: {host}:{port}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
               f"Sec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\nOrigin: {origin}\r\n\r\n")
        self.s.sendall(req.encode())
        head = b""
        while b"\r\n\r\n" not in head:
            chunk = self.s.recv(1)
            if not chunk:
                break
            head += chunk
        self.status = int(head.split(b" ")[1]) if head else 0
        self.buf = b""

    def _read(self, n):
        while len(self.buf) < n:
            chunk = self.s.recv(65536)
            if not chunk:
                raise EOFError
            self.buf += chunk
        out, self.buf = self.buf[:n], self.buf[n:]
        return out

    def recv(self):
        """(opcode, payload) of the next whole message."""
        payload, op0 = b"", None
        while True:
            b0, b1 = self._read(2)
            op, fin, n = b0 & 0x0F, b0 & 0x80, b1 & 0x7F
            if n == 126:
                n = struct.unpack(">H", self._read(2))[0]
            elif n == 127:
                n = struct.unpack(">Q", self._read(8))[0]
            data = self._read(n)
            if op0 is None:
                op0 = op
            payload += data
            if fin:
                return op0, payload

    def send_text(self, text):
        data = text.encode()
        mask = os.urandom(4)
        head = bytes([0x81, 0x80 | len(data)]) + mask
        self.s.sendall(head + bytes(b ^ mask[i % 4] for i, b in enumerate(data)))


def main():
    gyrostab, src, work = sys.argv[1:4]
    scene = os.path.join(src, "sim/scenes/ship-roll-damper-active.toml")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)

    # 1. Bit-identical with and without the view.
    a = run(gyrostab, scene, os.path.join(work, "plain"))
    b = run(gyrostab, scene, os.path.join(work, "viewed"), "--view", "--view-linger", "0")
    check(a.returncode == 0 and b.returncode == 0, f"both runs exit 0 ({a.returncode}, {b.returncode})")
    check("live view of" in b.stderr and "token=" in b.stderr, "the view's URL with its token is printed")

    def same_outputs(other, what):
        with open(os.path.join(work, "plain/signals.csv"), "rb") as f1, open(os.path.join(other, "signals.csv"), "rb") as f2:
            check(f1.read() == f2.read(), f"signals.csv byte for byte equal {what}")
        with open(os.path.join(work, "plain/report.json")) as f1, open(os.path.join(other, "report.json")) as f2:
            check(json.load(f1)["figures"] == json.load(f2)["figures"], f"report.json figures equal {what}")

    same_outputs(os.path.join(work, "viewed"), "with --view")

    # 2. The security model, with a run whose view lingers until SIGTERM.
    p, url = start_view(gyrostab, scene, os.path.join(work, "served"), "--view-linger", "60")
    try:
        base, token = url.split("/?token=")
        host, port = base[len("http://"):].rsplit(":", 1)
        port = int(port)
        check(host == "127.0.0.1", "bound to 127.0.0.1 by default")
        check(len(token) == 32 and all(c in "0123456789abcdef" for c in token), "a 128-bit random token")
        status, body = http_status(url)
        check(status == 200 and "uPlot.iife.min.js" in body, "the page with its token: 200")
        check(http_status(base + "/")[0] == 403, "the page without a token: 403")
        check(http_status(base + "/?token=" + "0" * 32)[0] == 403, "the page with a wrong token: 403")
        check(http_status(url, {"Host": f"evil.example:{port}"})[0] == 403, "a foreign Host header: 403")
        check(http_status(base + "/view.js")[0] == 200, "the page's script: 200")
        own = f"http://{host}:{port}"
        check(WebSocket(host, port, "/ws?token=" + "1" * 32, own).status == 403, "WebSocket, wrong token: 403")
        check(WebSocket(host, port, f"/ws?token={token}", "http://evil.example").status == 403,
              "WebSocket, foreign Origin: 403")
        check(WebSocket(host, port, "/ws", own).status == 403, "WebSocket, no token: 403")
        ws = WebSocket(host, port, f"/ws?token={token}", own)
        check(ws.status == 101, "WebSocket, right token and own origin: 101")
        op, payload = ws.recv()
        meta = json.loads(payload)
        with open(os.path.join(work, "plain/signals.csv")) as f:
            columns = f.readline().strip().split(",")
        names = [s["name"] for s in meta["channels"][0]["signals"]]
        check(meta["type"] == "meta" and names == columns, "meta message: the CSV's columns in order")
        limits = {l["key"]: l["signal"] for l in meta["limits"]}
        check(limits.get("precession_stop_rad") == "precession_rad" and
              limits.get("precession_torque_limit_Nm") == "precession_torque_Nm" and
              limits.get("precession_soft_limit_rad") == "precession_rad", f"limits placed on their signals: {limits}")
        units = {s["name"]: s["unit"] for s in meta["channels"][0]["signals"]}
        check(units["roll_rate_rad_s"] == "rad/s" and units["wave_moment_Nm"] == "N m" and units["status_bits"] == "bits",
              "units from the signal table")
        end, rows = None, 0
        deadline = time.time() + 60
        while end is None and time.time() < deadline:
            op, payload = ws.recv()
            msg = json.loads(payload)
            if msg["type"] == "data":
                rows = msg["channels"][0]["rows"]
            elif msg["type"] == "end":
                end = msg
        check(end is not None, "the end message arrives")
        with open(os.path.join(work, "served/report.json")) as f:
            served = json.load(f)
        check(end is not None and all(end["report"]["figures"][k] == v for k, v in served["figures"].items() if k != "ticks"),
              "the end message carries report.json's figures")
        check(rows == 100000 // 50, f"every recorded row reached the view ({rows})")
        ws.send_text("acknowledge")
        op, payload = ws.recv()
        code = struct.unpack(">H", payload[:2])[0] if len(payload) >= 2 else None
        check(op == 8 and code == 1008, f"a message from the page closes the socket with 1008 (got op {op}, code {code})")
    finally:
        p.send_signal(signal.SIGTERM)
        rc = p.wait(timeout=30)
    check(rc == 0, f"SIGTERM ends the lingering view, exit 0 ({rc})")
    same_outputs(os.path.join(work, "served"), "with a page attached")

    # 3. Refused before the run.
    r = run(gyrostab, scene, os.path.join(work, "bad"), "--view", "300.1.2.3:80")
    check(r.returncode == 2 and "--view" in r.stderr, f"--view 300.1.2.3:80 refused (exit {r.returncode})")
    r = run(gyrostab, scene, os.path.join(work, "bad"), "--mcap", os.path.join(work, "no/such/dir/run.mcap"))
    check(r.returncode == 2 and "does not exist" in r.stderr and not os.path.exists(os.path.join(work, "bad/report.json")),
          f"--mcap into a missing directory refused before the run (exit {r.returncode})")

    print(f"{len(FAILS) == 0 and 'all' or len(FAILS)} {'checks passed' if not FAILS else 'checks failed'}")
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
