#!/usr/bin/env python3
"""tools/cluster/slurm-sweep on a real single-node Slurm (Debian's slurmctld, slurmd, slurm-client, munge).

    slurm_sweep_test.py SOURCE_DIR GYROSTAB

Starts munged, slurmctld and slurmd in a private temporary directory (own munge key and socket, own
slurm.conf, free ports, loopback only), so it neither needs nor disturbs a Slurm or munge of the system, and
stops them afterwards whatever happens. On it:

1. a tiny study (sim/studies/ship-sizing-small.toml, shortened) through `slurm-sweep --shards 3`: every
   shard and the merge end with exit 0, and every file of results/ but the figures is byte-identical to
   `gyrostab sweep` run locally on the same study;
2. the same study where shard 2 fails: the merge still runs (afterany), exits 4 and names every missing
   task; submitted again, only the missing tasks run (the finished task files are not rewritten), and the
   merged results equal the local run's.

Exit 77 (ctest: skipped) with the reason and the daemons' log tails where Slurm cannot be started here.
"""
import ctypes
import json
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import tomllib

SKIP = 77
PACKAGES = "slurmctld slurmd slurm-client munge"
DAEMON_START_DEADLINE_S = 60
# The study is a few seconds of compute; the rest is Slurm's scheduling passes (a dependent job becomes
# eligible on the controller's next pass) and the start of each job.
JOB_DEADLINE_S = 90
# Below ctest's TIMEOUT (300 s), so that the test gives up and stops its daemons itself rather than be killed.
TEST_DEADLINE_S = 240
test_deadline = time.monotonic() + TEST_DEADLINE_S
TERMINAL_STATES = {"COMPLETED", "FAILED", "CANCELLED", "TIMEOUT", "NODE_FAIL", "OUT_OF_MEMORY", "PREEMPTED",
                   "BOOT_FAIL", "DEADLINE"}
SHARDS = 3


class Skip(Exception):
    pass


failures = []


def check(condition, message):
    """Records a failed assertion and goes on, so that one run reports every difference."""
    if not condition:
        failures.append(message)
        print(f"FAIL: {message}", flush=True)
    return condition


def tail(path, lines=25):
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-lines:])
    except OSError as e:
        return f"({e})"


def free_port():
    # Bound on all addresses, as slurmctld and slurmd bind; the kernel picks a port no one listens on.
    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("", 0))
        return s.getsockname()[1]


def die_with_parent():
    # If this test is killed outright (a ctest timeout sends SIGKILL), the kernel ends its daemons too.
    PR_SET_PDEATHSIG = 1
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


def adopt_orphans():
    # slurmd starts each job's slurmstepd through a double fork; as subreaper this test, not init, inherits
    # them and reaps them in Cluster.stop(), so none is left even as a zombie when the test ends.
    PR_SET_CHILD_SUBREAPER = 36
    ctypes.CDLL(None, use_errno=True).prctl(PR_SET_CHILD_SUBREAPER, 1, 0, 0, 0)


def reap_children():
    while True:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return


