// Label volumes as NIfTI (read back with the NIfTI reference library: header, affine, voxels,
// the ITK-SNAP label table) and as DICOM SEG (read back with DCMTK's dcmseg: segments,
// colours, frames voxel for voxel, references; validated with dicom3tools' dciodvfy when it
// is installed), on hand-made volumes and on CT series and RT Structure Sets written here.
#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcsequen.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmfg/fgderimg.h>
#include <dcmtk/dcmfg/fgplanpo.h>
#include <dcmtk/dcmfg/fgseg.h>
#include <dcmtk/dcmiod/cielabutil.h>
#include <dcmtk/dcmseg/segdoc.h>
#include <dcmtk/dcmseg/segment.h>
#include <dcmtk/dcmseg/segutils.h>
#include <gtest/gtest.h>
#include <nifti1_io.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "scansurf/input.h"
#include "scansurf/nesting.h"
#include "scansurf/outputs.h"
#include "scansurf/palette.h"
#include "support/reference_rasterizer.h"
#include "support/rtstruct_builder.h"
#include "support/scratch_dir_test.h"

namespace scansurf {
namespace {

namespace fs = std::filesystem;

using VolumeFormats = test::ScratchDirTest;

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct NimDeleter {
  void operator()(nifti_image* nim) const { nifti_image_free(nim); }
};
using Nim = std::unique_ptr<nifti_image, NimDeleter>;

// Two features: "outer" with its own colour, and one whose name holds quotes (palette colour).
ContourSet twoFeatures() {
  ContourSet set;
  set.source = "hand-made";
  set.features.resize(2);
  set.features[0].name = "outer";
  set.features[0].color = Rgb{200, 10, 10};
  set.features[1].name = "in \"side\"";
  return set;
}

// 4 x 3 x 3 voxels at LPS origin (-10, 20, 5) with steps 0.5, 0.75, 2.5 mm; labels 0..2.
LabelVolume handVolume() {
  LabelVolume v;
  v.grid.nx = 4, v.grid.ny = 3, v.grid.nz = 3;
  v.grid.originX = -10, v.grid.originY = 20;
  v.grid.spacingX = 0.5, v.grid.spacingY = 0.75;
  v.grid.layerZ = {5, 7.5, 10};
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 4; ++i) v.labels.push_back(static_cast<Label>((i + 2 * j + k) % 3));
  return v;
}

// ---------------------------------------------------------------------------------------
// NIfTI

TEST_F(VolumeFormats, NiftiGzipHasTheRasAffineTheLabelsAndAnItkSnapTable) {
  const ContourSet set = twoFeatures();
  const LabelVolume v = handVolume();
  const fs::path path = dir_ / "labels.nii.gz";
  ASSERT_TRUE(writeLabelVolume(path, set, v));
  const std::string bytes = readFile(path);
  ASSERT_GE(bytes.size(), 2u);
  EXPECT_EQ(static_cast<unsigned char>(bytes[0]), 0x1f) << "gzip";
  EXPECT_EQ(static_cast<unsigned char>(bytes[1]), 0x8b) << "gzip";

  Nim nim(nifti_image_read(path.c_str(), 1));
  ASSERT_TRUE(nim && nim->data);
  EXPECT_EQ(nim->nifti_type, NIFTI_FTYPE_NIFTI1_1);
  EXPECT_EQ(nim->ndim, 3);
  EXPECT_EQ(nim->nx, 4);
  EXPECT_EQ(nim->ny, 3);
  EXPECT_EQ(nim->nz, 3);
  EXPECT_EQ(nim->datatype, DT_UINT8);
  EXPECT_FLOAT_EQ(nim->dx, 0.5f);
  EXPECT_FLOAT_EQ(nim->dy, 0.75f);
  EXPECT_FLOAT_EQ(nim->dz, 2.5f);
  EXPECT_EQ(nim->xyz_units, NIFTI_UNITS_MM);
  EXPECT_EQ(nim->intent_code, NIFTI_INTENT_LABEL);
  EXPECT_FLOAT_EQ(nim->cal_min, 0);
  EXPECT_FLOAT_EQ(nim->cal_max, 2);
  EXPECT_EQ(nim->qform_code, NIFTI_XFORM_SCANNER_ANAT);
  EXPECT_EQ(nim->sform_code, NIFTI_XFORM_SCANNER_ANAT);
  // RAS = diag(-1, -1, 1) * LPS: x and y steps and origin negated.
  const double expected[3][4] = {{-0.5, 0, 0, 10}, {0, -0.75, 0, -20}, {0, 0, 2.5, 5}};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) {
      EXPECT_NEAR(nim->sto_xyz.m[r][c], expected[r][c], 1e-5) << "sform " << r << "," << c;
      EXPECT_NEAR(nim->qto_xyz.m[r][c], expected[r][c], 1e-5) << "qform " << r << "," << c;
    }
  const auto* data = static_cast<const std::uint8_t*>(nim->data);
  EXPECT_EQ(std::vector<Label>(data, data + nim->nvox), v.labels);

