#!/usr/bin/python3
"""gyrostab sweep, from the outside (docs/sweep.md): a small study of the active ship (3 cells x 2 seeds x 2
variants, 3 s each) run whole, in 2 and in 7 shards in shuffled order, resumed, with a failing variant, with
damaged and stale task files, and a table of bad study files.

    sweep_cli_test.py GYROSTAB SOURCE_DIR WORK_DIR

Claims:
  ShardsAnyOrderAnyJobsGiveTheSameBytes   results/ (csv, json) of 1 shard --jobs 2 == 2 shards == 7 shards in
                                          shuffled order, each --jobs 1; and the run found something (figures
                                          not null, the two variants differ)
  SeedsFollowTheSeaNotTheVariant          both variants of a (cell, replicate) share the scene seed; cells and
                                          replicates differ
  ResumeRunsOnlyTheMissingTasks           half the shards, then the whole study: only the other half runs, the
                                          kept files are untouched, the results equal the whole run's
  FailingVariantIsRecordedOthersComplete  a variant the scene check refuses: its tasks "refused" with the
                                          reader's reason, the other variant complete, exit 3
  DamagedAndStaleFilesAreFoundAndRerun    merge: exit 4, left out, named; rerun: exactly those run again
  HeadingsSplitTheCellsProbability        headings_deg = [90, 45] with probabilities [3, 1]: a row per cell and
                                          heading with the split probability, the heading in the task's scene,
                                          and a different unstabilized roll at the two headings
  BadStudyFilesAreRefusedNothingWritten   each bad file: exit 2, its message names file, key and reason, no
                                          output directory
"""
import json
import os
import random
import re
import shutil
import subprocess
import sys

GYROSTAB, SOURCE, WORK = sys.argv[1], sys.argv[2], sys.argv[3]
SCENE = os.path.join(SOURCE, "sim", "scenes", "ship-roll-damper-active.toml")
failures = []

STUDY = """[study]
name = "sweep-test"
scene = "{scene}"
seed = 7
seeds_per_cell = 2
duration_s = 3
settle_s = 1

[[sea_state]]
Hs = 1.5
Tp = 8.0
probability = 0.5

[[sea_state]]
Hs = 2.5
Tp = 10.0
probability = 0.3

[[sea_state]]
Hs = 3.5
Tp = 9.0
probability = 0.2

[[variant]]
name = "H-1.018e6"
set = {{ "gyro.H" = 1.018e6 }}

[[variant]]
name = "{second}"
set = {{ "gyro.H" = {second_H}, "controller.roll_rate_gain" = 0.7e6 }}
"""


def check(claim, ok, message):
    if not ok:
        failures.append(f"{claim}: {message}")
        print(f"FAIL {claim}: {message}", file=sys.stderr)


def study(path, second="H-0.7e6", second_H="0.7e6", text=None):
    with open(path, "w") as f:
        f.write(text if text is not None else STUDY.format(scene=SCENE, second=second, second_H=second_H))
    return path


def run(*args):
    env = dict(os.environ, GYROSTAB_SWEEP_PLOT_SCRIPT="")  # heat maps: drawn once, in the sample-study check
    p = subprocess.run([GYROSTAB, *args], capture_output=True, text=True, env=env, timeout=300)
    return p.returncode, p.stdout, p.stderr


def results(d):
    """Every table and summary under d/results: relative path -> bytes."""
    out = {}
    for root, _, files in os.walk(os.path.join(d, "results")):
        for name in files:
            if name.endswith((".csv", ".json", ".md")):
                path = os.path.join(root, name)
                with open(path, "rb") as f:
                    out[os.path.relpath(path, d)] = f.read()
    return out


def task_files(d):
    return sorted(os.path.relpath(os.path.join(r, n), d) for r, _, fs in os.walk(os.path.join(d, "tasks"))
                  for n in fs if n.endswith(".json") and not n.startswith("."))


def fresh(name):
    d = os.path.join(WORK, name)
    shutil.rmtree(d, ignore_errors=True)
    return d


