#!/usr/bin/env python3
"""Volumes between the slices: each structure's surface volume against its contour volume
(the slab rule), from the CLI's own table, for shape sets written here, the bundled example
and (when ../shared is there) the MIM phantom on its CT grid. docs/method.md, "Between the
slices", shows the table this prints.

    tests/bench/between_slices.py BUILD/cli/scansurf [--label NAME -- EXTRA FLAGS ...]

Each column is one way to run the CLI: defaults, then --interpolate off, then any given.
"""
import json, math, os, subprocess, sys, tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))
MIM = os.path.join(REPO, "..", "shared", "data", "rtstruct", "rt-utils", "mim_phantom")


def circle(cx, cy, r, n=128):
    return [[cx + r * math.cos(2 * math.pi * i / n), cy + r * math.sin(2 * math.pi * i / n)] for i in range(n)]


def ellipse(cx, cy, a, b, turn=0.0, n=128):
    pts = []
    for i in range(n):
        t = 2 * math.pi * i / n
        x, y = a * math.cos(t), b * math.sin(t)
        pts.append([cx + x * math.cos(turn) - y * math.sin(turn), cy + x * math.sin(turn) + y * math.cos(turn)])
    return pts


def feature(name, slices):
    return {"name": name, "slices": [{"z": z, "contours": [c]} for z, c in slices]}


def small_structures(gap):
    """BODY on ten planes with structures on one, two and three of them (a one-plane disc
    mid-stack, a two-plane disc, a 24 x 3 mm scar, a three-plane disc, one on the first plane)."""
    f = [feature("BODY", [(gap * k, circle(0, 0, 40)) for k in range(10)])]
    f.append(feature("one plane", [(4 * gap, circle(-15, 0, 6))]))
    f.append(feature("two planes", [(gap * k, circle(15, 0, 5)) for k in (4, 5)]))
    f.append(feature("scar", [(gap * k, ellipse(0, 20, 12, 1.5)) for k in (4, 5)]))
    f.append(feature("three planes", [(gap * k, circle(0, -20, 7)) for k in (3, 4, 5)]))
    f.append(feature("first plane", [(0.0, circle(-20, -20, 5))]))
    return f


def changing_outlines():
    """Outlines that change between planes 5 mm apart."""
    return [feature("disc", [(z, circle(-30, -30, 10)) for z in (0, 5, 10)]),
            feature("growing disc", [(0, circle(30, 0, 5)), (5, circle(30, 0, 10)), (10, circle(30, 0, 6))]),
            feature("moving ellipse", [(0, ellipse(0, 30, 8, 4)), (5, ellipse(0, 35, 8, 4)), (10, ellipse(0, 30, 8, 4))]),
            feature("turning ellipse", [(0, ellipse(30, 30, 10, 3)), (5, ellipse(30, 30, 10, 3, math.pi / 2)),
                                        (10, ellipse(30, 30, 10, 3))])]


def volumes(cli, args):
    out = subprocess.run([cli] + args, capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(out.stderr)
    rows, on = {}, False
    for line in out.stdout.splitlines():
        if line.startswith("  feature"):
            on = True
            continue
        if on and line.startswith("  ") and not line.startswith("   "):
            cells = line[2:].split()
            # name (may hold spaces), label, layer, triangles, volume, contour, components, genus, closed
            idx = next(i for i, c in enumerate(cells) if c.isdigit())
            name = " ".join(cells[:idx])
            volume, contour = float(cells[idx + 3]), float(cells[idx + 4])
            rows[name] = 100 * (volume - contour) / contour
        elif on and not line.startswith("  "):
            on = False
    return rows


def main():
    cli = os.path.abspath(sys.argv[1])
    columns = [("defaults", []), ("--interpolate off", ["--interpolate", "off"])]
    if "--label" in sys.argv:
        i = sys.argv.index("--label")
        columns.append((sys.argv[i + 1], sys.argv[sys.argv.index("--") + 1:]))
    tmp = tempfile.mkdtemp()
    sets = []
    for gap in (2, 3):
        path = os.path.join(tmp, f"small-{gap}mm.json")
        json.dump({"version": 1, "units": "mm", "features": small_structures(gap)}, open(path, "w"))
        for grid, flags in (("1 mm pixels", ["--voxel-size", "1"]), ("default grid", [])):
            sets.append((f"{gap} mm planes, {grid}", [path] + flags))
    path = os.path.join(tmp, "changing.json")
    json.dump({"version": 1, "units": "mm", "features": changing_outlines()}, open(path, "w"))
    for grid, flags in (("1 mm pixels", ["--voxel-size", "1"]), ("0.5 mm", ["--voxel-size", "0.5"]), ("default grid", [])):
        sets.append((f"5 mm planes, {grid}", [path] + flags))
    sets.append(("bundled example, default grid", [os.path.join(REPO, "examples", "phantom.json")]))
    if os.path.isdir(MIM):
        sets.append(("MIM phantom on its CT grid", [os.path.join(MIM, "rt.dcm"), "--reference", MIM]))
        sets.append(("MIM phantom, 1 mm pixels", [os.path.join(MIM, "rt.dcm"), "--reference", MIM, "--voxel-size", "1"]))
    print("| set | structure | " + " | ".join(c for c, _ in columns) + " |")
    print("|---|---|" + "---|" * len(columns))
    for title, args in sets:
        results = [volumes(cli, args + ["-o", os.path.join(tmp, "out")] + extra) for _, extra in columns]
        for name in results[0]:
            print(f"| {title} | {name} | " + " | ".join(f"{r[name]:+.1f} %" for r in results) + " |")


if __name__ == "__main__":
    main()
