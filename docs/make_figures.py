#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws the README's picture: docs/images/moai_blocks.png, the input model next
to its height-field blocks, each block in its own colour, pulled apart along
its milling direction.

Needs Debian's python3-matplotlib (numpy and PIL come with it):

    apt-get install -y python3-matplotlib

It is a documentation tool, not a build dependency (scripts/setup.sh does not
install it). Run it from the repository root, after `make run` (which builds
build/subfab):

    /usr/bin/python3 docs/make_figures.py
        # decomposes data/moai.obj at --max-height 0.225 into a temporary
        # folder with build/subfab, then draws docs/images/moai_blocks.png
    /usr/bin/python3 docs/make_figures.py --decomposition out/example
        # draws an existing folder written by `subfab decompose` instead
        # (`make run` writes out/example)

Options: --subfab PATH, --model MESH, --max-height F, --out PNG (see --help).
The drawing is an orthographic view with flat Lambert shading, painted back to
front (matplotlib's 2D polygons; no OpenGL needed).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

# One colour per block (cycled when there are more blocks): muted, distinct.
PALETTE = [
    "#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#b07aa1",
    "#edc948", "#76b7b2", "#ff9da7", "#9c755f", "#bab0ac",
]
INPUT_COLOUR = "#c8c4bc"
BACKGROUND = "#ffffff"


def read_obj(path):
    """Vertices (n x 3) and triangles (m x 3, 0-based) of an OBJ file
    (polygons are fanned into triangles)."""
    vertices, faces = [], []
    with open(path) as f:
        for line in f:
            if line.startswith("v "):
                vertices.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                ids = [int(tok.split("/")[0]) for tok in line.split()[1:]]
                ids = [i - 1 if i > 0 else len(vertices) + i for i in ids]
                for k in range(1, len(ids) - 1):
                    faces.append([ids[0], ids[k], ids[k + 1]])
    return np.array(vertices, dtype=float), np.array(faces, dtype=int)


def view_matrix(azimuth_deg, elevation_deg, up_axis):
    """Rotation taking model coordinates to view coordinates (x right, y up,
    z towards the viewer): turn about the up axis, then tilt."""
    # Put the model's up axis on view y.
    if up_axis == "y":
        base = np.eye(3)
    elif up_axis == "z":
        base = np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], dtype=float)
    else:
        base = np.array([[0, 1, 0], [1, 0, 0], [0, 0, -1]], dtype=float)
    a, e = np.radians(azimuth_deg), np.radians(elevation_deg)
    turn = np.array([[np.cos(a), 0, np.sin(a)], [0, 1, 0], [-np.sin(a), 0, np.cos(a)]])
    tilt = np.array([[1, 0, 0], [0, np.cos(e), -np.sin(e)], [0, np.sin(e), np.cos(e)]])
    return tilt @ turn @ base


def shaded_polygons(meshes, rotation):
    """2D polygons, colours and depths of the front faces of `meshes`
    (a list of (vertices, faces, rgb)), shaded with two lights."""
    light = np.array([-0.45, 0.65, 0.62])
    light /= np.linalg.norm(light)
    fill = np.array([0.6, -0.2, 0.77])
    fill /= np.linalg.norm(fill)
    polys, colours, depths = [], [], []
    for vertices, faces, rgb in meshes:
        v = vertices @ rotation.T
        tri = v[faces]  # m x 3 x 3
        n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        length = np.linalg.norm(n, axis=1)
        keep = (length > 0) & (n[:, 2] > 0)  # front faces only (closed meshes)
        tri, n = tri[keep], n[keep] / length[keep, None]
        shade = 0.38 + 0.52 * np.clip(n @ light, 0, 1) + 0.18 * np.clip(n @ fill, 0, 1)
        shade = np.clip(shade, 0, 1.08)
        c = np.clip(np.asarray(rgb)[None, :] * shade[:, None], 0, 1)
        polys.append(tri[:, :, :2])
        colours.append(c)
        depths.append(tri[:, :, 2].mean(axis=1))
    polys = np.concatenate(polys)
    colours = np.concatenate(colours)
    depths = np.concatenate(depths)
    order = np.argsort(depths)  # far to near
    return polys[order], colours[order]