class Cluster:
    def __init__(self, tmp):
        self.tmp = tmp
        self.host = socket.gethostname().split(".")[0]
        self.procs = {}
        self.logs = {}
        self.conf = os.path.join(tmp, "slurm.conf")
        self.env = {k: v for k, v in os.environ.items() if not k.startswith(("SLURM_", "SBATCH_", "SQUEUE_"))}
        self.env["SLURM_CONF"] = self.conf

    def spawn(self, name, argv, logs):
        out = open(os.path.join(self.tmp, f"{name}.stderr"), "wb")
        self.logs[name] = [out.name] + logs
        self.procs[name] = subprocess.Popen(argv, stdin=subprocess.DEVNULL, stdout=out, stderr=subprocess.STDOUT,
                                            env=self.env, cwd=self.tmp, start_new_session=True,
                                            preexec_fn=die_with_parent)
        out.close()

    def log_tails(self):
        """Each daemon's last lines: its stderr, or its log file where it wrote nothing to stderr (in the
        foreground they write the same lines to both)."""
        tails = []
        for paths in self.logs.values():
            written = [p for p in paths if os.path.exists(p) and os.path.getsize(p) > 0]
            if written:
                tails.append(f"--- {written[0]}:\n{tail(written[0])}")
        return "\n".join(tails)

    def dead_daemon(self):
        for name, p in self.procs.items():
            if p.poll() is not None:
                return f"{name} exited with {p.returncode}"
        return None

    def start_munge(self):
        d = os.path.join(self.tmp, "munge")
        os.mkdir(d, 0o755)  # munged refuses a socket whose directory others cannot traverse
        key_dir = os.path.join(self.tmp, "munge-key")
        os.mkdir(key_dir, 0o700)
        self.munge_key = os.path.join(key_dir, "munge.key")
        fd = os.open(self.munge_key, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o600)
        os.write(fd, os.urandom(1024))  # what mungekey writes by default: 1024 random bytes
        os.close(fd)
        self.munge_socket = os.path.join(d, "munge.socket")
        log = os.path.join(d, "munged.log")
        argv = ["munged", "--foreground", f"--socket={self.munge_socket}", f"--key-file={self.munge_key}",
                f"--pid-file={os.path.join(d, 'munged.pid')}", f"--log-file={log}",
                f"--seed-file={os.path.join(d, 'munged.seed')}"]
        self.spawn("munged", argv, [log])
        deadline = time.monotonic() + 15
        while not os.path.exists(self.munge_socket):
            if self.dead_daemon() or time.monotonic() > deadline:
                raise Skip(f"munged did not start ({self.dead_daemon() or 'no socket after 15 s'})")
            time.sleep(0.1)

    def write_conf(self):
        user = subprocess.run(["id", "-un"], capture_output=True, text=True, check=True).stdout.strip()
        for sub in ("state", "spool", "log"):
            os.mkdir(os.path.join(self.tmp, sub))
        with open("/proc/meminfo") as f:
            mem_mib = int(re.search(r"MemTotal:\s+(\d+)", f.read()).group(1)) // 1024
        self.ctld_log = os.path.join(self.tmp, "log", "slurmctld.log")
        self.slurmd_log = os.path.join(self.tmp, "log", "slurmd.log")
        ctld_port, slurmd_port = free_port(), free_port()
        while slurmd_port == ctld_port:
            slurmd_port = free_port()
        t = self.tmp
        # Addresses on the loopback: the daemons talk to nothing outside this machine. ReturnToService=2
        # lets the node come back by itself if it once failed to answer while the test's machine was busy.
        conf = f"""\
ClusterName=gyrostabtest
SlurmctldHost={self.host}(127.0.0.1)
SlurmctldPort={ctld_port}
SlurmdPort={slurmd_port}
AuthType=auth/munge
AuthInfo=socket={self.munge_socket}
CredType=cred/munge
SlurmUser={user}
SlurmdUser={user}
StateSaveLocation={t}/state
SlurmdSpoolDir={t}/spool
SlurmctldPidFile={t}/slurmctld.pid
SlurmdPidFile={t}/slurmd.pid
SlurmctldLogFile={self.ctld_log}
SlurmdLogFile={self.slurmd_log}
MailProg=/bin/true
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
SwitchType=switch/none
ReturnToService=2
NodeName={self.host} NodeAddr=127.0.0.1 CPUs={os.cpu_count()} RealMemory={min(1000, mem_mib)} State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
"""
        with open(self.conf, "w") as f:
            f.write(conf)

    def run(self, argv, **kw):
        return subprocess.run(argv, env=self.env, capture_output=True, text=True, **kw)

    def start_slurm(self):
        self.spawn("slurmctld", ["slurmctld", "-D"], [self.ctld_log])
        self.spawn("slurmd", ["slurmd", "-D"], [self.slurmd_log])
        deadline = time.monotonic() + DAEMON_START_DEADLINE_S
        state = ""
        while True:
            dead = self.dead_daemon()
            if dead:
                raise Skip(f"{dead} while starting")
            r = self.run(["scontrol", "show", "node", self.host], timeout=20)
            m = re.search(r"State=(\S+)", r.stdout)
            state = m.group(1) if m else (r.stderr.strip() or r.stdout.strip())
            if state.startswith("IDLE"):
                return
            if time.monotonic() > deadline:
                raise Skip(f"node {self.host} not idle after {DAEMON_START_DEADLINE_S} s (last state: {state})")
            time.sleep(0.5)

    def job_states(self, job_id):
        """{task or job id: (state, exit code)} of a job or of every task of an array job."""
        r = self.run(["scontrol", "-o", "show", "job", str(job_id)], timeout=20)
        states = {}
        for line in r.stdout.splitlines():
            jid = re.search(r"JobId=(\d+)", line)
            task = re.search(r"ArrayTaskId=(\S+)", line)
            state = re.search(r"JobState=(\S+)", line)
            code = re.search(r"ExitCode=(\d+):(\d+)", line)
            if jid and state and code:
                key = task.group(1) if task else jid.group(1)
                states[key] = (state.group(1), (int(code.group(1)), int(code.group(2))))
        return states

    def wait_for(self, job_id):
        deadline = min(time.monotonic() + JOB_DEADLINE_S, test_deadline)
        while True:
            states = self.job_states(job_id)
            if states and all(s in TERMINAL_STATES for s, _ in states.values()):
                return states
            if self.dead_daemon():
                raise RuntimeError(f"{self.dead_daemon()} while job {job_id} ran\n{self.log_tails()}")
            if time.monotonic() > deadline:
                queue = self.run(["squeue", "-a"], timeout=20).stdout
                raise RuntimeError(f"job {job_id} not ended in time: {states}\n{queue}\n"
                                   f"{self.log_tails()}")
            time.sleep(0.25)

    def our_processes(self):
        """Pids of processes left of this cluster: any whose command line or environment names the temp dir
        (slurmstepd and the jobs carry SLURM_CONF in their environment)."""
        mine = str(os.getpid())
        pids = []
        for pid in os.listdir("/proc"):
            if not pid.isdigit() or pid == mine:
                continue
            try:
                with open(f"/proc/{pid}/cmdline", "rb") as f:
                    cmdline = f.read()
                with open(f"/proc/{pid}/environ", "rb") as f:
                    environ = f.read()
            except OSError:
                continue
            if self.tmp.encode() in cmdline or f"SLURM_CONF={self.conf}".encode() in environ.split(b"\0"):
                pids.append(int(pid))
        return pids

    def stop(self):
        for name in ("slurmd", "slurmctld", "munged"):
            p = self.procs.get(name)
            if p is None or p.poll() is not None:
                continue
            try:
                os.killpg(p.pid, signal.SIGTERM)
            except ProcessLookupError:
                continue
            try:
                p.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(p.pid, signal.SIGKILL)
                p.wait()
        for pid in self.our_processes():
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + 5
        reap_children()
        while self.our_processes() and time.monotonic() < deadline:
            time.sleep(0.1)
            reap_children()
        left = self.our_processes()
        check(not left, f"processes of the test cluster left after stopping it: {left}")


