"""scansurf: separating surfaces from planar contours, on Vulkan.

    import scansurf
    cs = scansurf.read("RS.dcm", reference="CT/", rois=["Heart", "Lung_L"])   # any input format
    res = scansurf.build(cs, voxel_size=1.0)                                  # options as keywords
    heart = res.surfaces["Heart"]        # .vertices (N, 3) float32, .faces (M, 3) uint32, .volume ...
    res.label_volume                     # numpy array (z, y, x) + .origin, .spacing, .directions
    res.report                           # the report as a dict
    res.write("out/", formats=["glb", "ply"])

build() starts from the command-line tool's defaults, so a build with no options gives what
`scansurf INPUT -o OUT` gives, byte for byte. Errors are raised as the exception of their
category (scansurf.InvalidInput, scansurf.ResourceLimit, ...), with the library's message.
"""

import json
import os
import shutil
import tempfile
import threading
import weakref

import numpy as np

from . import _scansurf
from ._errors import (DefectiveSurface, Error, InternalError, InvalidArgument, InvalidInput,
                      IoError, NoDevice, OutOfMemory, ResourceLimit, VulkanError)
from ._scansurf import ContourSet, Engine, devices

__version__ = _scansurf.__version__

__all__ = ["read", "contours", "build", "devices", "engine", "batch", "ContourSet", "Engine",
           "BuildResult", "Surface", "LabelVolume", "Error", "InvalidArgument", "InvalidInput",
           "IoError", "NoDevice", "VulkanError", "InternalError", "OutOfMemory", "ResourceLimit",
           "DefectiveSurface"]


def _is_dataset(obj):
    """A pydicom Dataset (duck-typed: pydicom is not a dependency)."""
    return type(obj).__name__ in ("Dataset", "FileDataset") or hasattr(obj, "save_as")


def _save_dataset(ds, path):
    import pydicom  # only reached with a pydicom Dataset in hand
    pydicom.dcmwrite(str(path), ds, write_like_original=False)


def _as_path(source, scratch, name):
    """A path for a path or a pydicom Dataset (written into `scratch`)."""
    if _is_dataset(source):
        path = os.path.join(scratch, name)
        _save_dataset(source, path)
        return path
    return os.fspath(source)


def _reference_folder(reference, scratch):
    """A CT folder holding a sequence of pydicom Datasets (written into `scratch`)."""
    folder = os.path.join(scratch, "reference")
    os.mkdir(folder)
    for i, ds in enumerate(reference):
        _save_dataset(ds, os.path.join(folder, "%05d.dcm" % i))
    return folder


def _patterns(value):
    if value is None:
        return []
    return [value] if isinstance(value, str) else list(value)


def read(source, reference=None, rois=None, objects=None):
    """Reads and validates a contour set, recognised by content: contour-set JSON, DICOM RTSTRUCT,
    Reconstruct series, IMOD model.

    source: a path, or a pydicom Dataset of an RTSTRUCT.
    reference: RTSTRUCT only: the folder of the CT series the contours were drawn on (or a list of
        its pydicom Datasets); the label volume then lies on its voxel grid.
    rois, objects: glob patterns (case-insensitive) selecting ROIs (RTSTRUCT) or objects
        (Reconstruct, IMOD) by name; a pattern matching nothing is an InvalidArgument.
    """
    if not _is_dataset(source) and (reference is None or isinstance(reference, (str, bytes, os.PathLike))):
        return _scansurf._read(os.fspath(source), os.fspath(reference or ""), _patterns(rois), _patterns(objects))
    # Datasets are written to a folder that lives as long as the set: the report hashes the
    # RTSTRUCT, a DICOM SEG output reads the CT.
    kept = tempfile.mkdtemp(prefix="scansurf-datasets-")
    try:
        path = _as_path(source, kept, "rtstruct.dcm")
        folder = os.fspath(reference or "") if reference is None or isinstance(reference, (str, bytes, os.PathLike)) \
            else _reference_folder(reference, kept)
        cs = _scansurf._read(path, folder, _patterns(rois), _patterns(objects))
    except BaseException:
        shutil.rmtree(kept, ignore_errors=True)
        raise
    weakref.finalize(cs, shutil.rmtree, kept, True)
    return cs