def draw_panels(panels, rotation, width_inches=10.0):
    """One panel per (meshes, title), side by side, all at the same scale
    (model units per inch), each drawing centred in its panel."""
    painted = [shaded_polygons(meshes, rotation) for meshes, _ in panels]
    extents = [(p.reshape(-1, 2).min(axis=0), p.reshape(-1, 2).max(axis=0)) for p, _ in painted]
    pad = 0.05 * max((hi - lo).max() for lo, hi in extents)
    widths = [hi[0] - lo[0] + 2 * pad for lo, hi in extents]
    height = max(hi[1] - lo[1] for lo, hi in extents) + 2 * pad
    title_inches = 0.55
    height_inches = width_inches * height / sum(widths) + title_inches
    fig, axes = plt.subplots(1, len(panels), figsize=(width_inches, height_inches), dpi=100,
                             gridspec_kw={"width_ratios": widths, "wspace": 0.0})
    fig.subplots_adjust(left=0, right=1, bottom=0, top=1 - title_inches / height_inches)
    for ax, (polys, colours), (lo, hi), (_, title) in zip(axes, painted, extents, panels):
        ax.add_collection(PolyCollection(polys, facecolors=colours, edgecolors=colours, linewidths=0.25,
                                         antialiaseds=True))
        centre = (lo + hi) / 2
        half_w = (hi[0] - lo[0]) / 2 + pad
        ax.set_xlim(centre[0] - half_w, centre[0] + half_w)
        ax.set_ylim(centre[1] - height / 2, centre[1] + height / 2)
        ax.set_aspect("equal")
        ax.axis("off")
        ax.set_title(title, fontsize=11, color="#333333")
    return fig


def hex_rgb(colour):
    colour = colour.lstrip("#")
    return np.array([int(colour[k:k + 2], 16) / 255.0 for k in (0, 2, 4)])


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--subfab", default="build/subfab", help="the subfab binary [build/subfab]")
    parser.add_argument("--model", default="data/moai.obj", help="input mesh (OBJ) [data/moai.obj]")
    parser.add_argument("--max-height", default="0.225", help="decompose --max-height [0.225, thesis Table 4.1]")
    parser.add_argument("--decomposition", help="existing folder written by subfab decompose (skips decomposing)")
    parser.add_argument("--out", default="docs/images/moai_blocks.png", help="PNG to write")
    parser.add_argument("--explode", type=float, default=0.07,
                        help="how far each block moves along its milling direction, x bbox diagonal [0.07]")
    parser.add_argument("--azimuth", type=float, default=-30.0, help="view turn about the up axis, degrees [-30]")
    parser.add_argument("--elevation", type=float, default=18.0, help="view tilt, degrees [18]")
    parser.add_argument("--up", default="y", choices=["x", "y", "z"], help="the model's up axis [y]")
    args = parser.parse_args()

    scratch = None
    folder = args.decomposition
    if folder is None:
        scratch = tempfile.TemporaryDirectory(prefix="subfab_figure_")
        folder = scratch.name
        cmd = [args.subfab, "decompose", args.model, "-o", folder, "--max-height", args.max_height, "--quiet"]
        print("running:", " ".join(cmd), file=sys.stderr)
        subprocess.run(cmd, check=True)
    with open(os.path.join(folder, "decomposition.json")) as f:
        doc = json.load(f)

    model_v, model_f = read_obj(args.model if args.decomposition is None else doc["input"]["path"])
    diagonal = doc["input"]["bbox_diagonal"]
    blocks, assembled = [], []
    for k, b in enumerate(doc["blocks"]):
        v, f = read_obj(os.path.join(folder, b["mesh"]))
        colour = hex_rgb(PALETTE[k % len(PALETTE)])
        shift = np.asarray(b["direction"], dtype=float) * args.explode * diagonal
        assembled.append((v, f, colour))
        blocks.append((v + shift, f, colour))

    rotation = view_matrix(args.azimuth, args.elevation, args.up)
    name = os.path.basename(doc["input"]["path"])
    height = doc["parameters"].get("max_height_fraction")
    limit = f" (--max-height {height:g})" if height is not None else ""
    fig = draw_panels([([(model_v, model_f, hex_rgb(INPUT_COLOUR))], f"input: {name}"),
                       (assembled, f"{len(blocks)} height-field blocks{limit}"),
                       (blocks, "pulled apart along their milling directions")], rotation)
    fig.patch.set_facecolor(BACKGROUND)
    if scratch is not None:
        scratch.cleanup()

    os.makedirs(os.path.dirname(os.path.abspath(args.out)), exist_ok=True)
    tmp = args.out + ".full.png"
    fig.savefig(tmp, facecolor=BACKGROUND)
    plt.close(fig)
    # Palette PNG: a fraction of the size of the RGBA one, no visible loss.
    from PIL import Image

    Image.open(tmp).convert("RGB").quantize(colors=256, method=Image.Quantize.MEDIANCUT,
                                              dither=Image.Dither.NONE).save(args.out, optimize=True)
    os.remove(tmp)
    print(f"wrote {args.out} ({os.path.getsize(args.out) // 1024} KB)", file=sys.stderr)


if __name__ == "__main__":
    main()