def tiny_study(sample_path, duration_s=30.0, settle_s=5.0):
    """The sample study with every run shortened to a few simulated seconds and its base scene named by an
    absolute path (the study is written elsewhere, and a relative scene is read beside the study file)."""
    with open(sample_path) as f:
        text = f.read()
    study = tomllib.loads(text)["study"]
    scene = os.path.normpath(os.path.join(os.path.dirname(sample_path), study["scene"]))
    # Edited as text, within [study] alone, so that the sample's other tables and comments stay as they are.
    header = re.search(r"(?m)^\[study\][^\n]*\n", text)
    next_table = re.compile(r"(?m)^\s*\[").search(text, header.end())
    end = next_table.start() if next_table else len(text)
    section = text[header.end():end]
    for key, value in (("scene", json.dumps(scene)), ("duration_s", repr(duration_s)), ("settle_s", repr(settle_s))):
        line = re.compile(rf"(?m)^\s*{key}\s*=.*$")
        if key in study:
            section = line.sub(lambda _: f"{key} = {value}", section, count=1)
        else:
            section = f"{key} = {value}\n" + section
    text = text[:header.end()] + section + text[end:]
    got = tomllib.loads(text)["study"]
    if (got["scene"], got["duration_s"], got["settle_s"]) != (scene, duration_s, settle_s):
        raise RuntimeError(f"could not shorten {sample_path}: [study] became {got}")
    return text


def result_files(results_dir):
    """Relative paths of the merged tables: figures and timings differ from run to run by design."""
    files = {}
    for dirpath, _, names in os.walk(results_dir):
        for name in names:
            if name.endswith(".png") or "timing" in name:
                continue
            path = os.path.join(dirpath, name)
            files[os.path.relpath(path, results_dir)] = path
    return files


def figures(results_dir):
    return sorted(os.path.relpath(os.path.join(d, n), results_dir) for d, _, names in os.walk(results_dir)
                  for n in names if n.endswith(".png"))


