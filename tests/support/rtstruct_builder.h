// Test helper: writes RT Structure Sets and CT series with DCMTK (dcmdata), including
// deliberately malformed ones, so the readers can be tested on files built in the test.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "scansurf/contours.h"

namespace scansurf::test {

struct TestContour {
  std::string type = "CLOSED_PLANAR";
  std::vector<std::array<double, 3>> points;  // x, y, z (mm, patient LPS)
  std::optional<std::string> rawData;         // when set, written verbatim as Contour Data
                                              // (no points and no rawData: no Contour Data)
};

struct TestRoi {
  int number = 1;
  std::string name;
  std::string interpretedType = "ORGAN";
  std::optional<Rgb> color;
  std::vector<TestContour> contours;
  bool contourItem = true;  // write an ROI Contour Sequence item for it
  bool writeNumber = true;  // write ROI Number in the Structure Set ROI Sequence
};

struct TestRtStruct {
  std::vector<TestRoi> rois;
  bool fileHeader = true;                                     // DICOM Part 10 preamble and meta header
  std::string sopClassUid = "1.2.840.10008.5.1.4.1.1.481.3";  // RT Structure Set Storage
  std::string modality = "RTSTRUCT";
  bool structureSetRoiSequence = true;
  bool roiContourSequence = true;
  std::string frameOfReferenceUid = "1.2.826.0.1.3680043.2.1125.9.1";
  std::string referencedSeriesUid = "1.2.826.0.1.3680043.2.1125.9.2";
  std::string specificCharacterSet;  // (0008,0005), written when not empty; names are its bytes
};

// Writes the structure set; throws std::runtime_error when DCMTK cannot write.
void writeTestRtStruct(const TestRtStruct& rt, const std::filesystem::path& path);

struct TestCt {
  int columns = 32;
  int rows = 32;
  double spacingX = 1;
  double spacingY = 1;
  double originX = 0;
  double originY = 0;
  std::vector<double> sliceZ;
  std::array<double, 6> orientation{1, 0, 0, 0, 1, 0};
  std::string seriesUid = "1.2.826.0.1.3680043.2.1125.9.2";
  std::string frameOfReferenceUid = "1.2.826.0.1.3680043.2.1125.9.1";
  // Patient, study and series attributes a derived object (a DICOM SEG) copies.
  std::string patientName = "Test^Phantom";
  std::string patientId = "SCANSURF-TEST";
  std::string studyUid = "1.2.826.0.1.3680043.2.1125.9.4";
  double sliceThickness = 0;  // 0: not written
};

// The SOP Instance UID writeTestCtSeries gives image k (0-based) of a series.
std::string testCtInstanceUid(const TestCt& ct, std::size_t k);

// Writes one CT image file per slice (zero pixels) into directory, named ct_<k>.dcm, with the
// attributes of the CT Image IOD's mandatory modules (patient, study, series, frame of
// reference, equipment, image plane, image pixel, CT image, SOP common).
void writeTestCtSeries(const TestCt& ct, const std::filesystem::path& directory);

// A closed contour from (x, y) points on plane z.
TestContour closedContour(const std::vector<Point2>& points, double z);
// The contours of one feature of a contour set, as CLOSED_PLANAR contours.
TestRoi roiFromFeature(const Feature& feature, int number);

}  // namespace scansurf::test
