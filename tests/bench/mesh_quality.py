#!/usr/bin/env python3
"""The triangle-shape figures of a scansurf output folder (issue 28), as docs/method.md and
docs/benchmarks.md quote them: over OUTDIR/multilabel.ply, the triangles, their smallest angle,
its 5th percentile and mean, and the share under 5 degrees; over each OUTDIR/<feature>.ply, the
vertices whose area-weighted normal points against one of their faces (what a viewer's smooth
shading gets wrong). With --planes SET.json, where the triangles under 5 and 15 degrees sit: the
share with a vertex on a lattice layer (the set's contour planes, and with --per-gap N the N - 1
layers interpolated between each two and in the caps), with an edge on one, and with a junction vertex (its
triangles carry more than one label pair), each against the share of all triangles.

  build/cli/scansurf SET.json -o OUT [--grid NX NY] && tests/bench/mesh_quality.py OUT [--planes SET.json [--per-gap N]]
"""
import argparse
import glob
import json
import os
import re
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wireframe import read_ply  # noqa: E402


def smallest_angles(v, f):
    """Each triangle's smallest angle in degrees (v: points, f: triangles as rows of 3 indices)."""
    corners = []
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        u, w = v[f[:, b]] - v[f[:, a]], v[f[:, c]] - v[f[:, a]]
        corners.append(np.degrees(np.arctan2(np.linalg.norm(np.cross(u, w), axis=1), (u * w).sum(1))))
    return np.minimum.reduce(corners)


def normals_against_faces(v, f):
    """Used vertices, and those whose area-weighted normal has a non-positive dot with one of its faces' normals."""
    face_normals = np.cross(v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]])
    vertex_normals = np.zeros_like(v)
    for c in range(3):
        np.add.at(vertex_normals, f[:, c], face_normals)
    against = np.zeros(len(v), bool)
    for c in range(3):
        np.logical_or.at(against, f[:, c], (vertex_normals[f[:, c]] * face_normals).sum(1) <= 0)
    used = np.zeros(len(v), bool)
    used[f.ravel()] = True
    return int(used.sum()), int((against & used).sum())


def label_pairs(path, faces):
    """Each face's (label_inside, label_outside) of a scansurf multilabel.ply, as one integer."""
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            header += f.readline()
        vertices = int(re.search(rb"element vertex (\d+)", header).group(1))
        f.seek(len(header) + 12 * vertices)
        record = np.dtype([("n", "u1"), ("v", "<i4", 3), ("inside", "<u2"), ("outside", "<u2")])
        data = np.frombuffer(f.read(record.itemsize * faces), dtype=record)
    return data["inside"].astype(np.int64) * 65536 + data["outside"]


def layer_heights(set_path, per_gap):
    """The contour planes' z of a contours JSON, and per_gap - 1 evenly spaced layers between each two
    (and in the caps' gap beyond each end)."""
    with open(set_path) as f:
        planes = sorted({s["z"] for feature in json.load(f)["features"] for s in feature["slices"]})
    if per_gap > 1:  # the round caps take one more gap beyond each end
        planes = [2 * planes[0] - planes[1]] + planes + [2 * planes[-1] - planes[-2]]
    layers = [planes[0]]
    for a, b in zip(planes, planes[1:]):
        layers += [a + (b - a) * k / per_gap for k in range(1, per_gap + 1)]
    return np.array(layers)


def where_slivers(v, f, pairs, layers, smallest):
    """Shares of the sharp triangles (and of all) with a vertex on a layer, an edge on one, a junction vertex."""
    on_layer = np.min(np.abs(v[:, 2][:, None] - layers[None, :]), axis=1) < 1e-3
    low = np.full(len(v), np.iinfo(np.int64).max)
    high = np.full(len(v), -1)
    for c in range(3):
        np.minimum.at(low, f[:, c], pairs)
        np.maximum.at(high, f[:, c], pairs)
    junction = (low != high)[f].any(1)
    vertex_on, edge_on = on_layer[f].any(1), on_layer[f].sum(1) >= 2
    sides = np.stack([np.linalg.norm(v[f[:, (c + 1) % 3]] - v[f[:, c]], axis=1) for c in range(3)], 1)
    side_on = np.stack([on_layer[f[:, c]] & on_layer[f[:, (c + 1) % 3]] for c in range(3)], 1)
    share = lambda mask, among: 100 * mask[among].mean() if among.any() else 0.0  # noqa: E731
    everything = np.ones(len(f), bool)
    for limit in (5, 15):
        sharp = smallest < limit
        print(f"  under {limit} degrees: {share(vertex_on, sharp):.1f} % with a vertex on a layer (all: "
              f"{share(vertex_on, everything):.1f} %), {share(edge_on, sharp):.1f} % with an edge on one (all: "
              f"{share(edge_on, everything):.1f} %), {share(junction, sharp):.1f} % with a junction vertex (all: "
              f"{share(junction, everything):.1f} %)")
    held = (smallest < 5) & edge_on
    if held.any():
        shortest_on = side_on[np.arange(len(f)), np.argmin(sides, 1)]
        print(f"  under 5 degrees with an edge on a layer: {share(shortest_on, held):.1f} % have their shortest side "
              f"there; median shortest side {np.median(sides[held].min(1)):.3f}, longest {np.median(sides[held].max(1)):.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("out", help="a scansurf output folder")
    ap.add_argument("--planes", help="the contours JSON it was made from: where the sharp triangles sit")
    ap.add_argument("--per-gap", type=int, default=1, help="layers per slice gap, as the CLI's interpolation line says")
    args = ap.parse_args()
    out = args.out
    v, f = read_ply(os.path.join(out, "multilabel.ply"))
    m = smallest_angles(v, f)
    print(f"{out}: multilabel.ply {len(f)} triangles; smallest angle {m.min():.2f}, 5th percentile "
          f"{np.percentile(m, 5):.2f}, mean {m.mean():.1f} degrees; {100 * (m < 5).mean():.2f} % under 5 degrees")
    if args.planes:
        pairs = label_pairs(os.path.join(out, "multilabel.ply"), len(f))
        where_slivers(v, f, pairs, layer_heights(args.planes, args.per_gap), m)
    used = against = 0
    for ply in sorted(glob.glob(os.path.join(out, "*.ply"))):
        if os.path.basename(ply) == "multilabel.ply":
            continue
        v, f = read_ply(ply)
        if len(f):
            u, a = normals_against_faces(v, f)
            used, against = used + u, against + a
    print(f"{out}: feature surfaces {used} vertices, {against} ({100 * against / max(used, 1):.3f} %) with a normal "
          f"against one of their faces")


if __name__ == "__main__":
    main()
