#!/usr/bin/env python3
"""The analytic sphere's shape figures (issue 28): a sphere of radius 20 mm drawn on slices 3 mm
apart (256 points per contour), surfaced at 1 mm pixels with scansurf's defaults plus any flags
given; prints the faces, the area-weighted mean and 95th percentile of the angle between each
face's normal and the true sphere's at its centroid, the smallest and 5th-percentile angle, and
the vertices' mean and largest distance to the true sphere; then the normal figures between the
first and last contours and over each cap beyond them. --gap G and --pixel P (before the
flags) draw the slices G mm apart and surface them at P mm pixels.

  tests/bench/sphere_shape.py build/cli/scansurf [--gap G] [--pixel P] [FLAG...]      e.g. --no-simplify, --remesh
"""
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from mesh_quality import smallest_angles  # noqa: E402
from wireframe import read_ply  # noqa: E402


def sphere_contours(radius=20.0, gap=3.0, points=256):
    slices, z = [], -radius + gap
    while z < radius - 1e-9:
        r = math.sqrt(radius * radius - z * z)
        ring = [[r * math.cos(2 * math.pi * i / points), r * math.sin(2 * math.pi * i / points)] for i in range(points)]
        slices.append({"z": z, "contours": [ring]})
        z += gap
    return {"version": 1, "units": "mm", "features": [{"name": "ball", "slices": slices}]}


def main():
    scansurf, flags = sys.argv[1], sys.argv[2:]
    grid = {"--gap": "3", "--pixel": "1"}
    while flags[:1] and flags[0] in grid and len(flags) > 1:
        grid[flags[0]], flags = flags[1], flags[2:]
    with tempfile.TemporaryDirectory() as work:
        source = os.path.join(work, "sphere.json")
        with open(source, "w") as f:
            json.dump(sphere_contours(gap=float(grid["--gap"])), f)
        out = os.path.join(work, "out")
        subprocess.run([scansurf, source, "-o", out, "--voxel-size", grid["--pixel"], "-q", *flags], check=True)
        v, faces = read_ply(os.path.join(out, "ball.ply"))
    p = v[faces]
    n = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    centre = p.mean(1)
    area = np.linalg.norm(n, axis=1) / 2
    cosine = (n * centre).sum(1) / (np.linalg.norm(n, axis=1) * np.linalg.norm(centre, axis=1))
    error = np.degrees(np.arccos(np.clip(cosine, -1, 1)))
    smallest = smallest_angles(v, faces)
    distance = np.abs(np.linalg.norm(v[np.unique(faces)], axis=1) - 20)
    print("sphere r 20, %s mm / %s mm, %s: %d faces; face normal error mean %.1f, 95th percentile %.1f deg; "
          "smallest angle %.1f, 5th percentile %.1f deg; vertex distance mean %.4f, max %.4f mm"
          % (grid["--pixel"], grid["--gap"], " ".join(flags) or "defaults", len(faces),
             *normal_error(error, area), smallest.min(), np.percentile(smallest, 5), distance.mean(), distance.max()))
    # The caps beyond the first and last contours hold the slab rule's volume (the end contour's
    # area times half a gap), not the sphere's: where the last contour lies near the pole, that
    # cap is taller than the sphere's, and its normals cannot be the sphere's.
    planes = [s["z"] for s in sphere_contours(gap=float(grid["--gap"]))["features"][0]["slices"]]
    z = centre[:, 2]
    for name, part in (("between the contours", (z >= planes[0]) & (z <= planes[-1])),
                       ("cap below z %g" % planes[0], z < planes[0]), ("cap above z %g" % planes[-1], z > planes[-1])):
        print("  %s: %.1f %% of the area; face normal error mean %.1f, 95th percentile %.1f deg"
              % (name, 100 * area[part].sum() / area.sum(), *normal_error(error[part], area[part])))


def normal_error(error, area):
    """The area-weighted mean and 95th percentile of the faces' normal errors."""
    order = np.argsort(error)
    p95 = error[order][np.searchsorted(np.cumsum(area[order]) / area.sum(), 0.95)]
    return (error * area).sum() / area.sum(), p95


if __name__ == "__main__":
    main()
