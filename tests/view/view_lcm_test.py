#!/usr/bin/env python3
"""ctest label `view`: `gyrostab view --lcm-url`, the passive listener on a running bus.

  view_lcm_test.py GYROSTAB SOURCE_DIR WORKDIR

Runs itself inside a private network namespace (unshare -n; exit 77 where that is not permitted).

1. It never sends. The viewer runs in a second namespace of its own, joined to the test's by a veth pair (as
   another machine on the LAN would be; the bus's URL has ttl=1 so the frames cross it, and nothing leaves this
   host). The plant and controller run over LCM in the test's namespace with the viewer attached (the device and
   the tick learnt from the first frames: no --scene). Then: the viewer's namespace counted 0 UDP datagrams sent
   (the kernel's Udp OutDatagrams there) while it received every frame; its summary shows every frame of the run
   (20 000 sensor and 20 000 actuator frames); the run's signals.csv is byte for byte the in-process run's and
   report.json's figures equal.
2. Keys. A run with --key-file and three viewers at once (same namespace, loopback): with the right key every
   frame is shown and marked authenticated (the page's data message: flags, link panel); with a wrong key none
   is shown (all refused as bad MAC; the page's channels stay empty); without a key every frame is shown, marked
   NOT authenticated.
3. Bad options: a URL that is not udpm://, a bad --view address.
About 10 s."""
import json
import os
import shutil
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from view_cli_test import WebSocket  # noqa: E402

FAILS = []
TICKS = 20000


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what, flush=True)
    if not cond:
        FAILS.append(what)


def udp_counters(pid):
    """Udp InDatagrams and OutDatagrams of the network namespace `pid` is in (/proc/PID/net/snmp)."""
    with open(f"/proc/{pid}/net/snmp") as f:
        lines = [l.split() for l in f if l.startswith("Udp:")]
    row = dict(zip(lines[0][1:], map(int, lines[1][1:])))
    return row["InDatagrams"], row["OutDatagrams"]


def start_viewer(cmd, env):
    """Starts a viewer; returns (process, url) once it serves (it prints the URL once it knows the device)."""
    p = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    return p


def wait_url(p, timeout=60):
    deadline = time.time() + timeout
    while time.time() < deadline:
        line = p.stderr.readline()
        if not line:
            break
        if " at http://" in line:
            return line.rsplit(" at ", 1)[1].strip()
    return None


def wait_line(p, text, timeout=30):
    deadline = time.time() + timeout
    while time.time() < deadline:
        line = p.stderr.readline()
        if not line or text in line:
            return line
    return ""


def stop(p):
    p.send_signal(signal.SIGTERM)
    out, err = p.communicate(timeout=30)
    lines = [l for l in out.splitlines() if l.startswith("{")]
    return p.returncode, json.loads(lines[-1]) if lines else {}


def sent(out_dir):
    """Frames the plant and the controller published (their link counters: tick 0 may be resent)."""
    with open(f"{out_dir}/report.json") as f1, open(f"{out_dir}/controller/report.json") as f2:
        return json.load(f1)["link"]["counters"]["sent"], json.load(f2)["link"]["counters"]["sent"]


def data_message(url, want_rows):
    """The first data message of the viewer's page whose sensor channel holds `want_rows` rows (or the last)."""
    base, token = url.split("/?token=")
    host, port = base[len("http://"):].rsplit(":", 1)
    ws = WebSocket(host, int(port), f"/ws?token={token}", base)
    meta = json.loads(ws.recv()[1])
    msg, deadline = None, time.time() + 10
    while time.time() < deadline:
        m = json.loads(ws.recv()[1])
        if m["type"] == "data":
            msg = m
            if m["channels"][0]["rows"] >= want_rows:
                break
    return meta, msg