def shards_and_seeds(study_file):
    whole = fresh("whole")
    rc, out, err = run("sweep", study_file, "--out", whole, "--jobs", "2", "--quiet")
    check("ShardsAnyOrderAnyJobsGiveTheSameBytes", rc == 0, f"whole run exit {rc}: {err}")
    base = results(whole)
    check("ShardsAnyOrderAnyJobsGiveTheSameBytes", len(base) == 8, f"8 result files expected, got {sorted(base)}")
    rows = json.loads(base.get("results/H-1.018e6/cells.json", b"[]"))
    check("ShardsAnyOrderAnyJobsGiveTheSameBytes",
          len(rows) == 3 and all(isinstance(r["mean"]["roll_rms_rad"], float) and r["mean"]["roll_rms_rad"] > 0
                                 for r in rows), "cells.json rows with a positive roll_rms_rad expected")
    s1 = json.loads(base["results/H-1.018e6/summary.json"])
    s2 = json.loads(base["results/H-0.7e6/summary.json"])
    check("ShardsAnyOrderAnyJobsGiveTheSameBytes",
          s1["weighted_mean"]["roll_rms_rad"] != s2["weighted_mean"]["roll_rms_rad"],
          "the two variants gave the same weighted roll rms")
    check("ShardsAnyOrderAnyJobsGiveTheSameBytes",
          s1["weighted_mean"]["roll_rms_unstabilized_rad"] == s2["weighted_mean"]["roll_rms_unstabilized_rad"],
          "the unstabilized reference differs between variants: they did not see the same seas")
    for n in (2, 7):
        d = fresh(f"shards-{n}")
        order = list(range(1, n + 1))
        random.Random(n).shuffle(order)
        for i in order:
            rc, out, err = run("sweep", study_file, "--out", d, "--shard", f"{i}/{n}", "--jobs", "1", "--quiet")
            check("ShardsAnyOrderAnyJobsGiveTheSameBytes", rc == 0, f"shard {i}/{n} exit {rc}: {err}")
            check("ShardsAnyOrderAnyJobsGiveTheSameBytes", not os.path.exists(os.path.join(d, "results")),
                  f"shard {i}/{n} merged (a shard must not)")
        rc, out, err = run("sweep", "merge", d)
        check("ShardsAnyOrderAnyJobsGiveTheSameBytes", rc == 0, f"merge of {n} shards exit {rc}: {err}")
        got = results(d)
        differ = sorted(k for k in set(base) | set(got) if base.get(k) != got.get(k))
        check("ShardsAnyOrderAnyJobsGiveTheSameBytes", not differ, f"{n} shards differ from the whole run in {differ}")

    seeds = {}
    for rel in task_files(whole):
        t = json.load(open(os.path.join(whole, rel)))["task"]
        seeds.setdefault((t["cell"], t["heading"], t["replicate"]), set()).add(t["seed"])
    check("SeedsFollowTheSeaNotTheVariant", len(seeds) == 6 and all(len(v) == 1 for v in seeds.values()),
          f"one seed per (cell, heading, replicate) over both variants expected: {seeds}")
    distinct = {next(iter(v)) for v in seeds.values()}
    check("SeedsFollowTheSeaNotTheVariant", len(distinct) == 6, f"6 distinct seeds expected, got {len(distinct)}")
    return whole, base


