// Writers of electron-microscopy tracing files for the tests: Reconstruct series (XML series
// and section files, as Reconstruct 1.1 writes them) and IMOD binary models (V1.2). Each
// writes the format from its documentation, independently of scansurf's readers.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/contours.h"

namespace scansurf::test {

// ------------------------------------------------------------------------------ Reconstruct

struct TestTrace {
  std::string name;
  std::vector<Point2> points;  // section coordinates (series units): the writer stores T(p)
  bool closed = true;
  bool hidden = false;
  std::array<double, 3> border{1, 0, 0};  // 0..1
};

struct TestTransform {
  int dim = 0;
  std::array<double, 6> xcoef{0, 1, 0, 0, 0, 0};
  std::array<double, 6> ycoef{0, 0, 1, 0, 0, 0};
  std::vector<TestTrace> traces;
  // An image transform: <Image> plus its domain outline "domain1" (image pixels, mag 0.002);
  // traces are then ignored.
  bool image = false;
};

struct TestSection {
  int index = 1;
  double thickness = 0.05;
  std::vector<TestTransform> transforms;
};

struct TestSeries {
  std::string name = "series";
  std::string units = "microns";
  bool zMidSection = false;
  bool writeSeriesFile = true;
  std::vector<TestSection> sections;
};

// Reconstruct's forward mapping of a Transform (its Nform::X and Nform::Y per dim), for
// writing: a section point p is stored as forward(p).
Point2 reconstructForward(int dim, const std::array<double, 6>& a, const std::array<double, 6>& b, Point2 p);

// Writes dir/NAME.ser (unless !writeSeriesFile) and dir/NAME.<index> per section.
void writeReconstructSeries(const TestSeries& series, const std::filesystem::path& dir);

// ------------------------------------------------------------------------------------ IMOD

struct TestImodContour {
  std::vector<std::array<float, 3>> points;  // image pixels; z = section
  std::uint32_t flags = 0;                   // bit 3: open
};

struct TestImodObject {
  std::string name;
  std::uint32_t flags = 0;  // bit 3: open object; bit 9: scattered points
  std::array<float, 3> color{0, 1, 0};
  std::vector<TestImodContour> contours;
  bool mesh = false;      // append a MESH chunk (3 vertices, one triangle)
  bool material = false;  // append an IMAT chunk
};

struct TestImodModel {
  std::string name = "test model";
  float pixelSize = 1;
  int units = 0;  // 0 pixels, -6 microns, -9 nm, ...
  std::array<float, 3> scale{1, 1, 1};
  std::vector<TestImodObject> objects;
  bool unknownChunks = false;  // a "ZZZZ" chunk after the first object and a MINX chunk at the end
};

std::string imodModelBytes(const TestImodModel& model);
void writeImodModel(const TestImodModel& model, const std::filesystem::path& path);
void writeBytes(const std::string& bytes, const std::filesystem::path& path);

}  // namespace scansurf::test
