#!/usr/bin/env python3
"""What an empty margin costs classification and assembly: a benchmark set (scansurf_bench
generate's JSON) surfaced as it is and with two 2 x 2 mm squares placed so that its grid gets
twice its extent in x and y (four times the columns, the same surface), at one pixel size,
runs interleaved; prints each run's grid, classification and assembly times.

  tests/bench/empty_margin.py SCANSURF SET.json [PIXEL_MM] [RUNS]   e.g. build/cli/scansurf build-bench/bench-work/pelvis.json 0.9695 3
"""
import json
import os
import subprocess
import sys
import tempfile


def with_margin(contours):
    points = [p for f in contours["features"] for s in f["slices"] for c in s["contours"] for p in c]
    x0, x1 = min(p[0] for p in points), max(p[0] for p in points)
    y0, y1 = min(p[1] for p in points), max(p[1] for p in points)
    zs = sorted({s["z"] for f in contours["features"] for s in f["slices"]})
    z = zs[len(zs) // 2]
    w, h = x1 - x0, y1 - y0

    def square(cx, cy):
        return [[cx - 1, cy - 1], [cx + 1, cy - 1], [cx + 1, cy + 1], [cx - 1, cy + 1]]
    out = dict(contours, features=list(contours["features"]))
    out["features"].append({"name": "margin a", "slices": [{"z": z, "contours": [square(x0 - w / 2, y0 - h / 2)]}]})
    out["features"].append({"name": "margin b", "slices": [{"z": z, "contours": [square(x1 + w / 2, y1 + h / 2)]}]})
    return out


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    scansurf, source = sys.argv[1], sys.argv[2]
    pixel = sys.argv[3] if len(sys.argv) > 3 else "1"
    runs = int(sys.argv[4]) if len(sys.argv) > 4 else 3
    with open(source) as f:
        contours = json.load(f)
    with tempfile.TemporaryDirectory() as work:
        wide = os.path.join(work, "margin.json")
        with open(wide, "w") as f:
            json.dump(with_margin(contours), f)
        for run in range(runs):
            for name, path in (("as it is", source), ("margin x2", wide)):
                report = os.path.join(work, "report.json")
                subprocess.run([scansurf, path, "-o", os.path.join(work, "out"), "-q", "--voxel-size", pixel,
                                "--report", report], check=True, stderr=subprocess.DEVNULL)
                with open(report) as f:
                    r = json.load(f)
                t = {x["stage"]: x["seconds"] for x in r["timings"]}
                print("run %d %-9s grid %s: classification %.3f s, assembly %.3f s, together %.3f s"
                      % (run + 1, name, "x".join(map(str, r["grid"]["size"])), t["classification"], t["assembly"],
                         t["classification"] + t["assembly"]))
    return 0


if __name__ == "__main__":
    sys.exit(main())