  // A known point: the LPS centre of voxel (3, 1, 2) is (-8.5, 20.75, 10), RAS (8.5, -20.75, 10).
  const float ras[3] = {8.5f, -20.75f, 10.0f};
  int ijk[3];
  for (int r = 0; r < 3; ++r) {
    const float* row = nim->sto_ijk.m[r];
    ijk[r] = static_cast<int>(std::lround(row[0] * ras[0] + row[1] * ras[1] + row[2] * ras[2] + row[3]));
  }
  EXPECT_EQ(ijk[0], 3);
  EXPECT_EQ(ijk[1], 1);
  EXPECT_EQ(ijk[2], 2);
  EXPECT_EQ(data[ijk[0] + 4 * (ijk[1] + 3 * ijk[2])], v.at(3, 1, 2));

  // The ITK-SNAP label description beside it.
  const std::string table = readFile(dir_ / "labels.label.txt");
  EXPECT_NE(table.find("# ITK-SnAP Label Description File"), std::string::npos);
  std::map<int, std::string> lines;
  std::istringstream in(table);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    int idx = -1;
    std::istringstream(line) >> idx;
    lines[idx] = line;
  }
  ASSERT_EQ(lines.size(), 3u);
  auto fields = [&](int idx) {
    int i, r, g, b, vis, msh;
    double a;
    std::istringstream f(lines[idx]);
    f >> i >> r >> g >> b >> a >> vis >> msh;
    std::string rest;
    std::getline(f, rest);
    return std::make_tuple(r, g, b, a, vis, msh, rest.substr(rest.find('"')));
  };
  EXPECT_EQ(fields(0), std::make_tuple(0, 0, 0, 0.0, 0, 0, std::string("\"Clear Label\"")));
  EXPECT_EQ(fields(1), std::make_tuple(200, 10, 10, 1.0, 1, 1, std::string("\"outer\"")));
  const Rgb second = featureColors(set)[1];
  EXPECT_EQ(fields(2), std::make_tuple(int{second[0]}, int{second[1]}, int{second[2]}, 1.0, 1, 1, std::string("\"in 'side'\"")));
}