def contours(features, units="mm", source="<python>"):
    """A contour set made in Python, checked by the same validation as files.

    features: a mapping name -> slices, or a sequence of dicts {"name", "slices", "color"}; slices
        are a mapping z -> polygons or a sequence of (z, polygons); a polygon is anything numpy
        reads as an (N, 2) array of x, y (closed implicitly). Several polygons on a slice combine
        by the even-odd rule (holes).
    units: the unit of every coordinate; source: names the set in error messages.
    """
    entries = []
    if hasattr(features, "items"):
        for name, slices in features.items():
            entries.append((name, None, slices))
    else:
        for f in features:
            color = f.get("color")
            entries.append((f["name"], tuple(int(c) for c in color) if color is not None else None, f["slices"]))
    return _scansurf._contours(entries, units, source)


_engines = {}
_engines_lock = threading.Lock()


def engine(device=None, validation=None):
    """The engine this process keeps for a device (created on first use, then reused).

    device: an index or part of a name (scansurf.devices() lists them); None: SCANSURF_DEVICE or
    the best device. validation: the Vulkan validation layers (None: SCANSURF_VALIDATION).
    """
    if validation is None:
        validation = os.environ.get("SCANSURF_VALIDATION", "") not in ("", "0")
    key = ("" if device is None else str(device), bool(validation))
    with _engines_lock:
        if key not in _engines:
            _engines[key] = Engine(key[0], key[1])
        return _engines[key]


def build(contour_set, engine=None, device=None, validation=None, **options):
    """Surfaces a contour set; returns a BuildResult. The GIL is released while it builds.

    Options, named as the command-line flags (without "--", "-" written "_"), default as there:
    voxel_size, grid=(nx, ny), convention ("enclosing", "partition"), overlaps ("layers",
    "partition"), overlap_tolerance ("auto", "off", depth or (depth, percent)), interpolate
    ("auto", "off" or layers per gap), caps ("round", "flat"), smooth (True), smooth_iterations,
    smooth_strength, contour_fit, junction_smoothing, keep_volume, min_angle, snap, simplify (True),
    simplify_tolerance, simplify_edge_length, simplify_min_angle, remesh (False), edge_length,
    curvature_sizing, threads (0: all cores; more than the cores count as the cores), max_memory
    (bytes), volume_unit ("input", "mm3", "cm3" or "cc" or "ml", "um3", "nm3": the report's
    volumes; Surface.volume stays in the input's unit cubed). Every option is checked against the command line's range, whether its stage is on
    or not: a bad one raises InvalidArgument naming it.
    engine: a scansurf.Engine to build on; else the one kept for `device` and `validation`.
    """
    if isinstance(contour_set, (str, bytes, os.PathLike)) or _is_dataset(contour_set):
        contour_set = read(contour_set)
    eng = engine if engine is not None else globals()["engine"](device, validation)
    return BuildResult(_scansurf._build(eng, contour_set, options))


class Surface:
    """One feature's closed surface, oriented outward, with its own vertices.

    vertices (N, 3) float32 and faces (M, 3) uint32 are read-only numpy views of the result's
    memory (made on first access, no copy after that); the figures come from the mesh and the
    contours: volume (the surface's), contour_volume (slab rule), voxel_volume, area, components,
    genus, closed, manifold, oriented, triangles.
    """

    def __init__(self, result, index, name, label, color):
        self._result = result
        self.index = index
        self.name = name
        self.label = label
        self.color = color
        self._arrays = None
        self._stats = None

    def _mesh(self):
        if self._arrays is None:
            self._arrays = self._result._surface(self.index)
        return self._arrays

    @property
    def vertices(self):
        return self._mesh()[0]

    @property
    def faces(self):
        return self._mesh()[1]

    @property
    def stats(self):
        """Every figure of the surface, as a dict."""
        if self._stats is None:
            self._stats = self._result._stats(self.index)
        return dict(self._stats)

    def __getattr__(self, name):
        if name.startswith("_"):
            raise AttributeError(name)
        stats = self.stats
        if name in stats:
            return stats[name]
        raise AttributeError("Surface has no attribute %r" % name)

    def __repr__(self):
        return "<scansurf.Surface %r: %d triangles>" % (self.name, len(self.faces))

    def to_vtk(self):
        """A vtkPolyData (needs VTK's Python bindings, e.g. Debian's python3-vtk9)."""
        from . import interop
        return interop.to_vtk(self)

    def to_meshio(self):
        """A meshio.Mesh (needs meshio, e.g. Debian's python3-meshio)."""
        from . import interop
        return interop.to_meshio(self)