def compare_results(got_dir, want_dir, what):
    check(figures(want_dir) and figures(got_dir) == figures(want_dir),
          f"{what}: heat maps {figures(got_dir)}, the local run's {figures(want_dir)}")
    got, want = result_files(got_dir), result_files(want_dir)
    check(want, f"{what}: the local run wrote no result table under {want_dir}")
    check(any(p.endswith("cells.csv") for p in want) and "summary.csv" in want,
          f"{what}: the local run has no cells.csv or no summary.csv: {sorted(want)}")
    check(set(got) == set(want), f"{what}: other files than the local run's: only in Slurm's "
          f"{sorted(set(got) - set(want))}, only in the local {sorted(set(want) - set(got))}")
    same = 0
    for rel in sorted(set(got) & set(want)):
        with open(got[rel], "rb") as a, open(want[rel], "rb") as b:
            if check(a.read() == b.read(), f"{what}: results/{rel} differs from the local run's"):
                same += 1
    print(f"{what}: {same} of {len(want)} result files byte-identical to the local run")


def submit(slurm_sweep, study, out, gyrostab, cluster):
    r = cluster.run([slurm_sweep, study, "--out", out, "--shards", str(SHARDS), "--gyrostab", gyrostab],
                    timeout=60)
    print(r.stdout, r.stderr, sep="", end="", flush=True)
    if not check(r.returncode == 0, f"slurm-sweep exited {r.returncode}"):
        raise RuntimeError("slurm-sweep failed")
    m = re.search(r"shard array job (\d+) .*merge job (\d+)", r.stdout)
    if not check(m, "slurm-sweep did not print the two job ids"):
        raise RuntimeError("no job ids")
    return m.group(1), m.group(2)


