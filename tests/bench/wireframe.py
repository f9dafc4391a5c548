#!/usr/bin/env python3
"""Draws a close-up wireframe of one surface (a scansurf PLY) as SVG: the front-facing triangles
inside a square window, seen along +x, -x, +y or -y, painted back to front, contour planes
(horizontal lines at the slices' z) in blue. For docs/method.md's before/after figures:

  tests/bench/wireframe.py SURFACE.ply OUT.svg --axis=-x --centre Y Z --size MM [--planes input.json]
"""
import argparse
import json

import numpy as np


def read_ply(path):
    with open(path, "rb") as f:
        header = []
        while True:
            line = f.readline().decode("ascii").strip()
            header.append(line)
            if line == "end_header":
                break
        counts, face_props = {}, []
        element = None
        for line in header:
            words = line.split()
            if words[0] == "element":
                element = words[1]
                counts[element] = int(words[2])
            elif words[0] == "property" and element == "face" and words[1] != "list":
                face_props.append(words[1])
        vertices = np.frombuffer(f.read(12 * counts["vertex"]), dtype="<f4").reshape(-1, 3).astype(np.float64)
        extra = sum({"ushort": 2, "uint16": 2, "int": 4, "uint": 4, "float": 4}[p] for p in face_props)
        record = np.dtype([("n", "u1"), ("v", "<i4", 3)] + ([("extra", "u1", extra)] if extra else []))
        faces = np.frombuffer(f.read(record.itemsize * counts["face"]), dtype=record)
        assert (faces["n"] == 3).all(), "triangles only"
        return vertices, faces["v"].astype(np.int64)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("ply")
    ap.add_argument("svg")
    ap.add_argument("--axis", default="+x", choices=["+x", "-x", "+y", "-y"], help="direction the viewer looks along")
    ap.add_argument("--centre", nargs=2, type=float, required=True, help="window centre: the other in-plane axis, then z")
    ap.add_argument("--size", type=float, default=8.0, help="window side, input units")
    ap.add_argument("--planes", help="the contour set (JSON): draws its slices' z")
    ap.add_argument("--title", default="")
    a = ap.parse_args()

    v, f = read_ply(a.ply)
    look = {"+x": (0, 1.0), "-x": (0, -1.0), "+y": (1, 1.0), "-y": (1, -1.0)}[a.axis]
    depth_axis, sign = look
    u_axis = 1 if depth_axis == 0 else 0
    p = v[f]  # triangles x corners x xyz
    normal = np.cross(p[:, 1] - p[:, 0], p[:, 2] - p[:, 0])
    u, z = p[:, :, u_axis], p[:, :, 2]
    half = a.size / 2
    inside = ((u.max(1) > a.centre[0] - half) & (u.min(1) < a.centre[0] + half) & (z.max(1) > a.centre[1] - half)
              & (z.min(1) < a.centre[1] + half))
    front = sign * normal[:, depth_axis] < 0  # faces turned toward the viewer
    keep = np.nonzero(inside & front)[0]
    order = keep[np.argsort(sign * p[keep, :, depth_axis].mean(1))[::-1]]  # farthest first

    px = 600.0
    scale = px / a.size
    flip_u = -1.0 if (depth_axis == 0) == (sign > 0) else 1.0  # the viewer's right-hand side
    def to_svg(uu, zz):
        return (px / 2 + flip_u * (uu - a.centre[0]) * scale, px / 2 - (zz - a.centre[1]) * scale)

    lines = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{px:.0f}" height="{px + 30:.0f}" viewBox="0 0 {px:.0f} {px + 30:.0f}">',
             '<rect width="100%" height="100%" fill="white"/>', f'<clipPath id="w"><rect width="{px:.0f}" height="{px:.0f}"/></clipPath>',
             '<g clip-path="url(#w)" stroke="#222" stroke-width="0.6" stroke-linejoin="round" fill="#f4f1ea">']
    for t in order:
        pts = " ".join("%.1f,%.1f" % to_svg(u[t, c], z[t, c]) for c in range(3))
        lines.append(f'<polygon points="{pts}"/>')
    lines.append("</g>")
    if a.planes:
        zs = sorted({s["z"] for feat in json.load(open(a.planes))["features"] for s in feat["slices"]})
        for zz in zs:
            if abs(zz - a.centre[1]) < half:
                y = to_svg(0, zz)[1]
                lines.append(f'<line x1="0" x2="{px:.0f}" y1="{y:.1f}" y2="{y:.1f}" stroke="#2a6fdb" stroke-width="1" stroke-dasharray="4 4"/>')
    caption = f"{a.title} {len(keep)} triangles in {a.size:g} x {a.size:g} mm; dashed: contour planes".strip()
    lines.append(f'<text x="8" y="{px + 20:.0f}" font-family="sans-serif" font-size="14">{caption}</text>')
    lines.append("</svg>")
    with open(a.svg, "w") as out:
        out.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