def resume(study_file, base):
    d = fresh("resume")
    rc, _, err = run("sweep", study_file, "--out", d, "--shard", "1/2", "--quiet")
    check("ResumeRunsOnlyTheMissingTasks", rc == 0, f"shard 1/2 exit {rc}: {err}")
    kept = {rel: (os.stat(os.path.join(d, rel)).st_mtime_ns, open(os.path.join(d, rel), "rb").read())
            for rel in task_files(d)}
    check("ResumeRunsOnlyTheMissingTasks", len(kept) == 6, f"6 task files after shard 1/2, got {len(kept)}")
    rc, out, err = run("sweep", study_file, "--out", d, "--quiet")
    check("ResumeRunsOnlyTheMissingTasks", rc == 0, f"rerun exit {rc}: {err}")
    check("ResumeRunsOnlyTheMissingTasks", re.search(r"12 tasks: 6 run on \d+ threads?, 6 reused", out) is not None,
          f"'12 tasks: 6 run ..., 6 reused' expected in: {out}")
    for rel, (mtime, data) in kept.items():
        p = os.path.join(d, rel)
        check("ResumeRunsOnlyTheMissingTasks", os.stat(p).st_mtime_ns == mtime and open(p, "rb").read() == data,
              f"{rel} was rewritten")
    check("ResumeRunsOnlyTheMissingTasks", results(d) == base, "resumed results differ from the whole run's")


def failing_variant(study_file_dir):
    d = fresh("failing")
    f = study(os.path.join(study_file_dir, "failing.toml"), second="H-negative", second_H="-1.0")
    rc, out, err = run("sweep", f, "--out", d, "--quiet")
    check("FailingVariantIsRecordedOthersComplete", rc == 3, f"exit 3 expected, got {rc}: {err}")
    bad = [json.load(open(os.path.join(d, r))) for r in task_files(d) if r.startswith("tasks/H-negative/")]
    good = [json.load(open(os.path.join(d, r))) for r in task_files(d) if r.startswith("tasks/H-1.018e6/")]
    check("FailingVariantIsRecordedOthersComplete", len(bad) == 6 and all(
        t["outcome"] == "refused" and any("[gyro] H" in r and "out of range" in r for r in t["reasons"]) for t in bad),
        f"6 refused tasks naming [gyro] H out of range expected: {[t.get('reasons') for t in bad][:1]}")
    check("FailingVariantIsRecordedOthersComplete", len(good) == 6 and all(t["outcome"] == "completed" for t in good),
          "the other variant's 6 tasks should complete")
    s = json.load(open(os.path.join(d, "results", "H-negative", "summary.json")))
    check("FailingVariantIsRecordedOthersComplete",
          s["tasks"]["failed"] == 6 and s["excluded_probability_failed"] == 1.0 and s["weighted_mean"]["roll_rms_rad"] is None,
          f"failed 6, excluded probability 1, no mean expected: {s['tasks']}, {s['excluded_probability_failed']}")
    s = json.load(open(os.path.join(d, "results", "H-1.018e6", "summary.json")))
    check("FailingVariantIsRecordedOthersComplete", s["tasks"]["completed"] == 6 and s["included_probability"] == 1.0,
          f"the good variant complete expected: {s['tasks']}")
    check("FailingVariantIsRecordedOthersComplete", "failed: H-negative/c0-h0-r0 refused" in err,
          f"the failure listed on stderr expected: {err}")


