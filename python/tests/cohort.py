"""Generated structure sets for the batch tests and the batch benchmark: each a body holding two
organs of seeded, distinct sizes and places, drawn as polygons on 2.5 mm slices."""

import math
import os

import numpy as np


def ellipse(cx, cy, rx, ry, n=48):
    t = np.linspace(0, 2 * math.pi, n, endpoint=False)
    return np.stack([cx + rx * np.cos(t), cy + ry * np.sin(t)], axis=1)


def ellipsoid_slices(cx, cy, cz, rx, ry, rz, spacing):
    slices = {}
    k0, k1 = math.ceil((cz - rz) / spacing), math.floor((cz + rz) / spacing)
    for k in range(k0, k1 + 1):
        z = k * spacing
        s = 1 - ((z - cz) / rz) ** 2
        if s > 0.01:
            slices[z] = [ellipse(cx, cy, rx * math.sqrt(s), ry * math.sqrt(s))]
    return slices


def structure_set(seed, spacing=2.5):
    """{name: {z: [polygon]}} of one generated patient."""
    rng = np.random.default_rng(seed)
    body = ellipsoid_slices(0, 0, 0, 60 + 10 * rng.random(), 45 + 8 * rng.random(), 40, spacing)
    a = ellipsoid_slices(-20 + 5 * rng.random(), 0, 0, 10 + 6 * rng.random(), 9 + 5 * rng.random(), 14, spacing)
    b = ellipsoid_slices(22 + 5 * rng.random(), 5, 4, 8 + 5 * rng.random(), 8 + 4 * rng.random(), 12, spacing)
    return {"Body": body, "Organ_A": a, "Organ_B": b}


def write_cohort(folder, count, scansurf):
    os.makedirs(folder, exist_ok=True)
    paths = []
    for i in range(count):
        path = os.path.join(folder, "patient%02d.json" % i)
        if not os.path.exists(path):
            scansurf.contours(structure_set(i), source=path).write_json(path)
        paths.append(path)
    return paths