class LabelVolume(np.ndarray):
    """The label volume: label = feature index + 1 per voxel (0 background; inner features first
    where they share voxels), indexed [k, j, i] (z, y, x), a read-only view of the result's
    memory. origin: the centre of voxel (0, 0, 0); spacing: (di, dj, dk); directions: a 3x3
    matrix whose columns are the unit directions of i, j and k; all in the input's units and
    frame (LPS for DICOM). With a reference CT it lies on the CT's lattice."""

    def __array_finalize__(self, obj):
        for name in ("origin", "spacing", "directions", "resampled"):
            setattr(self, name, getattr(obj, name, None))

    def index_to_point(self, ijk):
        """Positions of voxel indices (i, j, k), rows of (N, 3)."""
        ijk = np.asarray(ijk, dtype=float)
        return self.origin + (ijk * self.spacing) @ self.directions.T


class BuildResult:
    """What build() gives back: surfaces by name, the shared mesh, the label volume, the report."""

    def __init__(self, core):
        self._core = core
        cs = core.contours
        self.contours = cs
        colors = cs._colors()  # the input's, else the library's palette
        self.surfaces = {}
        for i, name in enumerate(cs.names):
            self.surfaces[name] = Surface(core, i, name, i + 1, tuple(colors[i]))
        self.warnings = list(cs.warnings) + list(core.warnings)
        self.timings = dict(core.timings)
        self.grid = core.grid
        self.device = core.device
        self._label_volume = None
        self._report = None

    @property
    def mesh(self):
        """(vertices (V, 3) float32, faces (T, 3) uint32, labels (T, 2) uint16): every separating
        surface in one mesh, vertices shared; face t separates labels[t, 0] (behind, a < b) from
        labels[t, 1] (in front). Read-only views, no copy."""
        return self._core._mesh()

    @property
    def label_volume(self):
        if self._label_volume is None:
            labels, origin, axes, resampled, warnings = self._core._label_volume()
            axes = np.asarray(axes, dtype=float)
            spacing = np.linalg.norm(axes, axis=1)
            volume = labels.view(LabelVolume)
            volume.origin = np.asarray(origin, dtype=float)
            volume.spacing = spacing
            volume.directions = (axes / spacing[:, None]).T
            volume.resampled = resampled
            self.warnings.extend(warnings)
            self._label_volume = volume
        return self._label_volume

    @property
    def report(self):
        """The report as a dict, as the command-line tool's --report writes it (no outputs)."""
        if self._report is None:
            self._report = json.loads(self._core._report_json())
        return self._report

    def write(self, out_dir, formats=("ply",), label_volume=None, dicom_seg=None, report="report.json",
              draco=True, scene_name=None):
        """Writes the outputs as the command-line tool does, all or nothing: per-feature files in
        out_dir for each of formats (ply, drc, obj, stl, vtp; glb and seg.vtm scenes), the label
        volume (.nrrd, .seg.nrrd, .nii, .nii.gz), a DICOM SEG (needs the reference CT), and the
        report (last; None: none). Relative file names are taken in out_dir. Returns the paths."""
        formats = [formats] if isinstance(formats, str) else list(formats)
        if scene_name is None:
            scene_name = _stem(self.contours.input)
        _check_scene_name(scene_name)
        paths = self._core._write(os.fspath(out_dir), formats, os.fsencode(scene_name), os.fspath(label_volume or ""),
                                  os.fspath(dicom_seg or ""), os.fspath(report or ""), bool(draco))
        return [os.fspath(p) for p in paths]

    def __repr__(self):
        return "<scansurf.BuildResult: %d surfaces on %s>" % (len(self.surfaces), self.device)


def _check_scene_name(name):
    """A scene's name becomes a file name in out_dir: never a path out of it."""
    if (not isinstance(name, str) or not name or name in (".", "..") or "/" in name or "\\" in name
            or "\0" in name):
        raise InvalidArgument("scene_name %r must be a plain file name (no folder, '.', '..' or NUL): "
                              "the scene files are written in out_dir" % (name,))


def _stem(path):
    """The scene's name, as the command line names it (the file name without its last extension)."""
    name = os.path.basename(os.fspath(path)) or "surfaces"
    return os.path.splitext(name)[0] or name


def batch(inputs, out_dir, client=None, **options):
    """Surfaces many inputs on Dask; see scansurf.batch_runs.batch."""
    from .batch_runs import batch as run_batch
    return run_batch(inputs, out_dir, client=client, **options)