def inside(gyrostab, src, work):
    env = dict(os.environ, GYROSTAB_PLOT_SCRIPT="")
    scene = os.path.join(src, "sim/scenes/ship-roll-damper-active.toml")
    sh = lambda c: subprocess.run(c, shell=True, check=True)  # noqa: E731  (fixed commands, no user text)
    sh("ip link set lo up && ip link set lo multicast on")
    ref = os.path.join(work, "inproc")
    r = subprocess.run([gyrostab, "run", scene, "--no-progress", "--ticks", str(TICKS), "--out", ref], env=env,
                       capture_output=True, text=True, timeout=300)
    check(r.returncode == 0, "the in-process reference run")

    # 1. A viewer in a namespace of its own, across a veth pair.
    holder = subprocess.Popen(["unshare", "-n", "sleep", "600"])
    try:
        for _ in range(200):
            if os.readlink(f"/proc/{holder.pid}/ns/net") != os.readlink("/proc/self/ns/net"):
                break
            time.sleep(0.01)
        sh(f"ip link add gvp type veth peer name gvv netns {holder.pid}")
        sh("ip addr add 10.78.0.1/24 dev gvp && ip link set gvp up multicast on && "
           "ip route add 224.0.0.0/4 dev gvp")
        sh(f"nsenter -t {holder.pid} -n sh -c 'ip link set lo up && ip addr add 10.78.0.2/24 dev gvv && "
           "ip link set gvv up multicast on && ip route add 224.0.0.0/4 dev gvv'")
        url = "udpm://239.255.76.67:7667?ttl=1"
        viewer = start_viewer(["nsenter", "-t", str(holder.pid), "-n", gyrostab, "view", "--lcm-url", url], env)
        check("listening" in wait_line(viewer, "listening"), "the viewer listens, waiting for the first frames")
        time.sleep(0.3)
        _, out0 = udp_counters(holder.pid)
        pair = os.path.join(work, "pair")
        r = subprocess.run([gyrostab, "run", scene, "--no-progress", "--ticks", str(TICKS), "--out", pair,
                            "--transport", "lcm", "--lcm-url", url], env=env, capture_output=True, text=True,
                           timeout=300)
        check(r.returncode == 0, f"the plant/controller pair over LCM with the viewer attached exits 0 ({r.returncode})")
        url_printed = wait_url(viewer, timeout=5)
        check(url_printed is not None, "the viewer learnt the device and the tick from the frames and serves its page")
        time.sleep(0.5)
        rx, out1 = udp_counters(holder.pid)
        rc, summary = stop(viewer)
        check(rc == 0, f"the viewer exits 0 on SIGTERM ({rc})")
        check(out0 == 0 and out1 == 0, f"the viewer's namespace sent no UDP datagram (OutDatagrams {out0} -> {out1})")
        check(rx >= 2 * TICKS, f"while it received the bus's datagrams (InDatagrams {rx})")
        s, a = summary.get("sensor", {}), summary.get("actuator", {})
        ps, cs = sent(pair)
        # The end-of-run frame and its answer (with their copies) are verified and counted, not charted.
        se, ae = s.get("end_of_run", 0), a.get("end_of_run", 0)
        check(s.get("shown") + se == ps and a.get("shown") + ae == cs and se >= 1 and ae >= 1 and
              s.get("shown") >= TICKS and a.get("shown") >= TICKS,
              f"every frame on the bus was shown: {s.get('shown')} sensor, {a.get('shown')} actuator, and the end "
              f"of the run counted ({se}, {ae}) (the plant sent {ps}, the controller {cs}, for {TICKS} ticks)")
        check(summary.get("device") == "ship_roll_damper" and summary.get("sessions") == 1,
              f"one session, the device's table learnt from the frame type ({summary.get('device')})")
        check(summary.get("authenticated") is False, "no key: the summary says the frames were not authenticated")
        with open(f"{ref}/signals.csv", "rb") as f1, open(f"{pair}/signals.csv", "rb") as f2:
            check(f1.read() == f2.read(), "signals.csv with the viewer attached equals the in-process run's, byte for byte")
        with open(f"{ref}/report.json") as f1, open(f"{pair}/report.json") as f2:
            check(json.load(f1)["figures"] == json.load(f2)["figures"], "report.json's figures equal")
    finally:
        holder.kill()
        holder.wait()

    # 2. Keys: the right one, a wrong one, none; three viewers on one bus (loopback).
    sh("ip route replace 224.0.0.0/4 dev lo")
    key, wrong = os.path.join(work, "link.key"), os.path.join(work, "wrong.key")
    for path, text in ((key, "00112233445566778899aabbccddeeff\n"), (wrong, "ffeeddccbbaa99887766554433221100\n")):
        with open(path, "w") as f:
            f.write(text)
        os.chmod(path, 0o600)
    url = "udpm://239.255.76.67:7667?ttl=0"
    viewers = {}
    for name, extra in (("right", ["--key-file", key]), ("wrong", ["--key-file", wrong]), ("none", [])):
        p = start_viewer([gyrostab, "view", "--lcm-url", url, "--scene", scene, "--ticks", str(TICKS), *extra], env)
        viewers[name] = (p, wait_url(p))
    check(all(u for _, u in viewers.values()), "with --scene each viewer serves its page at once")
    keyed = os.path.join(work, "keyed")
    r = subprocess.run([gyrostab, "run", scene, "--no-progress", "--ticks", str(TICKS), "--out", keyed,
                        "--transport", "lcm", "--lcm-url", url, "--key-file", key], env=env, capture_output=True,
                       text=True, timeout=300)
    check(r.returncode == 0, f"a keyed run with three viewers attached exits 0 ({r.returncode})")
    pages = {}
    for name, (p, u) in viewers.items():
        pages[name] = data_message(u, TICKS if name != "wrong" else 0)
    results = {name: stop(p)[1] for name, (p, _) in viewers.items()}
    right, bad, none = results["right"], results["wrong"], results["none"]
    ps, cs = sent(keyed)
    shown = lambda c: c["shown"] + c.get("end_of_run", 0)
    check(shown(right["sensor"]) == ps and shown(right["actuator"]) == cs and right["authenticated"],
          f"the right key: every frame verified and shown ({right['sensor']['shown']} of {ps}, "
          f"{right['actuator']['shown']} of {cs})")
    check(bad["sensor"]["shown"] == 0 and bad["actuator"]["shown"] == 0 and
          bad["sensor"]["bad_mac"] == ps and bad["actuator"]["bad_mac"] == cs,
          f"a wrong key: no frame shown, every one refused as bad MAC ({bad['sensor']['bad_mac']}, "
          f"{bad['actuator']['bad_mac']})")
    check(shown(none["sensor"]) == ps and shown(none["actuator"]) == cs and not none["authenticated"],
          "no key: every frame shown, not authenticated")
    _, m = pages["right"]
    check(m is not None and all((c["latest"]["flags"] & 4) != 0 for c in m["channels"]) and m["link"]["authenticated"],
          "the right key's page: the frames are marked authenticated")
    _, m = pages["wrong"]
    check(m is not None and all(c["rows"] == 0 and c["latest"] is None for c in m["channels"]) and
          m["link"]["sensor"]["refused"] > 0, "a wrong key's page: no frame at all, the refusals counted")
    meta, m = pages["none"]
    check(m is not None and all((c["latest"]["flags"] & 4) == 0 for c in m["channels"]) and
          "NOT authenticated" in m["link"]["authentication"], "no key's page: the frames are marked NOT authenticated")
    check([c["topic"] for c in meta["channels"]] == ["/gyrostab/sensor", "/gyrostab/actuator"] and
          meta["channels"][1]["status"] == "fault", "two channels: the sensor frames and the actuator frames (status)")

    # 3. Refused before listening.
    r = subprocess.run([gyrostab, "view", "--lcm-url", "tcpq://127.0.0.1:7700"], capture_output=True, text=True)
    check(r.returncode == 2 and "udpm" in r.stderr, f"a URL that is not udpm:// is refused ({r.returncode})")
    r = subprocess.run([gyrostab, "view", "--view", "300.1.1.1:80"], capture_output=True, text=True)
    check(r.returncode == 2, f"a bad --view address is refused ({r.returncode})")
    return 1 if FAILS else 0


def main():
    gyrostab, src, work = sys.argv[1:4]
    if "--inside" in sys.argv:
        t0 = time.time()
        rc = inside(gyrostab, src, work)
        print(f"{'all checks passed' if rc == 0 else str(len(FAILS)) + ' checks failed'} in {time.time() - t0:.1f} s")
        return rc
    if subprocess.run(["unshare", "-n", "true"], capture_output=True).returncode != 0:
        print("skip: no private network namespace here (unshare -n)")
        return 77
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    return subprocess.run(["unshare", "-n", sys.executable, os.path.abspath(__file__), gyrostab, src, work,
                           "--inside"]).returncode


if __name__ == "__main__":
    sys.exit(main())
