"""The Python package: reading, contours from Python, build, results as numpy, writing."""

import filecmp
import gc
import json
import os
import subprocess
import threading

import numpy as np
import pytest

import scansurf
from conftest import EXAMPLE, ROOT, sphere


def test_devices_lists_the_default_device():
    devices = scansurf.devices()
    assert devices and all({"index", "name", "type", "usable", "default"} <= set(d) for d in devices)
    assert sum(d["default"] for d in devices) == 1


def test_read_gives_names_units_and_source(phantom):
    assert phantom.names == ["BODY", "prostate", "rectum", "target", "vessel", "vertebra"]
    assert phantom.units == "mm" and len(phantom) == 6
    assert phantom.input == str(EXAMPLE)


def test_surfaces_are_numpy_arrays_of_the_right_shapes(phantom_result):
    body = phantom_result.surfaces["BODY"]
    assert body.vertices.dtype == np.float32 and body.vertices.ndim == 2 and body.vertices.shape[1] == 3
    assert body.faces.dtype == np.uint32 and body.faces.shape[1] == 3
    assert body.faces.max() == len(body.vertices) - 1  # compact: every vertex used
    assert body.closed and body.manifold and body.oriented and body.genus == 0 and body.components == 1
    assert body.triangles == len(body.faces)
    assert abs(body.volume - body.contour_volume) < 0.01 * body.contour_volume
    for s in phantom_result.surfaces.values():
        assert s.volume > 0 and len(s.color) == 3


def test_the_shared_mesh_carries_two_labels_per_face(phantom_result):
    vertices, faces, labels = phantom_result.mesh
    assert vertices.dtype == np.float32 and faces.dtype == np.uint32 and labels.dtype == np.uint16
    assert faces.shape == (len(labels), 3) and labels.shape[1] == 2
    assert (labels[:, 0] < labels[:, 1]).all()


def test_views_are_zero_copy_read_only_and_outlive_the_result(phantom):
    result = scansurf.build(phantom)
    first = result.surfaces["rectum"].vertices
    assert np.shares_memory(first, result.surfaces["rectum"].vertices)  # no copy on a second access
    mesh_vertices = result.mesh[0]
    assert np.shares_memory(mesh_vertices, result.mesh[0])
    assert not first.flags.writeable and not mesh_vertices.flags.writeable
    with pytest.raises(ValueError):
        first[0, 0] = 1
    expected, expected_mesh = first.copy(), mesh_vertices.copy()
    del result
    gc.collect()
    np.testing.assert_array_equal(first, expected)  # the view keeps the result alive
    np.testing.assert_array_equal(mesh_vertices, expected_mesh)


def test_label_volume_has_its_geometry(phantom_result):
    lv = phantom_result.label_volume
    grid = phantom_result.grid
    assert lv.dtype == np.uint16 and lv.ndim == 3
    assert lv.shape[1:] == (grid["ny"], grid["nx"])
    assert lv.spacing[0] == pytest.approx(grid["spacing_x"]) and lv.origin[0] == pytest.approx(grid["origin_x"])
    np.testing.assert_allclose(lv.directions, np.eye(3))
    assert set(np.unique(lv)) == set(range(7))  # background and the six labels
    # The labelled volume of a label that nothing covers equals the report's (rectum: label 3).
    voxel = float(np.prod(lv.spacing))
    rectum = phantom_result.surfaces["rectum"]
    assert (lv == 3).sum() * voxel == pytest.approx(rectum.voxel_volume, rel=0.02)
    point = lv.index_to_point([[0, 0, 0]])[0]
    np.testing.assert_allclose(point, lv.origin)


def test_report_is_a_dict_with_the_parameters_used(phantom_result):
    report = phantom_result.report
    assert report["format"] == "scansurf-report"
    assert report["parameters"]["smoothing"] is True and report["parameters"]["interpolation"] == "auto"
    assert [f["name"] for f in report["features"]] == list(phantom_result.surfaces)


def test_options_as_keywords(phantom):
    raw = scansurf.build(phantom, smooth=False, interpolate="off", voxel_size=2.0)
    assert raw.report["parameters"]["smoothing"] is False
    assert raw.report["parameters"]["voxel_size"] == 2.0
    assert raw.grid["spacing_x"] == 2.0


