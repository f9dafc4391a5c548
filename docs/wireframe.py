#!/usr/bin/env python3
"""Close-up wireframe of a scansurf feature PLY (binary, float xyz, uchar+int faces), as PNG.

    docs/wireframe.py SURFACE.ply OUT.png CX CY CZ HALF [SIZE]

Looks along -y (anterior view, x to the right, z up) at the part of the surface within HALF
units of (CX, CZ) in x and z and in front (y <= CY + HALF, nearest faces only: back faces and
faces hidden behind nearer ones are skipped by a depth buffer). Pure Python (zlib, struct), so
that it runs where no imaging package is installed; used for the README's before/after picture
of remeshing (issue 11).
"""
import struct
import sys
import zlib


def read_ply(path):
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii", "replace").splitlines()
    nv = nf = 0
    for line in header:
        if line.startswith("element vertex"):
            nv = int(line.split()[2])
        if line.startswith("element face"):
            nf = int(line.split()[2])
    verts = [struct.unpack_from("<3f", data, end + 12 * i) for i in range(nv)]
    faces, at = [], end + 12 * nv
    for _ in range(nf):
        faces.append(struct.unpack_from("<3i", data, at + 1))
        at += 13
    return verts, faces


def main():
    path, out, cx, cy, cz, half = sys.argv[1], sys.argv[2], *map(float, sys.argv[3:7])
    size = int(sys.argv[7]) if len(sys.argv) > 7 else 480
    verts, faces = read_ply(path)
    scale = size / (2 * half)
    px = lambda v: ((v[0] - cx + half) * scale, (cz + half - v[2]) * scale)
    depth = [[float("inf")] * size for _ in range(size)]
    image = [[255] * size for _ in range(size)]
    shown = []
    for a, b, c in faces:
        p = [verts[a], verts[b], verts[c]]
        if any(abs(q[0] - cx) > half * 1.2 or abs(q[2] - cz) > half * 1.2 or q[1] > cy + half for q in p):
            continue
        (x0, y0), (x1, y1), (x2, y2) = px(p[0]), px(p[1]), px(p[2])
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if area >= 0:  # facing away (outward normal has y > 0 seen from the front)
            continue
        shown.append(p)
        # Depth: rasterize the triangle with its mean y (nearest wins).
        ymean = (p[0][1] + p[1][1] + p[2][1]) / 3
        lo_x, hi_x = max(0, int(min(x0, x1, x2))), min(size - 1, int(max(x0, x1, x2)) + 1)
        lo_y, hi_y = max(0, int(min(y0, y1, y2))), min(size - 1, int(max(y0, y1, y2)) + 1)
        for yy in range(lo_y, hi_y + 1):
            for xx in range(lo_x, hi_x + 1):
                w0 = (x1 - xx) * (y2 - yy) - (x2 - xx) * (y1 - yy)
                w1 = (x2 - xx) * (y0 - yy) - (x0 - xx) * (y2 - yy)
                w2 = (x0 - xx) * (y1 - yy) - (x1 - xx) * (y0 - yy)
                if (w0 <= 0 and w1 <= 0 and w2 <= 0) and ymean < depth[yy][xx]:
                    depth[yy][xx] = ymean
    for p in shown:
        ymean = (p[0][1] + p[1][1] + p[2][1]) / 3
        for i in range(3):
            (xa, ya), (xb, yb) = px(p[i]), px(p[(i + 1) % 3])
            steps = int(max(abs(xb - xa), abs(yb - ya))) + 1
            for s in range(steps + 1):
                x, y = int(xa + (xb - xa) * s / steps), int(ya + (yb - ya) * s / steps)
                if 0 <= x < size and 0 <= y < size and ymean <= depth[y][x] + 0.3:
                    image[y][x] = 0
    raw = b"".join(b"\x00" + bytes(row) for row in image)
    chunk = lambda kind, body: struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body))
    with open(out, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", size, size, 8, 0, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b""))


if __name__ == "__main__":
    main()
