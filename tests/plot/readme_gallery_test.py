#!/usr/bin/python3
"""README.md's device gallery and links are current (ctest label plot; under 1 s).

Fails when
- the README's gallery table (between the markers) is not the one tools/gallery/gallery writes from the
  registry (tools/devices/registry.cpp) and the signal tables (tools/devices/*/*_signals.toml): a device added,
  removed or renamed, a changed title or a new first scene -> run `tools/gallery/gallery` (pictures and table)
  or `tools/gallery/gallery --table-only`;
- the registry and the signal tables list different devices, or a device folder under tools/devices/ with a
  signal table is missing from the table;
- a picture, model page or scene the table links does not exist, or a picture is not a PNG;
- any relative link of README.md or docs/README.md points to a missing file;
- README.md does not hold the test command that .ci/run runs (CI runs the README's test command verbatim).
The pictures are not regenerated here.
"""
import glob
import os
import re
import sys

sys.dont_write_bytecode = True
REPO = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(REPO, "tools", "gallery"))
import gallery_table  # noqa: E402

failures = []


def check(cond, message):
    if not cond:
        failures.append(message)


def read(rel):
    with open(os.path.join(REPO, rel), encoding="utf-8") as f:
        return f.read()


readme = read("README.md")

# The table is exactly the generated one.
try:
    expected = gallery_table.table(REPO)
except gallery_table.GalleryError as e:
    expected = None
    check(False, str(e))
actual = gallery_table.readme_table(readme)
check(actual is not None, "README.md: no gallery markers")
if expected is not None and actual is not None and actual != expected:
    missing = [line for line in expected if line not in actual]
    extra = [line for line in actual if line not in expected]
    check(False, "README.md: the gallery table is stale (run tools/gallery/gallery --table-only, or "
                 "tools/gallery/gallery for new pictures)\n  missing rows:\n    " + "\n    ".join(missing)
          + "\n  rows no longer generated:\n    " + "\n    ".join(extra))

# Every device folder with a signal table has a row, independently of the generator.
table_text = "\n".join(actual or [])
for path in sorted(glob.glob(os.path.join(REPO, "tools", "devices", "*", "*_signals.toml"))):
    device = os.path.basename(os.path.dirname(path))
    check(f"({gallery_table.picture(device)})" in table_text, f"README.md: device {device} has no gallery row")
    check(f"({gallery_table.model_page(device)})" in table_text,
          f"README.md: device {device}'s row does not link {gallery_table.model_page(device)}")

# Every file the table links exists; the pictures are PNGs.
for target in re.findall(r"\]\(([^)#]+)(?:#[^)]*)?\)", table_text):
    full = os.path.join(REPO, target)
    check(os.path.isfile(full), f"README.md gallery: {target} does not exist")
    if target.endswith(".png") and os.path.isfile(full):
        with open(full, "rb") as f:
            check(f.read(8) == b"\x89PNG\r\n\x1a\n", f"README.md gallery: {target} is not a PNG")

# Every relative link of the README and of the docs index resolves.
for rel in ("README.md", "docs/README.md"):
    if not os.path.isfile(os.path.join(REPO, rel)):
        check(False, f"{rel} does not exist")
        continue
    base = os.path.dirname(os.path.join(REPO, rel))
    for target in re.findall(r"\]\(([^)\s]+)\)", read(rel)):
        if re.match(r"[a-z]+:", target) or target.startswith("#"):
            continue
        path = target.split("#", 1)[0]
        check(os.path.exists(os.path.normpath(os.path.join(base, path))), f"{rel}: link {target} is broken")

# The README's test command is the one CI runs verbatim.
m = re.search(r'^stage "README test command"\n(.+)$', read(".ci/run"), re.M)
check(m is not None, ".ci/run: no README test command stage")
if m:
    check(m.group(1).strip() in readme, f"README.md does not hold CI's test command `{m.group(1).strip()}`")

for f in failures:
    print("FAIL:", f)
print(f"readme_gallery_test: {len(failures)} failure(s)")
sys.exit(1 if failures else 0)