def test_simplify_merges_triangles_and_reports_it(phantom):
    plain = scansurf.build(phantom, voxel_size=2.0, simplify=False)
    default = scansurf.build(phantom, voxel_size=2.0)
    fewer = scansurf.build(phantom, voxel_size=2.0, simplify_min_angle=10)
    figures = fewer.report["simplification"]
    assert "simplification" not in plain.report and plain.report["parameters"]["simplification"] is False
    assert default.report["parameters"]["simplification"] is True, "on by default, as on the command line"
    assert default.report["multilabel_mesh"]["triangles"] < plain.report["multilabel_mesh"]["triangles"]
    assert fewer.report["parameters"]["simplification"] is True and fewer.report["parameters"]["simplify_min_angle"] == 10
    assert figures["triangles_after"] < 0.8 * figures["triangles_before"]
    for name, surface in fewer.surfaces.items():
        assert surface.closed and surface.volume == pytest.approx(plain.surfaces[name].volume, rel=0.01), name
    with pytest.raises(scansurf.InvalidArgument, match="option simplify_tolerance"):
        scansurf.build(phantom, voxel_size=2.0, simplify=True, simplify_tolerance=0.9)


def test_snap_merges_vertices_crowding_voxel_centres(phantom):
    snapped = scansurf.build(phantom, voxel_size=2.0)
    plain = scansurf.build(phantom, voxel_size=2.0, snap=0)
    assert snapped.report["parameters"]["snap"] == 0.05 and plain.report["parameters"]["snap"] == 0
    assert snapped.report["multilabel_mesh"]["triangles"] < plain.report["multilabel_mesh"]["triangles"]
    assert snapped.report["triangle_shape"]["points"] > 0 and plain.report["triangle_shape"]["points"] == 0
    assert snapped.report["triangle_shape"]["cube_fans"] > 0 and plain.report["triangle_shape"]["cube_fans"] > 0
    for name, surface in snapped.surfaces.items():
        assert surface.closed and surface.volume == pytest.approx(plain.surfaces[name].volume, rel=0.001), name
    with pytest.raises(scansurf.InvalidArgument, match="option snap"):
        scansurf.build(phantom, voxel_size=2.0, snap=0.5)


def test_a_build_with_no_options_is_the_command_line_tools(tmp_path, phantom_result, cli):
    py = tmp_path / "py"
    written = phantom_result.write(py, formats=["ply", "glb"])
    assert str(py / "report.json") == written[-1]  # the report is moved into place last
    subprocess.run([cli, str(EXAMPLE), "-o", str(tmp_path / "cli"), "-q", "--format", "ply,glb"], check=True)
    for name in ["BODY.ply", "rectum.ply", "multilabel.ply", "phantom.glb"]:
        assert filecmp.cmp(py / name, tmp_path / "cli" / name, shallow=False), name
    report = json.loads((py / "report.json").read_text())
    assert report["outputs"][-1] == str(py / "report.json")


def test_write_label_volume_and_vtk_formats(tmp_path, phantom_result):
    written = phantom_result.write(tmp_path, formats=["vtp", "seg.vtm"], label_volume="labels.nii.gz", report=None)
    names = {os.path.basename(p) for p in written}
    assert {"BODY.vtp", "phantom.seg.vtm", "labels.nii.gz", "labels.label.txt"} <= names
    assert "report.json" not in names


def test_contours_from_python_lists_are_validated():
    cs = scansurf.contours({"ball": sphere(), "hole": {0.0: [[(-1, -1), (1, -1), (1, 1), (-1, 1)]]}}, source="mine")
    assert cs.names == ["ball", "hole"] and cs.source == "mine"
    result = scansurf.build(cs, voxel_size=0.5)
    ball = result.surfaces["ball"]
    assert ball.closed and abs(ball.volume - ball.contour_volume) < 0.05 * ball.contour_volume
    with pytest.raises(scansurf.InvalidInput, match=r"feature \"bad\".*contour"):
        scansurf.contours({"bad": {0.0: [[(0, 0), (1, 0)]]}})
    with pytest.raises(scansurf.InvalidArgument, match=r"\(N, 2\)"):
        scansurf.contours({"bad": {0.0: [[1, 2, 3]]}})
    listed = scansurf.contours([{"name": "ball", "color": (255, 0, 0), "slices": list(sphere().items())}])
    assert scansurf.build(listed, voxel_size=1.0).surfaces["ball"].color == (255, 0, 0)


