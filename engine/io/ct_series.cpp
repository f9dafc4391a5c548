// scansurf: CT series geometry (DICOM PS3.3 C.7.6.2 Image Plane Module) for --reference.
#include "io/ct_series.h"

#include <dcmtk/dcmdata/dcdeftag.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "geometry/contours/validate.h"
#include "io/dicom_common.h"
#include "io/rtstruct_reader.h"

namespace scansurf {

namespace {

Unexpected invalid(std::string message) { return makeError(Errc::InvalidInput, std::move(message)); }

// Orientation, position and spacing values agree within this (DS values carry ~6 digits).
constexpr double kGeometryTolerance = 1e-3;

struct Image {
  std::string file;
  std::string seriesUid, frameUid, modality;
  std::string sopClassUid, sopInstanceUid;
  int rows = 0, columns = 0;
  double position[3] = {0, 0, 0};
  double spacing[2] = {0, 0};  // row spacing (y), column spacing (x)
  double thickness = 0;        // Slice Thickness, 0 when absent
};

Result<double> getDouble(DcmDataset& ds, const DcmTagKey& tag, unsigned long pos, const std::string& file, const char* name) {
  Float64 v = 0;
  if (ds.findAndGetFloat64(tag, v, pos).bad()) return invalid(file + ": missing or malformed " + std::string(name));
  if (!std::isfinite(v)) return invalid(file + ": non-finite value in " + std::string(name));
  return static_cast<double>(v);
}

// The files of the folder, sorted by name.
Result<std::vector<std::filesystem::path>> filesOf(const std::filesystem::path& directory) {
  const std::string dir = directory.string();
  std::error_code ec;
  if (!std::filesystem::is_directory(directory, ec))
    return makeError(Errc::Io, dir + ": not a directory (the reference is the folder of a CT series)");
  std::vector<std::filesystem::path> paths;
  for (const auto& entry : std::filesystem::directory_iterator(directory, ec))
    if (entry.is_regular_file()) paths.push_back(entry.path());
  if (ec) return makeError(Errc::Io, dir + ": cannot list the directory: " + ec.message());
  std::sort(paths.begin(), paths.end());
  return paths;
}

// Only axial images with rows along +x and columns along +y.
Result<void> checkAxial(DcmDataset& ds, const std::string& file) {
  double orientation[6];
  for (unsigned long i = 0; i < 6; ++i) {
    SCANSURF_ASSIGN_OR_RETURN(orientation[i],
                              getDouble(ds, DCM_ImageOrientationPatient, i, file, "Image Orientation (Patient) (0020,0037)"));
  }
  static constexpr double kAxial[6] = {1, 0, 0, 0, 1, 0};
  for (int i = 0; i < 6; ++i)
    if (std::abs(orientation[i] - kAxial[i]) > kGeometryTolerance) {
      std::string values;
      for (int k = 0; k < 6; ++k) values += (k ? "\\" : "") + formatNumber(orientation[k]);
      return invalid(file + ": Image Orientation (Patient) is " + values +
                     "; only axial images with rows along +x and columns along +y (1\\0\\0\\0\\1\\0) are supported");
    }
  return {};
}

// One image's identity and geometry, checked.
Result<Image> imageOf(DcmDataset& ds, const std::filesystem::path& path) {
  Image image;
  image.file = path.string();
  const std::string& file = image.file;
  OFString text;
  if (ds.findAndGetOFString(DCM_SeriesInstanceUID, text).good()) image.seriesUid = text.c_str();
  if (ds.findAndGetOFString(DCM_FrameOfReferenceUID, text).good()) image.frameUid = text.c_str();
  if (ds.findAndGetOFString(DCM_Modality, text).good()) image.modality = text.c_str();
  if (ds.findAndGetOFString(DCM_SOPClassUID, text).good()) image.sopClassUid = text.c_str();
  if (ds.findAndGetOFString(DCM_SOPInstanceUID, text).good()) image.sopInstanceUid = text.c_str();
  if (image.sopInstanceUid.empty()) return invalid(file + ": missing SOP Instance UID (0008,0018)");
  Uint16 rows = 0, columns = 0;
  if (ds.findAndGetUint16(DCM_Rows, rows).bad() || rows == 0) return invalid(file + ": missing Rows (0028,0010)");
  if (ds.findAndGetUint16(DCM_Columns, columns).bad() || columns == 0) return invalid(file + ": missing Columns (0028,0011)");
  image.rows = rows;
  image.columns = columns;
  for (unsigned long i = 0; i < 3; ++i) {
    SCANSURF_ASSIGN_OR_RETURN(image.position[i],
                              getDouble(ds, DCM_ImagePositionPatient, i, file, "Image Position (Patient) (0020,0032)"));
    if (std::abs(image.position[i]) > kMaxCoordinate)
      return invalid(file + ": Image Position (Patient) (0020,0032) value " + formatNumber(image.position[i]) + " is beyond " +
                     formatNumber(kMaxCoordinate) + " mm from the origin");
  }
  for (unsigned long i = 0; i < 2; ++i) {
    SCANSURF_ASSIGN_OR_RETURN(image.spacing[i], getDouble(ds, DCM_PixelSpacing, i, file, "Pixel Spacing (0028,0030)"));
    if (!(image.spacing[i] > 0)) return invalid(file + ": Pixel Spacing (0028,0030) is not positive");
  }
  if (Float64 t = 0; ds.findAndGetFloat64(DCM_SliceThickness, t).good() && std::isfinite(t) && t > 0) image.thickness = t;
  SCANSURF_TRY(checkAxial(ds, file));
  return image;
}

// The images of the folder: files that start like DICOM and carry a position in space (not an
// RTSTRUCT beside them); other files are passed over unparsed (a 1 GiB file of zeros cost
// DCMTK a minute of empty elements).
Result<std::vector<Image>> imagesOf(const std::vector<std::filesystem::path>& paths) {
  std::vector<Image> images;
  for (const auto& path : paths) {
    if (!hasDicomPreamble(path) && !looksLikeDicomDataSet(path)) continue;
    auto dicom = loadDicomFile(path, /*stopAtPixelData=*/true);
    if (!dicom) {
      if (dicom.error().code == Errc::InvalidInput) continue;  // not DICOM: not part of the series
      return std::move(dicom).takeError();
    }
    DcmDataset& ds = dicom->dataset();
    if (!ds.tagExists(DCM_ImagePositionPatient) && !ds.tagExists(DCM_PixelData)) continue;
    SCANSURF_ASSIGN_OR_RETURN(Image image, imageOf(ds, path));
    images.push_back(std::move(image));
  }
  return images;
}

// One series, one lattice: the same size, spacing and x, y position in every image.
Result<void> checkOneLattice(const std::vector<Image>& images, const std::string& dir) {
  const Image& first = images.front();
  auto differs = [](double a, double b) { return std::abs(a - b) > kGeometryTolerance; };
  for (const Image& image : images) {
    if (image.seriesUid != first.seriesUid)
      return invalid(dir + ": holds more than one series (" + first.seriesUid + " in " + first.file + ", " + image.seriesUid +
                     " in " + image.file + "); give a folder with one series");
    if (image.rows != first.rows || image.columns != first.columns)
      return invalid(image.file + ": " + std::to_string(image.columns) + " x " + std::to_string(image.rows) + " pixels, unlike " +
                     first.file + " (" + std::to_string(first.columns) + " x " + std::to_string(first.rows) + ")");
    if (differs(image.spacing[0], first.spacing[0]) || differs(image.spacing[1], first.spacing[1]))
      return invalid(image.file + ": Pixel Spacing differs from " + first.file + "'s");
    if (differs(image.position[0], first.position[0]) || differs(image.position[1], first.position[1]))
      return invalid(image.file + ": Image Position (Patient) x, y (" + formatNumber(image.position[0]) + ", " +
                     formatNumber(image.position[1]) + ") differ from " + first.file + "'s (" + formatNumber(first.position[0]) +
                     ", " + formatNumber(first.position[1]) + "); the slices must stack straight");
  }
  return {};
}

// Sorted by z, no two at one z, no SOP Instance UID twice.
Result<void> stackSlices(std::vector<Image>& images) {
  std::stable_sort(images.begin(), images.end(), [](const Image& a, const Image& b) { return a.position[2] < b.position[2]; });
  for (std::size_t i = 1; i < images.size(); ++i)
    if (images[i].position[2] - images[i - 1].position[2] <= kGeometryTolerance)
      return invalid(images[i].file + ": at z=" + formatNumber(images[i].position[2]) + " like " + images[i - 1].file);
  std::map<std::string, const Image*> byUid;
  for (const Image& image : images)
    if (const auto [at, added] = byUid.emplace(image.sopInstanceUid, &image); !added)
      return invalid(image.file + ": SOP Instance UID " + image.sopInstanceUid + " is also that of " + at->second->file);
  return {};
}

CtSeries seriesOf(const std::vector<Image>& images, const std::string& dir) {
  const Image& first = images.front();
  CtSeries ct;
  ct.directory = dir;
  ct.seriesUid = first.seriesUid;
  ct.frameOfReferenceUid = first.frameUid;
  ct.modality = first.modality;
  ct.columns = first.columns;
  ct.rows = first.rows;
  ct.spacingX = first.spacing[1];
  ct.spacingY = first.spacing[0];
  ct.originX = first.position[0];
  ct.originY = first.position[1];
  ct.sliceThickness = first.thickness;
  for (const Image& image : images) {
    ct.sliceZ.push_back(image.position[2]);
    ct.files.push_back(image.file);
    ct.sopClassUids.push_back(image.sopClassUid);
    ct.sopInstanceUids.push_back(image.sopInstanceUid);
  }
  return ct;
}

}  // namespace

Result<CtSeries> readCtSeries(const std::filesystem::path& directory) {
  const std::string dir = directory.string();
  SCANSURF_ASSIGN_OR_RETURN(const std::vector<std::filesystem::path> paths, filesOf(directory));
  SCANSURF_ASSIGN_OR_RETURN(std::vector<Image> images, imagesOf(paths));
  if (images.empty()) return invalid(dir + ": no DICOM images (files with Image Position (Patient)) in the directory");
  SCANSURF_TRY(checkOneLattice(images, dir));
  SCANSURF_TRY(stackSlices(images));
  return seriesOf(images, dir);
}

GridReference gridReferenceOf(const CtSeries& ct) {
  GridReference ref;
  ref.originX = ct.originX;
  ref.originY = ct.originY;
  ref.spacingX = ct.spacingX;
  ref.spacingY = ct.spacingY;
  ref.nx = ct.columns;
  ref.ny = ct.rows;
  ref.sliceZ = ct.sliceZ;
  return ref;
}

namespace {

// Whether the series has a slice missing at z: z lies beyond its first or last slice, or in a
// gap between two slices wider than 1.5 times its spacing (or the series is one slice). The
// spacing is its Slice Thickness where given, else its smallest gap: a series of two or three
// slices has no usual gap.
bool missingSliceAt(const CtSeries& ct, double z) {
  const std::vector<double>& zs = ct.sliceZ;
  if (zs.size() < 2 || z < zs.front() || z > zs.back()) return true;
  double spacing = zs[1] - zs[0];
  for (std::size_t k = 2; k < zs.size(); ++k) spacing = std::min(spacing, zs[k] - zs[k - 1]);
  if (ct.sliceThickness > 0) spacing = std::min(spacing, ct.sliceThickness);
  const auto it = std::lower_bound(zs.begin(), zs.end(), z);
  return *it - *(it - 1) > 1.5 * spacing;
}

}  // namespace

Result<std::vector<double>> placeOnCtSlices(ContourSet& contours, const CtSeries& ct, double tolerance) {
  const auto& zs = ct.sliceZ;
  std::vector<double> off;
  for (int f = 0; f < static_cast<int>(contours.features.size()); ++f) {
    for (int s = 0; s < static_cast<int>(contours.features[f].slices.size()); ++s) {
      FeatureSlice& slice = contours.features[f].slices[s];
      const auto it = std::lower_bound(zs.begin(), zs.end(), slice.z);
      double nearest = it == zs.end() ? zs.back() : *it;
      if (it != zs.begin() && std::abs(*(it - 1) - slice.z) < std::abs(nearest - slice.z)) nearest = *(it - 1);
      if (std::abs(nearest - slice.z) <= tolerance) {
        slice.z = nearest;
      } else if (missingSliceAt(ct, slice.z)) {  // a partial series: the plane keeps its own z,
        const auto same = std::find_if(off.begin(), off.end(), [&](double o) { return std::abs(o - slice.z) <= tolerance; });
        if (same != off.end())
          slice.z = *same;  // shared with the other structures drawn on it
        else
          off.push_back(slice.z);
      } else {
        return invalid(describeSlice(contours, f, s, slice.z) + ": not on a slice of the reference series " + ct.directory +
                       " (nearest z=" + formatNumber(nearest) + ", " + std::to_string(zs.size()) +
                       " slices from z=" + formatNumber(zs.front()) + " to " + formatNumber(zs.back()) + ")");
      }
    }
  }
  std::sort(off.begin(), off.end());
  off.erase(std::unique(off.begin(), off.end()), off.end());
  return off;
}

}  // namespace scansurf
