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
    of the nets' facets present in their #check colours;
  - hexmesh view.html (`subfab hexmesh` on a capsule written here): no
    errors, every cell counted; in #check mode (unlit) the colour of every
    quality bin holding at least 3 % of the boundary faces present (bins and
    scaled Jacobians read from hexmesh.vtk, colours from the page's legend),
    and nothing but legend and structure colours; a cut at mid x shows the
    cells whose centre is there; a click on a cell names it and gives its
    scaled Jacobian as hexmesh.vtk has it; preview.png shows the same bins'
    hues and the grey tubular structure.
Exit 0 on success, 1 on a failure, 77 (ctest SKIP_RETURN_CODE) when
chromium or three.js is not installed.
Usage: browser_test.py --subfab BUILD/subfab --data DATA_DIR --work DIR [--keep]
"""
import argparse
import json
import math
import os
import re
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


def write_capsule(path, radius=1.0, length=4.0, around=32, cap_rings=8):
    """A closed, outward-oriented capsule along x (a surface of revolution) as OFF."""
    profile = []  # (x, r) from the left pole's first ring to the right pole's last
    for k in range(1, cap_rings + 1):
        a = math.pi / 2 * k / cap_rings
        profile.append((-radius * math.cos(a), radius * math.sin(a)))
    for k in range(cap_rings):
        a = math.pi / 2 * (cap_rings - k) / cap_rings
        profile.append((length + radius * math.cos(a), radius * math.sin(a)))
    verts = [(-radius, 0.0, 0.0)]
    for x, r in profile:
        for j in range(around):
            t = 2 * math.pi * j / around
            verts.append((x, r * math.cos(t), r * math.sin(t)))
    verts.append((length + radius, 0.0, 0.0))
    ring = lambda k, j: 1 + k * around + j % around  # noqa: E731
    faces = [(0, ring(0, j + 1), ring(0, j)) for j in range(around)]
    for k in range(len(profile) - 1):
        for j in range(around):
            a, b, c, d = ring(k, j), ring(k, j + 1), ring(k + 1, j + 1), ring(k + 1, j)
            faces += [(a, b, c), (a, c, d)]
    last, pole = len(profile) - 1, len(verts) - 1
    faces += [(pole, ring(last, j), ring(last, j + 1)) for j in range(around)]
    with open(path, "w") as out:
        out.write("OFF\n%d %d 0\n" % (len(verts), len(faces)))
        out.writelines("%.9g %.9g %.9g\n" % v for v in verts)
        out.writelines("3 %d %d %d\n" % f for f in faces)


def read_vtk_hexes(path):
    """Points, hexahedra (8 corners each) and the per-cell scaled Jacobian of hexmesh.vtk."""
    lines = open(path).read().split("\n")
    at = next(i for i, l in enumerate(lines) if l.startswith("POINTS"))
    n = int(lines[at].split()[1])
    points = [tuple(map(float, lines[at + 1 + i].split())) for i in range(n)]
    at = next(i for i, l in enumerate(lines) if l.startswith("CELLS"))
    cells = [tuple(map(int, lines[at + 1 + i].split()[1:])) for i in range(int(lines[at].split()[1]))]
    at = next(i for i, l in enumerate(lines) if l.startswith("LOOKUP_TABLE"))
    sj = [float(lines[at + 1 + i]) for i in range(len(cells))]
    return points, cells, sj


HEX_FACES = ((0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (1, 2, 6, 5), (2, 3, 7, 6), (3, 0, 4, 7))


def quality_bin(sj):
    """hexmesh.json's histogram bin: 0 for <= 0, then b for ((b-1)/10, b/10]."""
    return 0 if sj <= 0 else min(10, max(1, math.ceil(sj * 10 - 1e-12)))


def near_colours(rows, at, r):
    """The colours of the pixels within r of `at` (a click may land on the border of two cells)."""
    x0, y0 = at
    out = set()
    for y in range(max(0, y0 - r), min(len(rows), y0 + r + 1)):
        for x in range(max(0, x0 - r), min(len(rows[y]) // 3, x0 + r + 1)):
            out.add(tuple(rows[y][3 * x:3 * x + 3]))
    return out


def check_hexmesh(page, folder, work, f):
    points, cells, sj = read_vtk_hexes(os.path.join(folder, "hexmesh.vtk"))
    faces = {}
    for c, cell in enumerate(cells):
        for q in HEX_FACES:
            faces.setdefault(tuple(sorted(cell[k] for k in q)), []).append(c)
    boundary_bins = {}
    for owners in faces.values():
        if len(owners) == 1:
            b = quality_bin(sj[owners[0]])
            boundary_bins[b] = boundary_bins.get(b, 0) + 1
    total_faces = sum(boundary_bins.values())
    common = sorted(b for b, k in boundary_bins.items() if k >= 0.03 * total_faces)
    view = os.path.join(folder, "view.html")
    html = open(view).read()
    legend = [tuple(int(h[i:i + 2], 16) for i in (0, 2, 4))
              for h in re.findall(r'<span style="background:#([0-9a-f]{6})"></span>', html)]
    f.check(len(legend) == 11, "hexmesh view.html: a legend of 11 quality bins")
    status = page.open(view)
    f.check(status["frames"] > 0 and status.get("cellsShown") == len(cells),
            "hexmesh view.html: first frame drawn, %d cells (%s)" % (len(cells), status))
    page.screenshot(os.path.join(work, "hex.png"))
    counts = {}
    for name, hash_part in (("up", "check&" + UP), ("down", "check&" + DOWN)):
        page.open(view, hash_part)
        png = os.path.join(work, "hex_check_%s.png" % name)
        page.screenshot(png)
        for rgb, k in counts_of(png).items():
            counts[rgb] = counts.get(rgb, 0) + k
    for b in common:
        n = counts.get(legend[b], 0)
        f.check(n >= 30, "hexmesh view.html#check: %d pixels of bin %d's colour %s (%d of %d boundary faces)"
                % (n, b, legend[b], boundary_bins[b], total_faces))
    drawn = sum(k for rgb, k in counts.items() if rgb != (0, 0, 0))
    known = sum(k for rgb, k in counts.items() if rgb in legend or rgb == id_color(1))
    f.check(drawn > 0 and known == drawn, "hexmesh view.html#check: %d of %d drawn pixels are legend colours "
            "or the structure's" % (known, drawn))
    # A cut half way along x keeps the cells whose centre is at most there.
    cx = [sum(points[v][0] for v in cell) / 8 for cell in cells]
    mid = min(cx) + 0.5 * (max(cx) - min(cx))
    expected = sum(1 for x in cx if x <= mid)
    status = page.open(view, "check&cut=x,50&" + UP)
    f.check(abs(status.get("cellsShown", -1) - expected) <= 2 and 0 < expected < len(cells),
            "hexmesh view.html#cut=x,50: %s cells shown, %d expected" % (status.get("cellsShown"), expected))
    png = os.path.join(work, "hex_cut.png")
    page.screenshot(png)
    # A click on a cell shows its number and its scaled Jacobian.
    rows = bc.read_png(png)[2]
    at = None
    for b in sorted(common, key=lambda b: -boundary_bins[b]):
        at = pixel_near_centre(rows, legend[b])
        if at:
            break
    if at:
        page.click(*at)
        cell = page.evaluate("window.subfabStatus.pickedCell")
        info = page.evaluate("document.getElementById('info').textContent")
        # The page holds the values in float32 and prints 3 decimals: a value
        # near a rounding boundary may print 0.001 away from the .vtk's.
        shown = [float(x) for x in re.findall(r"-?\d+\.\d{3}(?!\d)", info)]
        ok = isinstance(cell, int) and 0 <= cell < len(cells) \
            and any(abs(v - sj[cell]) <= 0.0005 + 1e-6 for v in shown) \
            and legend[quality_bin(sj[cell])] in near_colours(rows, at, 2)
        if not ok:
            print("click details: info=%r shown=%r pixel=%r" % (info, shown, tuple(rows[at[1]][3 * at[0]:3 * at[0] + 3])))
        f.check(ok, "click at %s shows cell %s with its scaled Jacobian (%s) and colour: %r"
                % (at, cell, "%.3f" % sj[cell] if isinstance(cell, int) and 0 <= cell < len(cells) else "?",
                   info[:90]))
    else:
        f.check(False, "hexmesh view.html#cut: no pixel of a common bin's colour to click")
    errors = page.errors()
    f.check(not errors, "hexmesh view.html: no console or page errors %s" % errors)
    # preview.png: the common bins' hues and the structure's grey.
    preview = counts_of(os.path.join(folder, "preview.png"))
    for b in common:
        hue = bc.hue_of(legend[b])[0]
        n = bc.pixels_of_hue(preview, hue, tolerance=4)
        f.check(n >= 20, "preview.png: %d pixels of bin %d's hue %.0f" % (n, b, hue))
    grey = sum(k for (r, g, b), k in preview.items() if r == g and 3 <= b - r <= 8 and r > 70)
    f.check(grey >= 200, "preview.png: %d pixels of the tubular structure's grey" % grey)


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
    capsule, hexdir = os.path.join(args.work, "capsule.off"), os.path.join(args.work, "hexmesh")
    write_capsule(capsule)
    run([args.subfab, "hexmesh", capsule, "-o", hexdir, "--subdivisions", "1", "--quiet"])
    f = Failures()
    with bc.Page() as page:
        check_decomposition(page, dec, args.work, f)
        check_assembly(page, dec, args.work, f)
        check_unfolding(page, unf, args.work, f)
        check_hexmesh(page, hexdir, args.work, f)
    print("%d failure(s); screenshots in %s" % (len(f.messages), args.work))
    return 1 if f.messages else 0


if __name__ == "__main__":
    sys.exit(main())
