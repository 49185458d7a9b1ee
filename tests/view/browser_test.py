#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Browser test of view.html and assembly.html (ctest: view_browser).

Runs `subfab decompose` (moai at the thesis's height 0.225), `subfab
assemble` and `subfab unfold` on a bundled model, then opens every page in
headless Debian chromium from disk with the network off (browser_check.py)
and checks, from screenshots:
  - decomposition view.html: no errors; the first frame drawn; the colour of
    every milling direction used present (views from above and below, fully
    exploded); in #check mode, every block's own flat colour present, and a
    click on a block shows that block's number and milling direction;
  - assembly.html: no errors, every direction's colour present in the pictures;
  - unfolding view.html: no errors, the first frame drawn, and at least 90 %
    of the nets' facets present in their #check colours.
Exit 0 on success, 1 on a failure, 77 (ctest SKIP_RETURN_CODE) when
chromium or three.js is not installed.
Usage: browser_test.py --subfab BUILD/subfab --data DATA_DIR --work DIR [--keep]
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import browser_check as bc  # noqa: E402

# Hues (degrees) of the milling directions' colours (subfab::direction_color).
DIRECTION_HUES = {"+x": 0, "-x": 180, "+y": 120, "-y": 300, "+z": 240, "-z": 60}
UP, DOWN = "eye=0.553,0.408,0.727", "eye=-0.553,-0.408,-0.727"


def id_color(i):
    """The flat colour of object i in #check mode (viewer.js's idColor)."""
    return (16 + 15 * (i % 16), 16 + 15 * ((i // 16) % 16), 16 + 15 * ((i // 256) % 16))


class Failures:
    def __init__(self):
        self.messages = []

    def check(self, ok, message):
        print(("ok      " if ok else "FAILED  ") + message)
        if not ok:
            self.messages.append(message)


def counts_of(png):
    _, _, rows = bc.read_png(png)
    return bc.color_counts(rows)


def run(cmd):
    print("$ " + " ".join(cmd))
    r = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if r.returncode != 0:
        print(r.stdout)
        raise SystemExit("command failed with exit %d" % r.returncode)


def pixel_near_centre(rows, color, hue=None):
    """A pixel of `color` (or, with `hue`, of that hue, saturated, away from
    edges): the one nearest the centroid of all of them."""
    def match(r, g, b):
        if hue is None:
            return (r, g, b) == color
        h, sat = bc.hue_of((r, g, b))
        return sat >= 0.3 and min(abs(h - hue), 360 - abs(h - hue)) <= 6
    points = []
    for y, row in enumerate(rows):
        for x in range(0, len(row), 3):
            if match(row[x], row[x + 1], row[x + 2]):
                points.append((x // 3, y))
    if hue is not None:  # keep pixels whose four neighbours match too (not on an edge)
        inside = set(points)
        points = [(x, y) for (x, y) in points
                  if all(p in inside for p in ((x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)))]
    if not points:
        return None
    cx = sum(p[0] for p in points) / len(points)
    cy = sum(p[1] for p in points) / len(points)
    return min(points, key=lambda p: (p[0] - cx) ** 2 + (p[1] - cy) ** 2)


def check_decomposition(page, folder, work, f):
    doc = json.load(open(os.path.join(folder, "decomposition.json")))
    axes = [b["axis"] for b in doc["blocks"]]
    view = os.path.join(folder, "view.html")
    counts = {}
    for name, hash_part in (("up", UP + "&explode=100"), ("down", DOWN + "&explode=100"), ("default", "")):
        status = page.open(view, hash_part)
        f.check(status["objects"] == len(axes), "view.html (%s): %d blocks drawn (%s)" % (name, len(axes), status))
        png = os.path.join(work, "view_%s.png" % name)
        page.screenshot(png)
        for rgb, k in counts_of(png).items():
            counts[rgb] = counts.get(rgb, 0) + k
    for axis in sorted(set(axes)):
        n = bc.pixels_of_hue(counts, DIRECTION_HUES[axis])
        f.check(n >= 30, "view.html: %d pixels of the %s colour (hue %d)" % (n, axis, DIRECTION_HUES[axis]))
    # In the default view (lit, the scene right of the panel), a click on a
    # pixel of a direction's hue shows a block of that direction.
    page.open(view)
    panel_right = int(page.evaluate("Math.ceil(document.getElementById('panel').getBoundingClientRect().right)"))
    rows = [row[3 * (panel_right + 1):] for row in bc.read_png(os.path.join(work, "view_default.png"))[2]]
    for axis in sorted(set(axes)):
        at = pixel_near_centre(rows, None, hue=DIRECTION_HUES[axis])
        at = at and (at[0] + panel_right + 1, at[1])  # the legend's swatches are left out
        if not at:
            continue
        page.click(*at)
        info = page.evaluate("document.getElementById('info').textContent")
        f.check("Milling direction" + axis in info, "default view: click at %s on the %s colour shows a %s block: %r"
                % (at, axis, axis, info[:60]))
    # Every block in its own flat colour, then a click on each.
    shots = {}
    for name, hash_part in (("up", "check&" + UP), ("down", "check&" + DOWN)):
        page.open(view, hash_part)
        png = os.path.join(work, "view_check_%s.png" % name)
        page.screenshot(png)
        shots[name] = bc.read_png(png)[2]
    for i, block in enumerate(doc["blocks"]):
        seen = {name: pixel_near_centre(rows, id_color(i)) for name, rows in shots.items()}
        f.check(any(seen.values()), "view.html#check: block %d drawn (%s)" % (block["id"], seen))
        for name in ("up", "down"):
            if seen[name]:
                page.open(view, "check&" + (UP if name == "up" else DOWN))
                page.click(*seen[name])
                info = page.evaluate("document.getElementById('info').textContent")
                f.check("block %d" % block["id"] in info and block["axis"] in info,
                        "click on block %d at %s shows it: %r" % (block["id"], seen[name], info[:80]))
                break
    errors = page.errors()
    f.check(not errors, "view.html: no console or page errors %s" % errors)


def check_assembly(page, folder, work, f):
    doc = json.load(open(os.path.join(folder, "decomposition.json")))
    page.open(os.path.join(folder, "assembly.html"))
    png = os.path.join(work, "assembly.png")
    page.screenshot(png, full_page=True)
    counts = counts_of(png)
    for axis in sorted({b["axis"] for b in doc["blocks"]}):
        n = bc.pixels_of_hue(counts, DIRECTION_HUES[axis])
        f.check(n >= 30, "assembly.html: %d pixels of the %s colour" % (n, axis))
    text = page.evaluate("document.body.innerText")
    f.check("Gluing order" in text and "Step %d:" % len(doc["blocks"]) in text and " mm" in text,
            "assembly.html: gluing order of all %d blocks, sizes in mm" % len(doc["blocks"]))
    errors = page.errors()
    f.check(not errors, "assembly.html: no console or page errors %s" % errors)


def check_unfolding(page, folder, work, f):
    facets = json.load(open(os.path.join(folder, "unfold.json")))["facets"]
    view = os.path.join(folder, "view.html")
    status = page.open(view)
    f.check(status["frames"] > 0, "unfold view.html: first frame drawn")
    page.screenshot(os.path.join(work, "unfold.png"))
    status = page.open(view, "check&explode=0")
    png = os.path.join(work, "unfold_check.png")
    page.screenshot(png)
    counts = counts_of(png)
    n = len(facets)
    f.check(status["objects"] == 2 * n, "unfold view.html: %d facets, each on the model and on the sheet" % n)
    on_sheet = sum(1 for j in range(n) if counts.get(id_color(n + j), 0) > 0)
    f.check(on_sheet >= 0.9 * n, "unfold view.html#check: %d of %d facets seen on the sheet" % (on_sheet, n))
    errors = page.errors()
    f.check(not errors, "unfold view.html: no console or page errors %s" % errors)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--subfab", required=True)
    parser.add_argument("--data", required=True)
    parser.add_argument("--work", required=True)
    args = parser.parse_args()
    if not bc.find_chromium():
        print("SKIPPED: chromium is not installed (scripts/setup.sh installs Debian's chromium)")
        return bc.SKIP
    three = os.environ.get("SUBFAB_THREE_JS", "/usr/share/javascript/three/three.min.js")
    if not os.path.isfile(three):
        print("SKIPPED: three.js is not installed at %s (scripts/setup.sh installs libjs-three)" % three)
        return bc.SKIP
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    model = os.path.join(args.data, "moai.obj")
    dec, unf = os.path.join(args.work, "decomposition"), os.path.join(args.work, "unfolding")
    run([args.subfab, "decompose", model, "-o", dec, "--max-height", "0.225", "--quiet"])
    run([args.subfab, "assemble", dec, "--size", "200", "--quiet"])
    run([args.subfab, "unfold", model, "-o", unf, "--quiet"])
    f = Failures()
    with bc.Page() as page:
        check_decomposition(page, dec, args.work, f)
        check_assembly(page, dec, args.work, f)
        check_unfolding(page, unf, args.work, f)
    print("%d failure(s); screenshots in %s" % (len(f.messages), args.work))
    return 1 if f.messages else 0


if __name__ == "__main__":
    sys.exit(main())