def test_contour_set_round_trips_through_json(tmp_path):
    cs = scansurf.contours({"ball": sphere()})
    cs.write_json(tmp_path / "ball.json")
    again = scansurf.read(tmp_path / "ball.json")
    assert again.names == ["ball"]
    assert [z for z, _ in again._slices(0)] == [z for z, _ in cs._slices(0)]


def test_each_error_is_its_class(tmp_path, phantom):
    with pytest.raises(scansurf.IoError):
        scansurf.read(tmp_path / "missing.json")
    (tmp_path / "bad.json").write_text("{ not json")
    with pytest.raises(scansurf.InvalidInput, match="bad.json"):
        scansurf.read(tmp_path / "bad.json")
    with pytest.raises(scansurf.InvalidArgument, match="smooth_strength"):
        scansurf.build(phantom, smooth_strength=5.0)
    with pytest.raises(scansurf.InvalidArgument, match="unknown option 'voxelsize'"):
        scansurf.build(phantom, voxelsize=1.0)
    with pytest.raises(scansurf.InvalidArgument, match="expected a number"):
        scansurf.build(phantom, voxel_size="fine")
    with pytest.raises(scansurf.ResourceLimit):
        scansurf.build(phantom, max_memory=1 << 20)
    with pytest.raises(scansurf.NoDevice, match="no-such-device"):
        scansurf.Engine("no-such-device")
    with pytest.raises(scansurf.InvalidArgument):
        scansurf.read(EXAMPLE, rois=["Heart"])  # ROI selection on a JSON file
    assert issubclass(scansurf.InvalidInput, ValueError) and issubclass(scansurf.IoError, OSError)
    assert issubclass(scansurf.OutOfMemory, MemoryError) and issubclass(scansurf.VulkanError, scansurf.Error)
    assert scansurf.InternalError.exit_code == 7 and scansurf.ResourceLimit.exit_code == 9
    assert scansurf.DefectiveSurface.exit_code == 10 and issubclass(scansurf.DefectiveSurface, RuntimeError)


def test_a_scene_name_never_leads_out_of_the_folder(tmp_path, phantom_result):
    out = tmp_path / "a" / "b"
    for name in ("../../x", "..", "sub/x", "x\\y", "x\0y", ""):
        with pytest.raises(scansurf.InvalidArgument, match="scene_name"):
            phantom_result.write(out, formats=("glb",), scene_name=name, report=None)
    assert not (tmp_path / "x.glb").exists() and not out.exists()
    assert phantom_result.write(out, formats=("glb",), scene_name="plan", report=None)


def test_the_gil_is_released_while_building(phantom):
    engine = scansurf.Engine()  # an engine of its own: builds on one engine are serialized
    done = threading.Event()
    ticks = 0

    def work():
        scansurf.build(phantom, engine=engine)
        done.set()

    thread = threading.Thread(target=work)
    thread.start()
    while not done.is_set():
        ticks += 1
    thread.join()
    assert ticks > 10000  # the main thread ran all along


def test_interop_meshio(phantom_result):
    meshio = pytest.importorskip("meshio", reason="meshio is not installed (Debian: python3-meshio)")
    mesh = phantom_result.surfaces["rectum"].to_meshio()
    assert isinstance(mesh, meshio.Mesh) and mesh.cells[0].data.shape == phantom_result.surfaces["rectum"].faces.shape


def test_interop_vtk(phantom_result):
    pytest.importorskip("vtkmodules", reason="VTK's Python bindings are not installed (Debian: python3-vtk9)")
    rectum = phantom_result.surfaces["rectum"]
    poly = rectum.to_vtk()
    assert poly.GetNumberOfPoints() == len(rectum.vertices) and poly.GetNumberOfPolys() == len(rectum.faces)
    assert poly.GetFieldData().GetAbstractArray("name").GetValue(0) == "rectum"