TEST_F(VolumeFormats, NiftiUncompressedUint16OnUnevenLayersIsResampled) {
  LabelVolume v;
  v.grid.nx = 2, v.grid.ny = 1, v.grid.nz = 3;
  v.grid.spacingX = 1, v.grid.spacingY = 1;
  v.grid.layerZ = {0, 1, 3};
  v.labels = {0, 300, 1, 2, 3, 4};
  ContourSet set;
  set.features.resize(300);
  for (std::size_t f = 0; f < set.features.size(); ++f) set.features[f].name = std::to_string(f) + "th";
  const fs::path path = dir_ / "wide.nii";
  ASSERT_TRUE(writeLabelVolume(path, set, v));
  const std::string bytes = readFile(path);
  ASSERT_GE(bytes.size(), 352u);
  EXPECT_EQ(bytes.substr(344, 4), std::string("n+1\0", 4)) << "single-file NIfTI-1 magic";
  Nim nim(nifti_image_read(path.c_str(), 1));
  ASSERT_TRUE(nim && nim->data);
  EXPECT_EQ(nim->datatype, DT_UINT16);
  EXPECT_EQ(nim->nz, 4);  // z = 0, 1, 2, 3: the smallest gap
  EXPECT_FLOAT_EQ(nim->dz, 1.0f);
  const auto* data = static_cast<const std::uint16_t*>(nim->data);
  EXPECT_EQ(std::vector<Label>(data, data + nim->nvox), (std::vector<Label>{0, 300, 1, 2, 1, 2, 3, 4}));
  EXPECT_TRUE(fs::exists(dir_ / "wide.label.txt"));
}

TEST_F(VolumeFormats, OutputChecksKnowTheVolumeAndSegExtensions) {
  for (const char* name : {"a.nrrd", "a.seg.nrrd", "a.nii", "a.nii.gz", "A.NII.GZ"}) {
    OutputPlan plan;
    plan.labelVolume = dir_ / name;
    EXPECT_TRUE(checkOutputs(plan)) << name;
  }
  OutputPlan plan;
  plan.labelVolume = dir_ / "a.mha";
  auto r = checkOutputs(plan);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidArgument);
  EXPECT_NE(r.error().message.find("known: .nrrd, .seg.nrrd, .nii, .nii.gz"), std::string::npos) << r.error().message;
  EXPECT_FALSE(writeLabelVolume(dir_ / "a.vtk", twoFeatures(), handVolume()));
  EXPECT_EQ(labelTablePathFor("x/a.nii.gz", VolumeFormat::Nifti), fs::path("x/a.label.txt"));
  EXPECT_EQ(labelTablePathFor("x/a.seg.nrrd", VolumeFormat::Nrrd), fs::path("x/a.seg.ctbl"));

  OutputPlan seg;
  seg.dicomSeg = dir_ / "seg.dcm";
  r = checkOutputs(seg);
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidArgument);
  EXPECT_NE(r.error().message.find("(a reference series)"), std::string::npos) << r.error().message;
  seg.referenceSeries = dir_;
  EXPECT_TRUE(checkOutputs(seg));
  seg.dicomSeg = dir_ / "seg.nii";
  EXPECT_FALSE(checkOutputs(seg));
  EXPECT_EQ(fileCount(), 0u) << "checks write nothing";
}

// ---------------------------------------------------------------------------------------
// DICOM SEG

