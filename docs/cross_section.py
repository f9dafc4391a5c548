#!/usr/bin/env python3
"""Close-up cross-section of feature surfaces and their drawn contours on one plane, as PNG.

    docs/cross_section.py CONTOURS.json Z X0 X1 Y0 Y1 OUT.png NAME=SURFACE.ply...

Draws, in the window [X0, X1] x [Y0, Y1] of the plane z = Z, each named feature's drawn
contours on the contour plane nearest Z (thin, dark) and the cross-section of its surface at Z
(thick, the feature's colour: first orange, then blue, green): where two surfaces cross, their
lines cross. Pure Python (json, struct, zlib), so that it runs where no imaging package is
installed (the PLY reader is wireframe.py's); used for docs/overlaps.md's before/after picture of an incidental overlap.
"""
import json
import os
import struct
import sys
import zlib

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from wireframe import read_ply  # noqa: E402  (the same PLY reader as the wireframe picture)

COLOURS = [(230, 150, 20), (40, 120, 220), (40, 170, 80)]
SCALE = 40  # pixels per unit


def section(verts, faces, z):
    """Segments where the triangles cross the plane z."""
    out = []
    for f in faces:
        pts = [verts[i] for i in f]
        cut = []
        for a, b in ((pts[0], pts[1]), (pts[1], pts[2]), (pts[2], pts[0])):
            if (a[2] - z) * (b[2] - z) < 0:
                t = (z - a[2]) / (b[2] - a[2])
                cut.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
        if len(cut) == 2:
            out.append(cut)
    return out


class Canvas:
    def __init__(self, x0, x1, y0, y1):
        self.x0, self.y1 = x0, y1
        self.w, self.h = int((x1 - x0) * SCALE), int((y1 - y0) * SCALE)
        self.px = bytearray(b"\xff" * (3 * self.w * self.h))

    def line(self, a, b, colour, width):
        ax, ay = (a[0] - self.x0) * SCALE, (self.y1 - a[1]) * SCALE
        bx, by = (b[0] - self.x0) * SCALE, (self.y1 - b[1]) * SCALE
        steps = int(max(abs(bx - ax), abs(by - ay))) + 1
        r = width // 2
        for s in range(steps + 1):
            cx, cy = int(ax + (bx - ax) * s / steps), int(ay + (by - ay) * s / steps)
            for dy in range(-r, r + 1):
                for dx in range(-r, r + 1):
                    x, y = cx + dx, cy + dy
                    if 0 <= x < self.w and 0 <= y < self.h:
                        self.px[3 * (y * self.w + x):3 * (y * self.w + x) + 3] = bytes(colour)

    def png(self, path):
        rows = b"".join(b"\x00" + bytes(self.px[3 * y * self.w:3 * (y + 1) * self.w]) for y in range(self.h))
        def chunk(kind, data):
            return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)
        with open(path, "wb") as f:
            f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", self.w, self.h, 8, 2, 0, 0, 0)) +
                    chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


def main():
    contours, z = json.load(open(sys.argv[1])), float(sys.argv[2])
    x0, x1, y0, y1 = map(float, sys.argv[3:7])
    canvas = Canvas(x0, x1, y0, y1)
    named = [arg.split("=", 1) for arg in sys.argv[8:]]
    for i, (name, ply) in enumerate(named):
        feature = next(f for f in contours["features"] if f["name"] == name)
        plane = min(feature["slices"], key=lambda s: abs(s["z"] - z))
        for c in plane["contours"]:
            pts = c["points"] if isinstance(c, dict) else c
            for a, b in zip(pts, pts[1:] + pts[:1]):
                canvas.line(a, b, (60, 60, 60), 1)
        verts, faces = read_ply(ply)
        for a, b in section(verts, faces, z):
            canvas.line(a, b, COLOURS[i % len(COLOURS)], 3)
    canvas.png(sys.argv[7])


if __name__ == "__main__":
    main()
