"""Every report validates against docs/report.schema.json, and says what it is about: the input
files' hashes, the ROI numbers and interpreted types, the frame of reference, the CT grid."""

import hashlib
import json
import re
import subprocess

import pytest

import scansurf
from conftest import EXAMPLE, ROOT, sphere

jsonschema = pytest.importorskip("jsonschema", reason="jsonschema is not installed (Debian: python3-jsonschema)")
SCHEMA = json.loads((ROOT / "docs" / "report.schema.json").read_text())


def validate(report):
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    jsonschema.validate(report, SCHEMA, cls=jsonschema.Draft202012Validator)
    return report


def cli_report(cli, tmp_path, *args):
    out = tmp_path / "out"
    subprocess.run([cli, *map(str, args), "-o", str(out), "--report", str(out / "report.json"), "-q"], check=True)
    return validate(json.loads((out / "report.json").read_text()))


def test_the_examples_report_validates_and_hashes_its_input(tmp_path, cli):
    report = cli_report(cli, tmp_path, EXAMPLE)
    assert report["input_files"] == [{"path": str(EXAMPLE), "sha256": hashlib.sha256(EXAMPLE.read_bytes()).hexdigest(),
                                      "bytes": EXAMPLE.stat().st_size}]
    assert report["frame_of_reference_uid"] is None and report["reference_grid"] is None
    assert all(f["source_number"] is None for f in report["features"])
    assert "volume" not in report["features"][0]  # one name for it: surface_volume


@pytest.mark.parametrize("flags", [["--overlaps", "partition"], ["--convention", "partition", "--interpolate", "off"],
                                   ["--no-smooth", "--caps", "flat", "--voxel-size", "1"]])
def test_reports_of_other_modes_validate(tmp_path, cli, flags):
    cli_report(cli, tmp_path, EXAMPLE, *flags)


def test_a_remeshed_report_validates(tmp_path, cli):
    path = tmp_path / "ball.json"
    scansurf.contours({"ball": sphere(radius=6)}).write_json(path)
    report = cli_report(cli, tmp_path, path, "--remesh", "--voxel-size", "1")
    assert report["remeshing"]["triangles_after"] > 0


def test_the_python_report_validates(phantom_result):
    validate(phantom_result.report)


def test_an_rtstruct_report_names_rois_frame_and_ct_grid(tmp_path, cli):
    pydicom = pytest.importorskip("pydicom", reason="pydicom is not installed (Debian: python3-pydicom)")
    import test_dicom
    rs = tmp_path / "rs.dcm"
    pydicom.dcmwrite(str(rs), test_dicom.rtstruct(), write_like_original=False)
    ct = tmp_path / "ct"
    ct.mkdir()
    for i, ds in enumerate(test_dicom.ct_series()):
        pydicom.dcmwrite(str(ct / ("%03d.dcm" % i)), ds, write_like_original=False)
    report = cli_report(cli, tmp_path, rs, "--reference", ct)
    assert [(f["name"], f["source_number"], f["interpreted_type"]) for f in report["features"]] == [
        ("Box", 1, "ORGAN"), ("Core", 2, "PTV")]
    assert report["frame_of_reference_uid"] == test_dicom.FRAME
    grid = report["reference_grid"]
    assert grid["size"] == [64, 64, 16] and grid["spacing"] == [1.0, 1.0] and grid["origin"] == [-32.0, -32.0]
    assert report["input_files"][0]["sha256"] == hashlib.sha256(rs.read_bytes()).hexdigest()


def test_object_numbers_of_a_reconstruct_series(tmp_path, cli):
    series = sorted((ROOT / "tests" / "data" / "reconstruct").glob("*.ser"))
    if not series:
        pytest.skip("no Reconstruct series in tests/data/reconstruct")
    report = cli_report(cli, tmp_path, series[0])
    assert all(isinstance(f["source_number"], int) and f["source_number"] >= 1 for f in report["features"])
    assert len(report["input_files"]) > 1  # the series file and its sections