def test_a_device_by_index_and_no_bool_for_a_number(phantom):
    index = [d["index"] for d in scansurf.devices() if d["default"]][0]
    assert scansurf.engine(index) is scansurf.engine(str(index))  # an int names the device as its text does
    assert scansurf.build(phantom, device=index, voxel_size=2.0).surfaces["BODY"].closed
    with pytest.raises(scansurf.InvalidArgument, match="interpolate: expected .* got bool"):
        scansurf.build(phantom, interpolate=True)
    with pytest.raises(scansurf.InvalidArgument, match="smooth_iterations"):
        scansurf.build(phantom, smooth_iterations=True)


@pytest.mark.parametrize("options, option", [
    (dict(smooth=False, snap=0.9), "snap"),
    (dict(smooth=False, min_angle=-5), "min_angle"),
    (dict(smooth=False, smooth_iterations=0), "smooth_iterations"),
    (dict(smooth_iterations=10_000_000), "smooth_iterations"),
    (dict(threads=100_000), "threads"),
    (dict(interpolate=0), "interpolate"),
    (dict(overlap_tolerance=0), "overlap_tolerance"),
    (dict(overlap_tolerance=(0, 2)), "overlap_tolerance"),
])
def test_options_are_checked_against_the_command_lines_ranges_whatever_is_on(phantom, options, option):
    with pytest.raises(scansurf.InvalidArgument, match="option " + option):
        scansurf.build(phantom, voxel_size=2.0, **options)


def test_volume_unit_gives_the_reports_volumes_in_it():
    cs = scansurf.contours({"ball": sphere()}, units="mm")
    mm = scansurf.build(cs, voxel_size=1.0)
    cc = scansurf.build(cs, voxel_size=1.0, volume_unit="cc")
    assert mm.report["volume_unit"] == "mm^3" and cc.report["volume_unit"] == "cm^3"
    a, b = mm.report["features"][0], cc.report["features"][0]
    assert b["surface_volume"] == pytest.approx(a["surface_volume"] / 1000, rel=1e-12)
    assert b["contour_volume"] == pytest.approx(a["contour_volume"] / 1000, rel=1e-12)
    assert cc.surfaces["ball"].volume == pytest.approx(mm.surfaces["ball"].volume)  # the surface's own unit
    with pytest.raises(scansurf.InvalidArgument, match="volume_unit"):
        scansurf.build(cs, volume_unit="litres")
    with pytest.raises(scansurf.InvalidArgument, match="'px'"):
        scansurf.build(scansurf.contours({"ball": sphere()}, units="px"), volume_unit="cm3")


def test_a_segment_surfaced_alone_is_the_one_surfaced_with_all():
    seg = ROOT.parent / "shared" / "data" / "slicer" / "EclipseEnt_Structures.seg.vtm"
    if not seg.exists():
        pytest.skip("the shared Slicer segmentation is absent (%s)" % seg)
    everything = scansurf.build(scansurf.read(seg))
    alone = scansurf.build(scansurf.read(seg, rois=["Optic Nerve*"]))
    assert sorted(alone.surfaces) == ["Optic Nerve - Rt", "Optic Nerve-Lt"]
    voxels = {f["name"]: f["labelled_voxels"] for f in everything.report["features"]}
    for f in alone.report["features"]:  # the same grid: the same voxels
        assert f["labelled_voxels"] == voxels[f["name"]], f["name"]
    # Among the others, a nerve gives up the voxels of an incidental overlap (split medially,
    # docs/overlaps.md: the right nerve's 7.4 mm3 with BRAIN and optBRAIN, 0.32 % of it), as the
    # report says; nothing else changes.
    given_up = {name: 0.0 for name in alone.surfaces}
    for pair in everything.report["overlaps"]["partial"]:
        for side in "ab":
            if pair[side] in given_up:
                given_up[pair[side]] += pair["given_up"][side]
    assert given_up["Optic Nerve - Rt"] > 0.003 * alone.surfaces["Optic Nerve - Rt"].contour_volume
    for name, s in alone.surfaces.items():
        whole = everything.surfaces[name]
        assert s.volume == pytest.approx(s.contour_volume, rel=1e-3), name
        assert whole.volume == pytest.approx(s.volume - given_up[name], rel=1e-3), name
        assert (s.components, s.genus) == (whole.components, whole.genus), name