def damaged(whole, study_file, base):
    d = fresh("damaged")
    shutil.copytree(whole, d)
    tasks = task_files(d)
    truncated, flipped, stale = (os.path.join(d, tasks[i]) for i in (0, 5, 9))
    data = open(truncated, "rb").read()
    open(truncated, "wb").write(data[: len(data) // 2])
    rec = json.load(open(flipped))
    rec["figures"]["roll_rms_rad"] *= 1.5
    json.dump(rec, open(flipped, "w"), indent=2, sort_keys=True)
    rec = json.load(open(stale))
    rec["definition_hash"] = "0123456789abcdef"
    json.dump(rec, open(stale, "w"), indent=2, sort_keys=True)
    rc, out, err = run("sweep", "merge", d)
    check("DamagedAndStaleFilesAreFoundAndRerun", rc == 4, f"merge exit 4 expected, got {rc}")
    for p, word in ((truncated, "damaged"), (flipped, "damaged"), (stale, "stale")):
        check("DamagedAndStaleFilesAreFoundAndRerun", f"{p}: {word}" in err, f"'{p}: {word}' expected in: {err}")
    s = json.load(open(os.path.join(d, "results", "H-1.018e6", "summary.json")))
    t = json.load(open(os.path.join(d, "results", "H-0.7e6", "summary.json")))
    check("DamagedAndStaleFilesAreFoundAndRerun",
          s["tasks"]["missing"] + t["tasks"]["missing"] == 3 and (not s["complete"] or not t["complete"]),
          "3 missing tasks and complete: false expected")
    rc, out, err = run("sweep", study_file, "--out", d, "--quiet")
    check("DamagedAndStaleFilesAreFoundAndRerun", rc == 0, f"rerun exit {rc}: {err}")
    check("DamagedAndStaleFilesAreFoundAndRerun", "12 tasks: 3 run" in out and err.count("running it again") == 3,
          f"exactly 3 tasks rerun expected: {out} {err}")
    check("DamagedAndStaleFilesAreFoundAndRerun", results(d) == base, "results after the rerun differ")


def headings(dir_):
    d = fresh("headings")
    text = STUDY.format(scene=SCENE, second="H-0.7e6", second_H="0.7e6").replace(
        "settle_s = 1\n", "settle_s = 1\nheadings_deg = [90, 45]\nheading_probability = [3, 1]\n")
    rc, out, err = run("sweep", study(os.path.join(dir_, "headings.toml"), text=text), "--out", d, "--quiet")
    check("HeadingsSplitTheCellsProbability", rc == 0 and "24 tasks" in out, f"24 tasks, exit 0 expected: {rc} {out} {err}")
    rows = json.load(open(os.path.join(d, "results", "H-1.018e6", "cells.json")))
    got = [(r["cell"], r["heading"], r["heading_deg"], round(r["probability"], 12)) for r in rows]
    want = [(0, 0, 90.0, 0.375), (0, 1, 45.0, 0.125), (1, 0, 90.0, 0.225), (1, 1, 45.0, 0.075), (2, 0, 90.0, 0.15),
            (2, 1, 45.0, 0.05)]
    check("HeadingsSplitTheCellsProbability", got == want, f"rows {got}, expected {want}")
    scene = json.load(open(os.path.join(d, "tasks", "H-1.018e6", "c0-h1-r0.json")))["scene"]
    check("HeadingsSplitTheCellsProbability", re.search(r"\[course\][^\[]*heading_deg = 45\.0", scene) is not None,
          "[course] heading_deg = 45.0 expected in the task's scene")
    check("HeadingsSplitTheCellsProbability",
          rows[0]["mean"]["roll_rms_unstabilized_rad"] != rows[1]["mean"]["roll_rms_unstabilized_rad"],
          "the same unstabilized roll at 90 and 45 degrees: the heading did not reach the sea")


BAD = [  # (what, replace this, with this, the message must hold all of these)
    ("missing name", 'name = "sweep-test"\n', "", ["[study] name: is missing"]),
    ("wrong type", "seeds_per_cell = 2", 'seeds_per_cell = "2"', ["[study] seeds_per_cell", "must be an integer"]),
    ("unknown key", "seed = 7\n", "seed = 7\nseeds = 3\n", ["[study] seeds", "unknown key"]),
    ("unknown table", "[study]", "[studdy]\n[study]", ["studdy", "unknown table"]),
    ("negative probability", "probability = 0.3", "probability = -0.3",
     ["[[sea_state]] #2 probability", "out of range"]),
    ("NaN probability", "probability = 0.3", "probability = nan", ["[[sea_state]] #2 probability", "out of range"]),
    ("no sea states", None, None, ["[[sea_state]]", "at least one sea state"]),
    ("duplicate cell", "Hs = 3.5\nTp = 9.0", "Hs = 2.5\nTp = 10.0", ["[[sea_state]] #3", "same cell"]),
    ("duplicate variant", 'name = "H-0.7e6"', 'name = "H-1.018e6"', ["[[variant]] #2 name", "earlier variant"]),
    ("dot-dot name", 'name = "H-0.7e6"', 'name = ".."', ["[[variant]] #2 name", "starts with '.'"]),
    ("escaping name", 'name = "H-0.7e6"', 'name = "../escape"', ["[[variant]] #2 name", "starts with '.'"]),
    ("slash name", 'name = "H-0.7e6"', 'name = "a/b"', ["[[variant]] #2 name", "outside [A-Za-z0-9._-]"]),
    ("owned key", '"gyro.H" = 1.018e6', '"sea.Hs" = 2.0', ["[[variant]] #1 set", "set by the study"]),
    ("missing scene", SCENE, "/nonexistent/ship.toml", ["[study] scene", "cannot read"]),
    ("not a ship", SCENE, os.path.join(SOURCE, "sim", "scenes", "monorail.toml"),
     ["[study] scene", "ship_roll_damper"]),
    ("settle beyond duration", "settle_s = 1", "settle_s = 5", ["[study] settle_s", "longer than duration_s"]),
    ("too many tasks", "seeds_per_cell = 2",
     "seeds_per_cell = 10000\nheadings_deg = [" + ", ".join(str(h) for h in range(0, 100, 5)) + "]",
     ["[study]", "3 × 20 × 10000 × 2 = 1200000 tasks", "more than 1000000"]),
    ("headings' probabilities", "settle_s = 1", "settle_s = 1\nheadings_deg = [90, 45]\nheading_probability = [1]",
     ["[study] heading_probability", "2 headings"]),
]


def bad_studies(dir_):
    for what, old, new, expect in BAD:
        text = STUDY.format(scene=SCENE, second="H-0.7e6", second_H="0.7e6")
        if old is None:
            text = re.sub(r"\[\[sea_state\]\]\nHs = [^\n]*\nTp = [^\n]*\nprobability = [^\n]*\n\n", "", text)
        else:
            check("BadStudyFilesAreRefusedNothingWritten", old in text, f"{what}: the mutation does not apply")
            text = text.replace(old, new, 1)
        f = study(os.path.join(dir_, "bad.toml"), text=text)
        out_dir = os.path.join(dir_, "bad-out")
        shutil.rmtree(out_dir, ignore_errors=True)
        rc, out, err = run("sweep", f, "--out", out_dir)
        check("BadStudyFilesAreRefusedNothingWritten", rc == 2, f"{what}: exit 2 expected, got {rc}")
        for e in [f, *expect]:
            check("BadStudyFilesAreRefusedNothingWritten", e in err, f"{what}: '{e}' expected in: {err.strip()}")
        check("BadStudyFilesAreRefusedNothingWritten", not os.path.exists(out_dir), f"{what}: {out_dir} was created")
        check("BadStudyFilesAreRefusedNothingWritten", not os.path.exists(os.path.join(dir_, "escape")) and
              not os.path.exists(os.path.join(out_dir, "..", "escape")), f"{what}: something escaped")
    rc, _, err = run("sweep", study(os.path.join(dir_, "good.toml")), "--out", os.path.join(dir_, "x"), "--shard", "3/2")
    check("BadStudyFilesAreRefusedNothingWritten", rc == 2 and "--shard 3/2" in err, f"--shard 3/2: {rc} {err}")
    rc, _, err = run("sweep", "merge", dir_)
    check("BadStudyFilesAreRefusedNothingWritten", rc == 2 and "not a study directory" in err, f"merge: {rc} {err}")


def main():
    shutil.rmtree(WORK, ignore_errors=True)
    os.makedirs(WORK)
    study_file = study(os.path.join(WORK, "study.toml"))
    whole, base = shards_and_seeds(study_file)
    resume(study_file, base)
    failing_variant(WORK)
    damaged(whole, study_file, base)
    headings(WORK)
    os.makedirs(os.path.join(WORK, "bad"))
    bad_studies(os.path.join(WORK, "bad"))
    if failures:
        print(f"{len(failures)} failed", file=sys.stderr)
        return 1
    print("sweep_cli_test: all claims hold")
    return 0


if __name__ == "__main__":
    sys.exit(main())
