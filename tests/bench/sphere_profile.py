#!/usr/bin/env python3
"""Where the analytic sphere's shape error lies between its contour planes: the sphere of
sphere_shape.py (radius 20 mm, slices 3 mm apart) surfaced at P mm pixels with scansurf's
defaults plus any flags, its vertices' signed distance to the true sphere (mean and spread) by
their height above the contour plane below, in quarter millimetres, away from the caps. A mean
that dips between the planes and returns at them is a ripple the normals see.

  tests/bench/sphere_profile.py build/cli/scansurf [--pixel P] [FLAG...]   e.g. --no-keep-volume
"""
import json
import os
import subprocess
import sys
import tempfile

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from sphere_shape import sphere_contours  # noqa: E402
from wireframe import read_ply  # noqa: E402


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    scansurf, flags = sys.argv[1], sys.argv[2:]
    pixel = "1"
    if flags[:1] == ["--pixel"] and len(flags) > 1:
        pixel, flags = flags[1], flags[2:]
    with tempfile.TemporaryDirectory() as work:
        source = os.path.join(work, "sphere.json")
        with open(source, "w") as f:
            json.dump(sphere_contours(), f)
        subprocess.run([scansurf, source, "-o", os.path.join(work, "out"), "--voxel-size", pixel, "-q", *flags], check=True)
        v, _ = read_ply(os.path.join(work, "out", "ball.ply"))
    error = np.linalg.norm(v, axis=1) - 20
    z = v[:, 2]
    body = np.abs(z) < 12  # away from the caps
    height = (z + 17) % 3  # above the contour plane below (planes at -17, -14, ...)
    print("sphere r 20, %s mm pixels / 3 mm slices, %s: signed vertex distance to the sphere (mm)"
          % (pixel, " ".join(flags) or "defaults"))
    for lo in np.arange(0, 3, 0.25):
        m = body & (height >= lo - 1e-4) & (height < lo + 0.25 - 1e-4)
        if m.any():
            print("  %.2f-%.2f mm above a plane: %5d vertices, mean %+.4f, sd %.4f"
                  % (lo, lo + 0.25, m.sum(), error[m].mean(), error[m].std()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