std::vector<Point2> square(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// A CT series and a structure set on it, read and scan converted on the CPU onto the CT grid.
class DicomSeg : public test::ScratchDirTest {
 protected:
  void SetUp() override {
    test::ScratchDirTest::SetUp();
    ct_.columns = 40;
    ct_.rows = 30;
    ct_.spacingX = 0.8;
    ct_.spacingY = 0.9;
    ct_.originX = -15.2;
    ct_.originY = -12.6;
    ct_.sliceZ = {-5, -2.5, 0, 2.5, 5, 7.5};
    ct_.sliceThickness = 2.5;
    test::writeTestCtSeries(ct_, ctDir());
  }
  fs::path ctDir() const { return dir_ / "ct"; }

  // organ (a square on three slices), core inside it (own colour), a speck that covers no
  // pixel centre, and "wide" reaching beyond the CT's right edge (x = 16 mm).
  test::TestRtStruct structureSet() const {
    test::TestRtStruct rt;
    test::TestRoi organ{1, "organ", "ORGAN", std::nullopt, {}};
    for (double z : {-2.5, 0.0, 2.5}) organ.contours.push_back(test::closedContour(square(-6, -5, 7, 6), z));
    test::TestRoi core{2, "core", "GTV", Rgb{40, 200, 90}, {}};
    for (double z : {0.0, 2.5}) core.contours.push_back(test::closedContour(square(-2, -2, 2.5, 2), z));
    test::TestRoi speck{3, "speck", "ORGAN", std::nullopt, {}};
    speck.contours.push_back(test::closedContour(square(-9.13, -8.2, -9.1, -8.17), 0.0));
    test::TestRoi wide{4, "wide", "ORGAN", std::nullopt, {}};
    wide.contours.push_back(test::closedContour(square(10, -3, 30, 3), 5.0));
    rt.rois = {organ, core, speck, wide};
    return rt;
  }

  struct Case {
    ContourSet contours;
    LabelVolume volume;
  };
  Case build(const test::TestRtStruct& rt, GridOptions options = {}) const {
    test::writeTestRtStruct(rt, dir_ / "rt.dcm");
    ReadOptions read;
    read.referenceSeries = ctDir();
    auto contours = readContours(dir_ / "rt.dcm", read);
    EXPECT_TRUE(contours) << contours.error().message;
    if (!contours) return {};
    auto grid = makeGrid(*contours, options);
    EXPECT_TRUE(grid) << grid.error().message;
    if (!grid) return {};
    const Nesting nesting = computeNesting(*contours);
    return {*contours, test::referenceScanConvert(*contours, *grid, nesting.order, 8)};
  }

  test::TestCt ct_;
};

// The label volume voxel of CT pixel (i, j) on CT slice k: the grid has one background voxel
// around the CT lattice (and here grows only to the right).
// CT voxel (i, j) of the slice at z: the grid's pixel (i + 1, j + 1) on the layer whose slab
// holds z (the grid's layers are the contour planes; CT slices between them take the nearer).
Label ctVoxel(const LabelVolume& v, int i, int j, double z) { return v.at(i + 1, j + 1, nearestLayer(v.grid, z)); }

TEST_F(DicomSeg, SegmentsFramesAndReferencesReadBackWithDcmseg) {
  const Case c = build(structureSet());
  ASSERT_EQ(c.contours.features.size(), 4u);
  ASSERT_EQ(c.volume.grid.originX, -15.2 - 0.8);
  const fs::path path = dir_ / "seg.dcm";
  auto written = writeDicomSeg(path, c.contours, c.volume, ctDir());
  ASSERT_TRUE(written) << written.error().message;

  // Which features have voxels on which CT slice, from the volume.
  std::vector<int> featureOf;  // segment number - 1 -> feature
  std::map<std::pair<int, std::size_t>, bool> expectedFrames;
  for (int f = 0; f < 4; ++f) {
    bool any = false;
    for (std::size_t k = 0; k < ct_.sliceZ.size(); ++k)
      for (int j = 0; j < ct_.rows; ++j)
        for (int i = 0; i < ct_.columns; ++i)
          if (ctVoxel(c.volume, i, j, ct_.sliceZ[k]) == labelOfFeature(f)) any = expectedFrames[{f, k}] = true;
    if (any) featureOf.push_back(f);
  }
  // organ, core and wide; the speck has no voxel.
  ASSERT_EQ(featureOf, (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(written->segments, 3);
  EXPECT_EQ(written->frames, static_cast<int>(expectedFrames.size()));
  ASSERT_EQ(written->warnings.size(), 2u);
  EXPECT_NE(written->warnings[0].find("\"speck\" has no voxel on the CT's grid"), std::string::npos) << written->warnings[0];
  EXPECT_NE(written->warnings[1].find("\"wide\": "), std::string::npos) << written->warnings[1];
  EXPECT_NE(written->warnings[1].find("beyond the CT's field of view"), std::string::npos) << written->warnings[1];

  DcmSegmentation* loaded = nullptr;
  ASSERT_TRUE(DcmSegmentation::loadFile(path.c_str(), loaded).good());
  std::unique_ptr<DcmSegmentation> seg(loaded);
  EXPECT_EQ(seg->getSegmentationType(), DcmSegTypes::ST_BINARY);
  ASSERT_EQ(seg->getNumberOfSegments(), 3u);
  const std::vector<Rgb> colors = featureColors(c.contours);
  for (std::size_t s = 0; s < 3; ++s) {
    DcmSegment* segment = seg->getSegment(s + 1);
    ASSERT_NE(segment, nullptr);
    const int f = featureOf[s];
    OFString label, algorithm;
    segment->getSegmentLabel(label);
    EXPECT_EQ(std::string(label.c_str()), c.contours.features[static_cast<std::size_t>(f)].name);
    EXPECT_EQ(segment->getSegmentAlgorithmType(), DcmSegTypes::SAT_AUTOMATIC);
    segment->getSegmentAlgorithmName(algorithm);
    EXPECT_EQ(std::string(algorithm.c_str()), "scansurf");
    Uint16 L = 0, a = 0, b = 0;
    ASSERT_TRUE(segment->getRecommendedDisplayCIELabValue(L, a, b).good());
    double rgb[3];
    IODCIELabUtil::dicomLab2RGB(rgb[0], rgb[1], rgb[2], L, a, b);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(rgb[ch] * 255, colors[static_cast<std::size_t>(f)][static_cast<std::size_t>(ch)], 1.0) << "segment " << s + 1;
  }
  EXPECT_EQ(colors[1], (Rgb{40, 200, 90}));

  // Every frame: its segment, its CT slice (position and source image) and its pixels.
  ASSERT_EQ(seg->getNumberOfFrames(), expectedFrames.size());
  FGInterface& groups = seg->getFunctionalGroups();
  std::map<std::pair<int, std::size_t>, bool> seen;
  for (Uint32 frame = 0; frame < seg->getNumberOfFrames(); ++frame) {
    auto* segmentFg = dynamic_cast<FGSegmentation*>(groups.get(frame, DcmFGTypes::EFG_SEGMENTATION));
    auto* position = dynamic_cast<FGPlanePosPatient*>(groups.get(frame, DcmFGTypes::EFG_PLANEPOSPATIENT));
    auto* derivation = dynamic_cast<FGDerivationImage*>(groups.get(frame, DcmFGTypes::EFG_DERIVATIONIMAGE));
    ASSERT_TRUE(segmentFg && position && derivation) << "frame " << frame;
    Uint16 number = 0;
    ASSERT_TRUE(segmentFg->getReferencedSegmentNumber(number).good());
    ASSERT_GE(number, 1);
    ASSERT_LE(number, 3);
    const int f = featureOf[number - 1u];
    Float64 x = 0, y = 0, z = 0;
    ASSERT_TRUE(position->getImagePositionPatient(x, y, z).good());
    EXPECT_NEAR(x, ct_.originX, 1e-9);
    EXPECT_NEAR(y, ct_.originY, 1e-9);
    std::size_t k = 0;
    while (k < ct_.sliceZ.size() && std::abs(ct_.sliceZ[k] - z) > 1e-9) ++k;
    ASSERT_LT(k, ct_.sliceZ.size()) << "z=" << z;
    const std::pair<int, std::size_t> key{f, k};
    EXPECT_TRUE(expectedFrames.count(key)) << "frame " << frame << " is empty";
    EXPECT_FALSE(seen[key]) << "two frames for one segment and slice";
    seen[key] = true;
    ASSERT_EQ(derivation->getDerivationImageItems().size(), 1u);
    auto& sources = derivation->getDerivationImageItems()[0]->getSourceImageItems();
    ASSERT_EQ(sources.size(), 1u);
    OFString uid;
    sources[0]->getImageSOPInstanceReference().getReferencedSOPInstanceUID(uid);
    EXPECT_EQ(std::string(uid.c_str()), test::testCtInstanceUid(ct_, k));

    const DcmIODTypes::Frame* packed = seg->getFrame(frame);
    ASSERT_NE(packed, nullptr);
    std::unique_ptr<DcmIODTypes::Frame> pixels(
        DcmSegUtils::unpackBinaryFrame(packed, static_cast<Uint16>(ct_.rows), static_cast<Uint16>(ct_.columns)));
    ASSERT_TRUE(pixels && pixels->length == static_cast<std::size_t>(ct_.rows * ct_.columns));
    int differences = 0;
    for (int j = 0; j < ct_.rows; ++j)
      for (int i = 0; i < ct_.columns; ++i)
        differences +=
            (pixels->pixData[j * ct_.columns + i] != 0) != (ctVoxel(c.volume, i, j, ct_.sliceZ[k]) == labelOfFeature(f));
    EXPECT_EQ(differences, 0) << "frame " << frame << ", feature " << f << ", slice " << k;
  }
  EXPECT_EQ(seen.size(), expectedFrames.size());

  // Patient, study, frame of reference and the CT's grid; every CT image referenced.
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  DcmDataset& ds = *file.getDataset();
  auto text = [&](DcmItem& item, const DcmTagKey& tag) {
    OFString v;
    item.findAndGetOFStringArray(tag, v);
    return std::string(v.c_str());
  };
  EXPECT_EQ(text(ds, DCM_SOPClassUID), UID_SegmentationStorage);
  EXPECT_EQ(text(ds, DCM_Modality), "SEG");
  EXPECT_EQ(text(ds, DCM_PatientName), ct_.patientName);
  EXPECT_EQ(text(ds, DCM_PatientID), ct_.patientId);
  EXPECT_EQ(text(ds, DCM_StudyInstanceUID), ct_.studyUid);
  EXPECT_EQ(text(ds, DCM_FrameOfReferenceUID), ct_.frameOfReferenceUid);
  EXPECT_NE(text(ds, DCM_SeriesInstanceUID), ct_.seriesUid);
  EXPECT_EQ(text(ds, DCM_Rows), "30");
  EXPECT_EQ(text(ds, DCM_Columns), "40");
  DcmItem* shared = nullptr;
  DcmItem* measures = nullptr;
  ASSERT_TRUE(ds.findAndGetSequenceItem(DCM_SharedFunctionalGroupsSequence, shared).good());
  ASSERT_TRUE(shared->findAndGetSequenceItem(DCM_PixelMeasuresSequence, measures).good());
  EXPECT_EQ(text(*measures, DCM_PixelSpacing), "0.9\\0.8");  // row spacing \ column spacing
  EXPECT_EQ(text(*measures, DCM_SliceThickness), "2.5");
  DcmItem* series = nullptr;
  ASSERT_TRUE(ds.findAndGetSequenceItem(DCM_ReferencedSeriesSequence, series).good());
  EXPECT_EQ(text(*series, DCM_SeriesInstanceUID), ct_.seriesUid);
  DcmSequenceOfItems* instances = nullptr;
  ASSERT_TRUE(series->findAndGetSequence(DCM_ReferencedInstanceSequence, instances).good());
  ASSERT_EQ(instances->card(), ct_.sliceZ.size());
  for (unsigned long k = 0; k < instances->card(); ++k) {
    EXPECT_EQ(text(*instances->getItem(k), DCM_ReferencedSOPClassUID), UID_CTImageStorage);
    EXPECT_EQ(text(*instances->getItem(k), DCM_ReferencedSOPInstanceUID), test::testCtInstanceUid(ct_, k));
  }
}

// Names beyond ASCII: the ROI's from its ISO_IR 100 structure set, the patient's from a CT
// that declares no character set (Latin-1 bytes, read as Latin-1 with a warning); the SEG
// holds both in UTF-8 and says ISO_IR 192.
TEST_F(DicomSeg, NamesBeyondAsciiAreWrittenInUtf8) {
  ct_.patientName = "M\xFCller^Hans";
  test::writeTestCtSeries(ct_, ctDir());
  test::TestRtStruct rt = structureSet();
  rt.specificCharacterSet = "ISO_IR 100";
  rt.rois[0].name = "L\xE8vre";
  const Case c = build(rt);
  ASSERT_EQ(c.contours.features[0].name, "L\xC3\xA8vre");
  const fs::path path = dir_ / "seg.dcm";
  auto written = writeDicomSeg(path, c.contours, c.volume, ctDir());
  ASSERT_TRUE(written) << written.error().message;
  EXPECT_TRUE(std::any_of(written->warnings.begin(), written->warnings.end(),
                          [](const std::string& w) { return w.find("read as Latin-1 (ISO_IR 100)") != std::string::npos; }));
  DcmFileFormat file;
  ASSERT_TRUE(file.loadFile(path.c_str()).good());
  OFString charset, patient;
  file.getDataset()->findAndGetOFStringArray(DCM_SpecificCharacterSet, charset);
  file.getDataset()->findAndGetOFStringArray(DCM_PatientName, patient);
  EXPECT_EQ(std::string(charset.c_str()), "ISO_IR 192");
  EXPECT_EQ(std::string(patient.c_str()), "M\xC3\xBCller^Hans");
  DcmSegmentation* loaded = nullptr;
  ASSERT_TRUE(DcmSegmentation::loadFile(path.c_str(), loaded).good());
  std::unique_ptr<DcmSegmentation> seg(loaded);
  OFString label;
  ASSERT_NE(seg->getSegment(1), nullptr);
  seg->getSegment(1)->getSegmentLabel(label);
  EXPECT_EQ(std::string(label.c_str()), "L\xC3\xA8vre");
}

// dicom3tools' IOD validator finds no error (warnings about optional attributes are allowed).
TEST_F(DicomSeg, DciodvfyFindsNoError) {
  const int found = std::system("command -v dciodvfy > /dev/null 2>&1");
  if (found != 0) GTEST_SKIP() << "dciodvfy (Debian package dicom3tools) is not installed";
  const Case c = build(structureSet());
  const fs::path path = dir_ / "seg.dcm";
  ASSERT_TRUE(writeDicomSeg(path, c.contours, c.volume, ctDir()));
  const std::string command = "dciodvfy '" + path.string() + "' 2>&1";
  std::FILE* pipe = ::popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  char buffer[4096];
  for (std::size_t n; (n = std::fread(buffer, 1, sizeof buffer, pipe)) > 0;) output.append(buffer, n);
  ::pclose(pipe);
  std::printf("%s", output.c_str());
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) EXPECT_NE(line.rfind("Error", 0), 0u) << line;
  EXPECT_NE(output.find("Segmentation"), std::string::npos) << "dciodvfy recognised the IOD:\n" << output;
}

TEST_F(DicomSeg, RefusedOffTheCtLatticeOrWithoutVoxels) {
  GridOptions own;
  own.voxelSize = 1.0;
  const Case off = build(structureSet(), own);
  auto r = writeDicomSeg(dir_ / "off.dcm", off.contours, off.volume, ctDir());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidArgument);
  EXPECT_NE(r.error().message.find("not on the voxel lattice of the reference series"), std::string::npos) << r.error().message;

  test::TestRtStruct specks;
  specks.rois = {structureSet().rois[2]};
  const Case empty = build(specks);
  r = writeDicomSeg(dir_ / "empty.dcm", empty.contours, empty.volume, ctDir());
  ASSERT_FALSE(r);
  EXPECT_EQ(r.error().code, Errc::InvalidInput);
  EXPECT_NE(r.error().message.find("no feature has a voxel on the CT's grid"), std::string::npos) << r.error().message;
  EXPECT_FALSE(fs::exists(dir_ / "off.dcm"));
  EXPECT_FALSE(fs::exists(dir_ / "empty.dcm"));
}

}  // namespace
}  // namespace scansurf
