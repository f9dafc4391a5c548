"""pydicom Datasets wherever a path is taken (the RTSTRUCT, and the CT series as Datasets)."""

import numpy as np
import pytest

import scansurf

pydicom = pytest.importorskip("pydicom", reason="pydicom is not installed (Debian: python3-pydicom)")
from pydicom.dataset import Dataset, FileMetaDataset  # noqa: E402
from pydicom.sequence import Sequence  # noqa: E402
from pydicom.uid import ExplicitVRLittleEndian, generate_uid  # noqa: E402

RTSTRUCT_CLASS = "1.2.840.10008.5.1.4.1.1.481.3"
FRAME = generate_uid()


def item(**values):
    ds = Dataset()
    for k, v in values.items():
        setattr(ds, k, v)
    return ds


def rtstruct():
    """An RTSTRUCT of two ROIs: a square prism and a small box inside it, on 2 mm slices."""
    meta = FileMetaDataset()
    meta.MediaStorageSOPClassUID = RTSTRUCT_CLASS
    meta.MediaStorageSOPInstanceUID = generate_uid()
    meta.TransferSyntaxUID = ExplicitVRLittleEndian
    ds = Dataset()
    ds.file_meta = meta
    ds.SOPClassUID, ds.SOPInstanceUID, ds.Modality = RTSTRUCT_CLASS, meta.MediaStorageSOPInstanceUID, "RTSTRUCT"
    ds.PatientName, ds.StructureSetLabel = "Test^Python", "python"
    ds.ReferencedFrameOfReferenceSequence = Sequence([item(FrameOfReferenceUID=FRAME)])
    rois = [(1, "Box", 20.0, range(0, 11)), (2, "Core", 5.0, range(3, 8))]
    ds.StructureSetROISequence = Sequence(
        [item(ROINumber=n, ReferencedFrameOfReferenceUID=FRAME, ROIName=name, ROIGenerationAlgorithm="MANUAL")
         for n, name, _, _ in rois])
    contours = []
    for n, _, half, slices in rois:
        seq = []
        for k in slices:
            z = 2.0 * k
            data = [-half, -half, z, half, -half, z, half, half, z, -half, half, z]
            seq.append(item(ContourGeometricType="CLOSED_PLANAR", NumberOfContourPoints=4, ContourData=data))
        contours.append(item(ReferencedROINumber=n, ROIDisplayColor=[255, 0, 0], ContourSequence=Sequence(seq)))
    ds.ROIContourSequence = Sequence(contours)
    ds.RTROIObservationsSequence = Sequence(
        [item(ObservationNumber=n, ReferencedROINumber=n, RTROIInterpretedType="ORGAN" if n == 1 else "PTV")
         for n, _, _, _ in rois])
    return ds


def test_a_pydicom_dataset_reads_like_its_file(tmp_path):
    ds = rtstruct()
    from_dataset = scansurf.read(ds, rois=["Box", "Core"])
    assert from_dataset.names == ["Box", "Core"]
    path = tmp_path / "rs.dcm"
    pydicom.dcmwrite(str(path), ds, write_like_original=False)
    from_file = scansurf.read(path)
    a, b = scansurf.build(from_dataset, voxel_size=1.0), scansurf.build(from_file, voxel_size=1.0)
    np.testing.assert_array_equal(a.surfaces["Box"].vertices, b.surfaces["Box"].vertices)
    inputs = a.report["input_files"]  # the Dataset's file lives as long as the set: hashed, sized
    assert inputs[0]["sha256"] is not None and inputs[0]["bytes"] == path.stat().st_size
    box = a.surfaces["Box"]
    assert box.contour_volume == pytest.approx(40 * 40 * 22, rel=1e-6)  # 11 planes of 2 mm slabs
    assert scansurf.build(ds, voxel_size=1.0).surfaces["Core"].closed  # build() takes a Dataset too


def ct_series():
    """A 64 x 64 CT of 1 mm pixels on the RTSTRUCT's 2 mm slices, with two slices beyond each end."""
    ct = []
    series, study = generate_uid(), generate_uid()
    for k in range(-2, 14):
        meta = FileMetaDataset()
        meta.MediaStorageSOPClassUID = "1.2.840.10008.5.1.4.1.1.2"
        meta.MediaStorageSOPInstanceUID = generate_uid()
        meta.TransferSyntaxUID = ExplicitVRLittleEndian
        s = Dataset()
        s.file_meta = meta
        s.SOPClassUID, s.SOPInstanceUID, s.Modality = meta.MediaStorageSOPClassUID, meta.MediaStorageSOPInstanceUID, "CT"
        s.PatientName, s.PatientID, s.StudyInstanceUID, s.SeriesInstanceUID = "Test^Python", "P1", study, series
        s.FrameOfReferenceUID = FRAME
        s.ImagePositionPatient = [-32.0, -32.0, 2.0 * k]
        s.ImageOrientationPatient = [1, 0, 0, 0, 1, 0]
        s.PixelSpacing = [1.0, 1.0]
        s.Rows = s.Columns = 64
        s.SamplesPerPixel, s.PhotometricInterpretation = 1, "MONOCHROME2"
        s.BitsAllocated, s.BitsStored, s.HighBit, s.PixelRepresentation = 16, 16, 15, 0
        s.PixelData = np.zeros((64, 64), np.uint16).tobytes()
        ct.append(s)
    return ct


def test_a_reference_series_as_datasets(tmp_path):
    ct = ct_series()
    cs = scansurf.read(rtstruct(), reference=ct)
    result = scansurf.build(cs)
    assert result.grid["spacing_x"] == 1.0  # on the CT's lattice
    lv = result.label_volume
    assert lv.shape[1:] == (64, 64)