@pytest.mark.parametrize("inside", [10.0, 5.0])
def test_a_thin_scar_across_the_bodys_edge_keeps_its_volume(inside):
    def ellipse(rx, ry, n=96):
        t = np.linspace(0, 2 * np.pi, n, endpoint=False)
        return np.column_stack([rx * np.cos(t), ry * np.sin(t)])
    x0 = 150.0 - inside  # the BODY's edge at x = 150; the scar 13 x 3 mm on two 3 mm slices
    scar = np.array([[x0, -12], [x0 + 13, -12], [x0 + 13, -9], [x0, -9]], float)
    cs = scansurf.contours({"BODY": {z: [ellipse(150, 100)] for z in np.arange(-30, 30.1, 3.0)},
                            "scar": {0.0: [scar], 3.0: [scar]}})
    for options in ({}, {"voxel_size": 1.0}):  # the default grid (1.2 mm pixels) and a finer one
        s = scansurf.build(cs, **options).surfaces["scar"]
        assert s.volume == pytest.approx(234.0, rel=1e-2) and s.contour_volume == pytest.approx(234.0)
        assert (s.components, s.genus, s.closed) == (1, 0, True)


def test_an_roi_surfaced_alone_is_the_one_surfaced_with_all():
    plan = ROOT.parent / "shared" / "data" / "rtstruct" / "slicerrt-prostate"
    files = sorted(plan.glob("RS*.dcm")) if plan.exists() else []
    if not files:
        pytest.skip("the shared prostate plan is absent (%s)" % plan)
    everything = scansurf.build(scansurf.read(files[0]))
    whole = {f["name"]: f for f in everything.report["features"]}
    for roi in ("Rectum", "PTV", "Bladder"):
        alone = scansurf.build(scansurf.read(files[0], rois=[roi])).report["features"]
        assert [f["name"] for f in alone] == [roi]
        f, w = alone[0], whole[roi]
        assert f["labelled_voxels"] == w["labelled_voxels"], roi  # the grid follows the whole file
        assert f["surface_volume"] == pytest.approx(w["surface_volume"], rel=1e-3), roi
        assert (f["components"], f["genus"], f["closed"]) == (w["components"], w["genus"], w["closed"]), roi


def test_a_self_crossing_spiral_keeps_its_even_odd_volume():
    # IMOD's example: one spiral contour on each of two sections, each crossing itself, whose
    # arms lie where the other section has none; the layers between them keep their area by
    # growing their blended outline several pixels.
    model = ROOT.parent / "shared" / "data" / "em" / "imod" / "two_contour_example.mod"
    if not model.exists():
        pytest.skip("the shared IMOD model is absent (%s)" % model)
    s = scansurf.build(scansurf.read(model)).surfaces["object 1"]
    assert s.volume == pytest.approx(s.contour_volume, rel=1e-2)
    assert s.closed and s.components == 1


def test_a_spiral_crossing_itself_comes_out_closed_at_the_default_grid():
    # Two self-crossing spirals, 8 and 17 points: simplification's patches of one label once
    # each joined the same two shared vertices, leaving an edge with four triangles.
    def spiral(points):
        return [(2.0 * 1.6 ** (i / 4) * np.cos(1.45 * i), 2.0 * 1.6 ** (i / 4) * np.sin(1.45 * i)) for i in range(points)]
    cs = scansurf.contours({"spiral": {0.0: [spiral(8)], 9.4: [spiral(17)]}})
    s = scansurf.build(cs).surfaces["spiral"]
    assert s.closed
    assert s.volume == pytest.approx(s.contour_volume, rel=5e-2)


