"""Surfaces as VTK and meshio objects, where those libraries are installed (neither is a
dependency of scansurf: each is imported only when asked for)."""

import numpy as np


def to_vtk(surface):
    """A vtkPolyData of a scansurf.Surface: its points, triangles and name (field data "name")."""
    try:
        from vtkmodules.util.numpy_support import numpy_to_vtk, numpy_to_vtkIdTypeArray
        from vtkmodules.vtkCommonCore import vtkPoints, vtkStringArray
        from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
    except ImportError as e:
        raise ImportError("to_vtk() needs VTK's Python bindings (Debian: python3-vtk9)") from e
    points = vtkPoints()
    points.SetData(numpy_to_vtk(np.ascontiguousarray(surface.vertices), deep=True))
    faces = np.asarray(surface.faces, dtype=np.int64)
    offsets = np.arange(0, 3 * len(faces) + 1, 3, dtype=np.int64)
    cells = vtkCellArray()
    cells.SetData(numpy_to_vtkIdTypeArray(offsets, deep=True), numpy_to_vtkIdTypeArray(faces.ravel(), deep=True))
    poly = vtkPolyData()
    poly.SetPoints(points)
    poly.SetPolys(cells)
    name = vtkStringArray()
    name.SetName("name")
    name.InsertNextValue(surface.name)
    poly.GetFieldData().AddArray(name)
    return poly


def to_meshio(surface):
    """A meshio.Mesh of a scansurf.Surface (one "triangle" cell block)."""
    try:
        import meshio
    except ImportError as e:
        raise ImportError("to_meshio() needs meshio (Debian: python3-meshio)") from e
    return meshio.Mesh(np.asarray(surface.vertices), [("triangle", np.asarray(surface.faces))])
