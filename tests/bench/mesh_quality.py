#!/usr/bin/env python3
"""The triangle-shape figures of a scansurf output folder (issue 28), as docs/method.md and
docs/benchmarks.md quote them: over OUTDIR/multilabel.ply, the triangles, their smallest angle,
its 5th percentile and mean, and the share under 5 degrees; over each OUTDIR/<feature>.ply, the
vertices whose area-weighted normal points against one of their faces (what a viewer's smooth
shading gets wrong).

  build/cli/scansurf SET.json -o OUT [--grid NX NY] && tests/bench/mesh_quality.py OUT
"""
import glob
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wireframe import read_ply  # noqa: E402


def smallest_angles(v, f):
    """Each triangle's smallest angle in degrees."""
    corners = []
    for a, b, c in ((0, 1, 2), (1, 2, 0), (2, 0, 1)):
        u, w = v[f[:, b]] - v[f[:, a]], v[f[:, c]] - v[f[:, a]]
        lengths = np.maximum(np.linalg.norm(u, axis=1) * np.linalg.norm(w, axis=1), 1e-300)
        corners.append(np.degrees(np.arccos(np.clip((u * w).sum(1) / lengths, -1, 1))))
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


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = sys.argv[1]
    v, f = read_ply(os.path.join(out, "multilabel.ply"))
    m = smallest_angles(v, f)
    print(f"{out}: multilabel.ply {len(f)} triangles; smallest angle {m.min():.2f}, 5th percentile "
          f"{np.percentile(m, 5):.2f}, mean {m.mean():.1f} degrees; {100 * (m < 5).mean():.2f} % under 5 degrees")
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