def write_reconstruct_series(folder, traces, sections, thickness=0.05):
    """A Reconstruct series: traces[name] = {section: [(x, y), ...]} in microns."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "cells.ser").write_text(
        '<?xml version="1.0"?>\n<Series index="1" units="microns" defaultThickness="%g" zMidSection="false">\n</Series>\n'
        % thickness)
    for s in range(1, sections + 1):
        contours = "".join(
            '<Contour name="%s" hidden="false" closed="true" border="1 0 0" fill="1 0 0" mode="9"\n points="%s"/>\n'
            % (name, ", ".join("%.5f %.5f" % p for p in by_section[s]))
            for name, by_section in traces.items() if s in by_section)
        (folder / ("cells.%d" % s)).write_text(
            '<?xml version="1.0"?>\n<Section index="%d" thickness="%g" alignLocked="true">\n'
            '<Transform dim="0" xcoef=" 0 1 0 0 0 0" ycoef=" 0 0 1 0 0 0">\n%s</Transform>\n</Section>\n'
            % (s, thickness, contours))
    return folder / "cells.ser"


def test_a_spine_surfaced_alone_is_the_one_surfaced_with_its_siblings(tmp_path):
    # A dendrite over 30 sections with four spines on its side whose heads reach into the
    # shaft's outline (0.005 to 0.1 um), and a second dendrite beside it, as a Reconstruct
    # series: a spine's surface is the same alone, with its dendrite and siblings ('d1*'), and
    # with everything, less what an incidental overlap would give up (the report's given_up;
    # these overlaps are judged real and kept in layers).
    def circle(cx, cy, r, n=48):
        return [(cx + r * np.cos(a), cy + r * np.sin(a)) for a in np.linspace(0, 2 * np.pi, n, endpoint=False)]
    traces = {"d1": {s: circle(2.0, 2.0, 0.3) for s in range(1, 31)},
              "d2": {s: circle(3.2, 2.0, 0.25) for s in range(1, 31)}}
    for i, (first, angle) in enumerate([(4, 0.3), (10, 2.0), (17, 3.6), (23, 5.0)]):
        depth = (0.005, 0.02, 0.05, 0.1)[i]  # how far the head reaches into the shaft's outline
        cx, cy = 2.0 + (0.4 - depth) * np.cos(angle), 2.0 + (0.4 - depth) * np.sin(angle)
        traces["d1sp%02d" % (i + 1)] = {s: circle(cx, cy, 0.1 + 0.015 * (s - first), 32) for s in range(first, first + 4)}
    series = write_reconstruct_series(tmp_path / "series", traces, 30)
    everything = scansurf.build(scansurf.read(series))
    group = scansurf.build(scansurf.read(series, objects=["d1*"]))
    for spine in ("d1sp01", "d1sp02", "d1sp03", "d1sp04"):
        alone = scansurf.build(scansurf.read(series, objects=[spine]))
        s = alone.surfaces[spine]
        assert s.closed and s.volume == pytest.approx(s.contour_volume, rel=1e-2), spine
        for run in (group, everything):
            given_up = sum(pair["given_up"][side] for pair in run.report["overlaps"]["partial"]
                           for side in "ab" if pair[side] == spine)
            other = run.surfaces[spine]
            assert other.volume == pytest.approx(s.volume - given_up, rel=1e-3), spine
            assert (other.components, other.genus, other.closed) == (s.components, s.genus, True), spine


def test_an_outline_drawn_on_two_neighbours_outlines_keeps_its_volume():
    # A quarter ring drawn on its neighbours: its inner edge is the disc A's own points, its
    # lower edge the top edge of the rectangle B (the shared head-and-neck set's optic
    # structures lie on the orbits' outlines so). Each keeps its contours' volume, in one
    # piece, and the ring shares its surface with both.
    arc = [(10 * np.cos(a), 10 * np.sin(a)) for a in np.linspace(0, np.pi / 2, 17)]
    disc = [(10 * np.cos(a), 10 * np.sin(a)) for a in np.linspace(0, 2 * np.pi, 64, endpoint=False)]
    ring = arc[::-1] + [(16 * np.cos(a), 16 * np.sin(a)) for a in np.linspace(0, np.pi / 2, 25)]
    rectangle = [(10, 0), (10, -6), (16, -6), (16, 0)]
    planes = np.arange(0, 12.1, 3.0)
    cs = scansurf.contours({"A": {z: [np.array(disc)] for z in planes},
                            "B": {z: [np.array(rectangle, float)] for z in planes},
                            "ring": {z: [np.array(ring)] for z in planes}})
    for options in ({}, {"voxel_size": 0.5}, {"voxel_size": 3.0}):
        built = scansurf.build(cs, **options)
        for name, s in built.surfaces.items():
            assert s.volume == pytest.approx(s.contour_volume, rel=1e-2), (name, options)
            assert (s.components, s.genus, s.closed) == (1, 0, True), (name, options)
        shares = {f["name"]: f["shares_surface_with"] for f in built.report["features"]}
        assert sorted(shares["ring"]) == ["A", "B"], options