def test_rt_types_become_segment_terminology(tmp_path, cli):
    """RT ROI Interpreted Types as the codes the DICOM SEG, seg.nrrd and .seg.vtm carry."""
    pydicom = pytest.importorskip("pydicom", reason="pydicom is not installed (Debian: python3-pydicom)")
    import test_dicom
    rs, ct = tmp_path / "rs.dcm", tmp_path / "ct"
    pydicom.dcmwrite(str(rs), test_dicom.rtstruct(), write_like_original=False)
    ct.mkdir()
    for i, ds in enumerate(test_dicom.ct_series()):
        pydicom.dcmwrite(str(ct / ("%03d.dcm" % i)), ds, write_like_original=False)
    out = tmp_path / "out"
    subprocess.run([cli, str(rs), "--reference", str(ct), "-o", str(out), "--format", "seg.vtm", "-q",
                    "--dicom-seg", str(out / "seg.dcm"), "--label-volume", str(out / "rs.seg.nrrd")], check=True)
    seg = pydicom.dcmread(str(out / "seg.dcm"))
    codes = [(s.SegmentLabel, s.SegmentedPropertyCategoryCodeSequence[0].CodeValue,
              s.SegmentedPropertyTypeCodeSequence[0].CodeValue) for s in seg.SegmentSequence]
    assert codes == [("Box", "123037004", "85756007"), ("Core", "130041", "228793007")]  # ORGAN; PTV
    header = (out / "rs.seg.nrrd").read_bytes().split(b"\n\n")[0].decode()
    assert "Segment1_Tags:=TerminologyEntry:Segmentation category and type - DICOM master list~DCM^130041^RT Target~" \
           "SCT^228793007^PTV~" in header
    assert "SCT^228793007^PTV" in segment_tags(out / "rs.seg_1.vtp")  # the second segment's block
    assert "SCT^123037004^Anatomical Structure~SCT^85756007^Tissue" in segment_tags(out / "rs.seg_0.vtp")


def segment_tags(vtp):
    """The Segment_Tags field of a Slicer segment .vtp (a VTK String array in ascii: byte codes)."""
    found = re.search(r'<Array type="String" Name="Segment_Tags"[^>]*>([0-9 ]*)</Array>', vtp.read_text())
    return bytes(int(c) for c in found.group(1).split() if c != "0").decode()


def test_the_seg_carries_the_cts_patient_and_study(tmp_path, cli):
    """dcentvfy (dicom3tools) finds no attribute of the patient or study that the CT has and the
    SEG lacks, de-identification included; dciodvfy finds no error."""
    pydicom = pytest.importorskip("pydicom", reason="pydicom is not installed (Debian: python3-pydicom)")
    import shutil
    import test_dicom
    from pydicom.dataset import Dataset
    if not shutil.which("dcentvfy") or not shutil.which("dciodvfy"):
        pytest.skip("dicom3tools (dcentvfy, dciodvfy) is not installed")
    rs, ct = tmp_path / "rs.dcm", tmp_path / "ct"
    pydicom.dcmwrite(str(rs), test_dicom.rtstruct(), write_like_original=False)
    ct.mkdir()
    for i, s in enumerate(test_dicom.ct_series()):
        s.StudyDescription, s.NameOfPhysiciansReadingStudy, s.AdditionalPatientHistory = "Planning CT", "Reader^Rita", "none"
        s.PatientIdentityRemoved, s.DeidentificationMethod = "YES", "test profile"
        code = Dataset()
        code.CodeValue, code.CodingSchemeDesignator, code.CodeMeaning = "113100", "DCM", "Basic Application Confidentiality Profile"
        s.DeidentificationMethodCodeSequence = [code]
        s.PatientBirthDate, s.PatientSex, s.StudyDate, s.StudyTime, s.AccessionNumber = "19500101", "O", "20240101", "120000", "A1"
        s.StudyID, s.ReferringPhysicianName, s.PatientAge, s.PatientWeight = "S1", "Ref^Rob", "074Y", "70"
        s.SeriesNumber, s.InstanceNumber = 1, i + 1
        pydicom.dcmwrite(str(ct / ("%03d.dcm" % i)), s, write_like_original=False)
    out = tmp_path / "out"
    subprocess.run([cli, str(rs), "--reference", str(ct), "-o", str(out), "--dicom-seg", str(out / "seg.dcm"), "-q"], check=True)
    entity = subprocess.run(["dcentvfy", str(out / "seg.dcm"), *map(str, sorted(ct.glob("*.dcm")))], capture_output=True, text=True)
    assert entity.stdout + entity.stderr == "", entity.stdout + entity.stderr
    iod = subprocess.run(["dciodvfy", str(out / "seg.dcm")], capture_output=True, text=True)
    assert not [line for line in (iod.stdout + iod.stderr).splitlines() if line.startswith("Error")], iod.stderr
    seg = pydicom.dcmread(str(out / "seg.dcm"))
    assert seg.PatientIdentityRemoved == "YES" and seg.StudyDescription == "Planning CT"