def task_files(out):
    """{path under DIR/tasks/: stat} of the finished task files (DIR/tasks/<variant>/<task>.json)."""
    d = os.path.join(out, "tasks")
    files = {}
    for dirpath, _, names in os.walk(d):
        for name in names:
            if name.endswith(".json"):
                path = os.path.join(dirpath, name)
                files[os.path.relpath(path, d)] = os.stat(path)
    return files


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    source_dir, gyrostab = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    slurm_sweep = os.path.join(source_dir, "tools", "cluster", "slurm-sweep")
    sample = os.path.join(source_dir, "sim", "studies", "ship-sizing-small.toml")
    missing = [t for t in ("munged", "slurmctld", "slurmd", "sbatch", "squeue", "scontrol")
               if shutil.which(t) is None]
    if missing:
        print(f"SKIP: {', '.join(missing)} not found; apt-get install --no-install-recommends {PACKAGES} "
              "(tools/setup installs them)")
        return SKIP
    for path in (gyrostab, slurm_sweep, sample):
        if not os.path.exists(path):
            print(f"FAIL: {path} does not exist")
            return 1

    # A signal from ctest or a user ends the test through the finally below, which stops the daemons.
    def interrupted(signum, _frame):
        raise KeyboardInterrupt(f"signal {signum}")
    signal.signal(signal.SIGTERM, interrupted)

    adopt_orphans()
    tmp = tempfile.mkdtemp(prefix="gyrostab-slurm-")
    os.chmod(tmp, 0o755)  # munged checks that every directory above its socket is traversable by all
    cluster = Cluster(tmp)
    keep = os.environ.get("GYROSTAB_KEEP_SLURM_TMP") == "1"
    try:
        try:
            cluster.start_munge()
            cluster.write_conf()
            cluster.start_slurm()
        except Skip as e:
            print(f"SKIP: Slurm could not be started here: {e}\n{cluster.log_tails()}")
            return SKIP
        print(f"slurm: single node {cluster.host} idle ({tmp})", flush=True)

        study = os.path.join(tmp, "study.toml")
        with open(study, "w") as f:
            f.write(tiny_study(sample))

        t0 = time.monotonic()
        r = subprocess.run([gyrostab, "sweep", study, "--out", os.path.join(tmp, "local"), "--quiet"],
                           capture_output=True, text=True, timeout=120)
        local_s = time.monotonic() - t0
        if not check(r.returncode == 0, f"the local sweep exited {r.returncode}: {r.stderr[-2000:]}"):
            return 1
        print(f"local: gyrostab sweep took {local_s:.1f} s", flush=True)

        # 1. A clean run on Slurm equals the local run.
        out = os.path.join(tmp, "on-slurm")
        t0 = time.monotonic()
        array_id, merge_id = submit(slurm_sweep, study, out, gyrostab, cluster)
        merge = cluster.wait_for(merge_id)
        slurm_s = time.monotonic() - t0
        shards = cluster.job_states(array_id)
        print(f"slurm: shards {shards}, merge {merge}; submit to merge end {slurm_s:.1f} s "
              f"(local {local_s:.1f} s)", flush=True)
        check(sorted(shards) == [str(i) for i in range(1, SHARDS + 1)],
              f"the array job has tasks {sorted(shards)}, not 1..{SHARDS}")
        for task, (state, code) in shards.items():
            check(state == "COMPLETED" and code == (0, 0), f"shard {task} ended {state} with exit {code}; "
                  f"log: {tail(os.path.join(out, 'slurm', f'{array_id}_{task}.out'))}")
        merge_log = os.path.join(out, "slurm", f"merge_{merge_id}.out")
        check(merge.get(merge_id) == ("COMPLETED", (0, 0)), f"the merge ended {merge}; log: {tail(merge_log)}")
        for i in range(1, SHARDS + 1):
            check(os.path.exists(os.path.join(out, "slurm", f"{array_id}_{i}.out")),
                  f"no log of shard {i} in {out}/slurm/")
        compare_results(os.path.join(out, "results"), os.path.join(tmp, "local", "results"), "clean run")

        # 2. Shard 2 fails: the merge runs all the same and says what is missing; resubmitted, only the
        #    missing tasks run.
        failing = os.path.join(tmp, "gyrostab-failing-shard-2")
        with open(failing, "w") as f:
            f.write(f"""#!/bin/bash
for a in "$@"; do [ "$a" = 2/{SHARDS} ] && {{ echo "shard 2 fails on purpose" >&2; exit 3; }}; done
exec {gyrostab} "$@"
""")
        os.chmod(failing, 0o755)
        out = os.path.join(tmp, "on-slurm-resumed")
        array_id, merge_id = submit(slurm_sweep, study, out, failing, cluster)
        merge = cluster.wait_for(merge_id)
        shards = cluster.job_states(array_id)
        merge_log = os.path.join(out, "slurm", f"merge_{merge_id}.out")
        print(f"slurm, shard 2 failing: shards {shards}, merge {merge}; the merge said:\n{tail(merge_log, 5)}")
        check(shards.get("2", ("", None))[0] == "FAILED", f"shard 2 did not fail: {shards}")
        check(all(shards.get(str(i), ("",))[0] == "COMPLETED" for i in range(1, SHARDS + 1) if i != 2),
              f"shards 1 and 3 did not complete: {shards}")
        merge_state, merge_code = merge.get(merge_id, ("", (0, 0)))
        # gyrostab sweep merge: exit 4 when tasks are missing (`gyrostab sweep --help`, docs/sweep.md).
        check(merge_state == "FAILED" and merge_code[0] == 4,
              f"the merge after a failed shard ended {merge_state} {merge_code}, not FAILED with exit 4")
        before = task_files(out)
        local_tasks = task_files(os.path.join(tmp, "local"))
        check(0 < len(before) < len(local_tasks),
              f"{len(before)} task files after shard 2 failed, expected some but fewer than all {len(local_tasks)}")
        merge_said = open(merge_log, errors="replace").read() if os.path.exists(merge_log) else ""
        unnamed = [t for t in set(local_tasks) - set(before) if t.removesuffix(".json") not in merge_said]
        check(not unnamed, f"the merge's log does not name the missing tasks {sorted(unnamed)}")

        array_id, merge_id = submit(slurm_sweep, study, out, gyrostab, cluster)
        merge = cluster.wait_for(merge_id)
        shards = cluster.job_states(array_id)
        merge_log = os.path.join(out, "slurm", f"merge_{merge_id}.out")
        check(all(s == ("COMPLETED", (0, 0)) for s in shards.values()) and len(shards) == SHARDS,
              f"resubmitted shards ended {shards}")
        check(merge.get(merge_id) == ("COMPLETED", (0, 0)), f"the resumed merge ended {merge}; log: {tail(merge_log)}")
        after = task_files(out)
        check(set(after) == set(local_tasks), f"task files after resuming differ from the local run's: "
              f"{sorted(set(after) ^ set(local_tasks))}")
        rewritten = [n for n, st in before.items()
                     if n not in after or (after[n].st_ino, after[n].st_mtime_ns) != (st.st_ino, st.st_mtime_ns)]
        check(not rewritten, f"the resubmission rewrote finished task files: {rewritten}")
        compare_results(os.path.join(out, "results"), os.path.join(tmp, "local", "results"), "resumed run")
    except RuntimeError as e:
        check(False, str(e))
    finally:
        cluster.stop()
        if keep or failures:
            print(f"kept {tmp} for inspection")
        else:
            shutil.rmtree(tmp, ignore_errors=True)

    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("slurm_sweep_test: all checks passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
