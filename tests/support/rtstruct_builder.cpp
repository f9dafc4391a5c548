// Test helper: RT Structure Sets and CT series written with DCMTK's dcmdata.
#include "support/rtstruct_builder.h"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>

#include <stdexcept>
#include <vector>

#include "geometry/contours/validate.h"

namespace scansurf::test {

namespace {

void check(const OFCondition& c, const std::string& what) {
  if (c.bad()) throw std::runtime_error(what + ": " + c.text());
}

void put(DcmItem& item, const DcmTagKey& tag, const std::string& value) {
  check(item.putAndInsertString(tag, value.c_str()), "put " + std::string(DcmTag(tag).getTagName()));
}

DcmItem& newItem(DcmItem& parent, const DcmTagKey& sequence) {
  DcmItem* item = nullptr;
  check(parent.findOrCreateSequenceItem(sequence, item, -2), "sequence item");
  return *item;
}

std::string join(const std::vector<double>& values) {
  std::string out;
  for (double v : values) {
    if (!out.empty()) out += '\\';
    out += formatNumber(v);
  }
  return out;
}

void save(DcmFileFormat& file, const std::filesystem::path& path, bool header) {
  const std::string name = path.string();
  if (header)
    check(file.saveFile(name.c_str(), EXS_LittleEndianExplicit), "save " + name);
  else
    check(file.getDataset()->saveFile(name.c_str(), EXS_LittleEndianImplicit), "save " + name);
}

}  // namespace

TestContour closedContour(const std::vector<Point2>& points, double z) {
  TestContour c;
  for (Point2 p : points) c.points.push_back({p.x, p.y, z});
  return c;
}

TestRoi roiFromFeature(const Feature& feature, int number) {
  TestRoi roi;
  roi.number = number;
  roi.name = feature.name;
  roi.color = feature.color;
  for (const FeatureSlice& s : feature.slices)
    for (const Contour& c : s.contours) roi.contours.push_back(closedContour(c.points, s.z));
  return roi;
}

void writeTestRtStruct(const TestRtStruct& rt, const std::filesystem::path& path) {
  DcmFileFormat file;
  DcmDataset& ds = *file.getDataset();
  if (!rt.specificCharacterSet.empty()) put(ds, DCM_SpecificCharacterSet, rt.specificCharacterSet);
  if (!rt.sopClassUid.empty()) put(ds, DCM_SOPClassUID, rt.sopClassUid);
  put(ds, DCM_SOPInstanceUID, "1.2.826.0.1.3680043.2.1125.9.3");
  if (!rt.modality.empty()) put(ds, DCM_Modality, rt.modality);
  put(ds, DCM_PatientName, "Test^Phantom");
  put(ds, DCM_StructureSetLabel, "scansurf test");
  DcmItem& frame = newItem(ds, DCM_ReferencedFrameOfReferenceSequence);
  put(frame, DCM_FrameOfReferenceUID, rt.frameOfReferenceUid);
  DcmItem& study = newItem(frame, DCM_RTReferencedStudySequence);
  put(study, DCM_ReferencedSOPClassUID, UID_RETIRED_DetachedStudyManagementSOPClass);
  put(study, DCM_ReferencedSOPInstanceUID, "1.2.826.0.1.3680043.2.1125.9.4");
  DcmItem& series = newItem(study, DCM_RTReferencedSeriesSequence);
  put(series, DCM_SeriesInstanceUID, rt.referencedSeriesUid);

  for (const TestRoi& roi : rt.rois) {
    if (rt.structureSetRoiSequence) {
      DcmItem& item = newItem(ds, DCM_StructureSetROISequence);
      if (roi.writeNumber) put(item, DCM_ROINumber, std::to_string(roi.number));
      put(item, DCM_ReferencedFrameOfReferenceUID, rt.frameOfReferenceUid);
      put(item, DCM_ROIName, roi.name);
      put(item, DCM_ROIGenerationAlgorithm, "MANUAL");
    }
    if (rt.roiContourSequence && roi.contourItem) {
      DcmItem& item = newItem(ds, DCM_ROIContourSequence);
      put(item, DCM_ReferencedROINumber, std::to_string(roi.number));
      if (roi.color)
        put(item, DCM_ROIDisplayColor, join({double((*roi.color)[0]), double((*roi.color)[1]), double((*roi.color)[2])}));
      int number = 0;
      for (const TestContour& c : roi.contours) {
        DcmItem& contour = newItem(item, DCM_ContourSequence);
        put(contour, DCM_ContourGeometricType, c.type);
        put(contour, DCM_NumberOfContourPoints, std::to_string(c.points.size()));
        put(contour, DCM_ContourNumber, std::to_string(++number));
        if (c.rawData) {
          put(contour, DCM_ContourData, *c.rawData);
        } else if (!c.points.empty()) {
          std::vector<double> values;
          for (const auto& p : c.points) values.insert(values.end(), p.begin(), p.end());
          put(contour, DCM_ContourData, join(values));
        }
      }
    }
    DcmItem& obs = newItem(ds, DCM_RTROIObservationsSequence);
    put(obs, DCM_ObservationNumber, std::to_string(roi.number));
    put(obs, DCM_ReferencedROINumber, std::to_string(roi.number));
    put(obs, DCM_RTROIInterpretedType, roi.interpretedType);
  }
  // An empty sequence still has to exist when asked for (a structure set with no ROIs).
  if (rt.structureSetRoiSequence && !ds.tagExists(DCM_StructureSetROISequence))
    check(ds.insertEmptyElement(DCM_StructureSetROISequence), "empty sequence");
  if (rt.roiContourSequence && !ds.tagExists(DCM_ROIContourSequence))
    check(ds.insertEmptyElement(DCM_ROIContourSequence), "empty sequence");
  save(file, path, rt.fileHeader);
}

std::string testCtInstanceUid(const TestCt& ct, std::size_t k) {
  // Distinct per series: the last component of the series UID, then the image number.
  const std::string series = ct.seriesUid.substr(ct.seriesUid.rfind('.') + 1);
  return "1.2.826.0.1.3680043.2.1125.9.10." + series + "." + std::to_string(k + 1);
}

void writeTestCtSeries(const TestCt& ct, const std::filesystem::path& directory) {
  std::filesystem::create_directories(directory);
  for (std::size_t k = 0; k < ct.sliceZ.size(); ++k) {
    DcmFileFormat file;
    DcmDataset& ds = *file.getDataset();
    put(ds, DCM_SOPClassUID, UID_CTImageStorage);
    put(ds, DCM_SOPInstanceUID, testCtInstanceUid(ct, k));
    put(ds, DCM_Modality, "CT");
    put(ds, DCM_PatientName, ct.patientName);
    put(ds, DCM_PatientID, ct.patientId);
    put(ds, DCM_PatientBirthDate, "");
    put(ds, DCM_PatientSex, "O");
    put(ds, DCM_StudyInstanceUID, ct.studyUid);
    put(ds, DCM_StudyDate, "20240101");
    put(ds, DCM_StudyTime, "120000");
    put(ds, DCM_ReferringPhysicianName, "");
    put(ds, DCM_StudyID, "1");
    put(ds, DCM_AccessionNumber, "");
    put(ds, DCM_SeriesInstanceUID, ct.seriesUid);
    put(ds, DCM_SeriesNumber, "2");
    put(ds, DCM_FrameOfReferenceUID, ct.frameOfReferenceUid);
    put(ds, DCM_PositionReferenceIndicator, "");
    put(ds, DCM_Manufacturer, "scansurf tests");
    put(ds, DCM_InstanceNumber, std::to_string(k + 1));
    put(ds, DCM_ImageType, "ORIGINAL\\PRIMARY\\AXIAL");
    put(ds, DCM_KVP, "120");
    put(ds, DCM_AcquisitionNumber, "1");
    put(ds, DCM_RescaleIntercept, "0");
    put(ds, DCM_RescaleSlope, "1");
    if (ct.sliceThickness > 0) put(ds, DCM_SliceThickness, formatNumber(ct.sliceThickness));
    put(ds, DCM_ImagePositionPatient, join({ct.originX, ct.originY, ct.sliceZ[k]}));
    put(ds, DCM_ImageOrientationPatient, join(std::vector<double>(ct.orientation.begin(), ct.orientation.end())));
    put(ds, DCM_PixelSpacing, join({ct.spacingY, ct.spacingX}));
    check(ds.putAndInsertUint16(DCM_Rows, static_cast<Uint16>(ct.rows)), "rows");
    check(ds.putAndInsertUint16(DCM_Columns, static_cast<Uint16>(ct.columns)), "columns");
    check(ds.putAndInsertUint16(DCM_BitsAllocated, 16), "bits");
    check(ds.putAndInsertUint16(DCM_BitsStored, 16), "bits");
    check(ds.putAndInsertUint16(DCM_HighBit, 15), "bits");
    check(ds.putAndInsertUint16(DCM_PixelRepresentation, 1), "repr");
    check(ds.putAndInsertUint16(DCM_SamplesPerPixel, 1), "samples");
    put(ds, DCM_PhotometricInterpretation, "MONOCHROME2");
    std::vector<Uint16> pixels(static_cast<std::size_t>(ct.rows) * static_cast<std::size_t>(ct.columns), 0);
    check(ds.putAndInsertUint16Array(DCM_PixelData, pixels.data(), static_cast<unsigned long>(pixels.size())), "pixels");
    save(file, directory / ("ct_" + std::to_string(k) + ".dcm"), true);
  }
}

}  // namespace scansurf::test
