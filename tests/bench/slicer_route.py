#!/usr/bin/env python3
"""The route 3D Slicer users take today, timed on the same input and grid as scansurf:
plastimatch rasterizes the structure set into a label volume (as SlicerRT does), then per
label VTK's vtkDiscreteFlyingEdges3D and vtkWindowedSincPolyDataFilter with Slicer's
default closed-surface parameters (20 iterations, smoothing factor 0.5 -> pass band 10^-2,
non-manifold smoothing on, coordinates normalized), plus normals as Slicer computes them.

usage: slicer_route.py INPUT.json NX NY NZ ORIGIN_X ORIGIN_Y ORIGIN_Z SPACING_XY SPACING_Z WORKDIR
Prints one JSON object: stage times, peak memory, triangle count; with SLICER_ROUTE_ANGLES=1 in
the environment, also the triangles' smallest angles (measured after the timing, untimed)."""
import json
import os
import resource
import subprocess
import sys
import time


def write_cxt(contours, path, origin, dims, spacing):
    """plastimatch's CXT text structure set (documented in plastimatch's cxt_file_format)."""
    with open(path, "w") as out:
        out.write("SERIES_CT_UID Unknown\n")
        out.write("OFFSET %g %g %g\n" % origin)
        out.write("DIMENSION %d %d %d\n" % dims)
        out.write("SPACING %g %g %g\n" % spacing)
        out.write("ROI_NAMES\n")
        for i, f in enumerate(contours["features"], start=1):
            r, g, b = f.get("color", [255, 0, 0])
            out.write("%d|%d\\%d\\%d|%s\n" % (i, r, g, b, f["name"]))
        out.write("END_OF_ROI_NAMES\n")
        for i, f in enumerate(contours["features"], start=1):
            for s in f["slices"]:
                z = s["z"]
                for c in s["contours"]:
                    pts = "\\".join("%g\\%g\\%g" % (p[0], p[1], z) for p in c)
                    out.write("%d||%d|||%s\n" % (i, len(c), pts))


def angle_figures(surfaces):
    """Smallest angle of every triangle, degrees: the least, the 5th percentile, the share under 5."""
    import numpy as np
    from vtk.util.numpy_support import vtk_to_numpy
    from mesh_quality import smallest_angles  # beside this script
    smallest = []
    for poly in surfaces:
        if poly.GetNumberOfPolys() == 0:
            continue
        points = vtk_to_numpy(poly.GetPoints().GetData()).astype(np.float64)
        cells = vtk_to_numpy(poly.GetPolys().GetData()).reshape(-1, 4)[:, 1:]
        smallest.append(smallest_angles(points, cells))
    m = np.concatenate(smallest)
    return {"min_angle": float(m.min()), "p5_angle": float(np.percentile(m, 5)), "under_5": float((m < 5).mean())}


def main():
    (inp, nx, ny, nz, ox, oy, oz, sxy, sz, work) = sys.argv[1:11]
    nx, ny, nz = int(nx), int(ny), int(nz)
    ox, oy, oz, sxy, sz = map(float, (ox, oy, oz, sxy, sz))
    os.makedirs(work, exist_ok=True)
    result = {}

    t = time.perf_counter()
    with open(inp) as f:
        contours = json.load(f)
    cxt = os.path.join(work, "structures.cxt")
    write_cxt(contours, cxt, (ox, oy, oz), (nx, ny, nz), (sxy, sxy, sz))
    result["convert_input"] = time.perf_counter() - t  # format translation, not counted

    labelmap = os.path.join(work, "labelmap.mha")
    t = time.perf_counter()
    subprocess.run(["plastimatch", "convert", "--input", cxt, "--output-labelmap", labelmap,
                    "--origin", "%g %g %g" % (ox, oy, oz), "--spacing", "%g %g %g" % (sxy, sxy, sz),
                    "--dim", "%d %d %d" % (nx, ny, nz)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    result["rasterize"] = time.perf_counter() - t

    import vtk  # noqa: E402  (imported late so its start-up is not timed as rasterization)
    t = time.perf_counter()
    reader = vtk.vtkMetaImageReader()
    reader.SetFileName(labelmap)
    reader.Update()
    image = reader.GetOutput()
    result["read_labelmap"] = time.perf_counter() - t
    # Slicer keeps each segment's labelmap cropped to the segment's extent; crop likewise to
    # each structure's bounding box (from its contours, one voxel of margin).
    def extent(feature):
        xs = [p[0] for s in feature["slices"] for c in s["contours"] for p in c]
        ys = [p[1] for s in feature["slices"] for c in s["contours"] for p in c]
        zs = [s["z"] for s in feature["slices"]]
        def index(v, o, d, n, up):
            i = (v - o) / d
            i = int(i) + 1 if up else int(i) - 1
            return max(0, min(n - 1, i + (1 if up else -1)))
        return (index(min(xs), ox, sxy, nx, False), index(max(xs), ox, sxy, nx, True),
                index(min(ys), oy, sxy, ny, False), index(max(ys), oy, sxy, ny, True),
                index(min(zs), oz, sz, nz, False), index(max(zs), oz, sz, nz, True))

    def surface(label, feature):
        voi = vtk.vtkExtractVOI()
        voi.SetInputData(image)
        voi.SetVOI(*extent(feature))
        fe = vtk.vtkDiscreteFlyingEdges3D()
        fe.SetInputConnection(voi.GetOutputPort())
        fe.SetValue(0, label)
        fe.ComputeGradientsOff()
        fe.ComputeNormalsOff()
        smoother = vtk.vtkWindowedSincPolyDataFilter()
        smoother.SetInputConnection(fe.GetOutputPort())
        smoother.SetNumberOfIterations(20)
        smoother.SetPassBand(10 ** (-4.0 * 0.5))
        smoother.BoundarySmoothingOff()
        smoother.FeatureEdgeSmoothingOff()
        smoother.NonManifoldSmoothingOn()
        smoother.NormalizeCoordinatesOn()
        normals = vtk.vtkPolyDataNormals()
        normals.SetInputConnection(smoother.GetOutputPort())
        normals.ConsistencyOn()
        normals.SplittingOff()
        normals.Update()
        return normals.GetOutput()

    t = time.perf_counter()
    triangles = 0
    for label, feature in enumerate(contours["features"], start=1):
        triangles += surface(label, feature).GetNumberOfPolys()
    result["surfaces"] = time.perf_counter() - t
    result["total"] = result["rasterize"] + result["read_labelmap"] + result["surfaces"]
    result["triangles"] = triangles
    self_kib = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    child_kib = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
    result["peak_rss_mib"] = max(self_kib, child_kib) / 1024.0
    if os.environ.get("SLICER_ROUTE_ANGLES"):  # untimed: the surfaces made again, their angles
        result.update(angle_figures([surface(label, f) for label, f in enumerate(contours["features"], start=1)]))
    print(json.dumps(result))


if __name__ == "__main__":
    main()
