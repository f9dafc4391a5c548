// scansurf: readContours and listRois, the public entry to every contour reader.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <fstream>

#include "core/guard.h"
#include "io/contours_json.h"
#include "io/ct_series.h"
#include "io/rtstruct_reader.h"
#include "scansurf/input.h"

namespace scansurf {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string formatNumber(double z) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", z);
  return buffer;
}

// The frame of reference and referenced series must agree before the CT's lattice is used.
Result<void> checkReference(const RtStructure& rt, const CtSeries& ct, const std::string& path, const std::string& ctDir,
                            std::vector<std::string>& warnings) {
  if (!rt.frameOfReferenceUid.empty() && !ct.frameOfReferenceUid.empty() && rt.frameOfReferenceUid != ct.frameOfReferenceUid)
    return makeError(Errc::InvalidInput, path + ": frame of reference " + rt.frameOfReferenceUid +
                                             " differs from the reference series' (" + ct.frameOfReferenceUid + " in " + ctDir +
                                             "): the coordinates are not comparable");
  const auto& series = rt.referencedSeriesUids;
  if (!series.empty() && std::find(series.begin(), series.end(), ct.seriesUid) == series.end())
    warnings.push_back(path + ": the contours reference series " + series.front() + ", not " + ct.seriesUid + " (" + ctDir +
                       "); using it as the reference grid anyway");
  return {};
}

std::string describeReference(const CtSeries& ct, const std::string& ctDir) {
  const std::string line = std::to_string(ct.columns) + " x " + std::to_string(ct.rows) + " pixels of " +
                           formatNumber(ct.spacingX) + " x " + formatNumber(ct.spacingY) + " mm, " +
                           std::to_string(ct.sliceZ.size()) + " slices z " + formatNumber(ct.sliceZ.front()) + " .. " +
                           formatNumber(ct.sliceZ.back());
  return "reference " + (ct.modality.empty() ? std::string("series") : ct.modality) + " " + ctDir + ": " + line +
         "; CT voxel (i, j, k) is grid voxel (i+1, j+1, k+1) unless the contours reach beyond the CT (the grid then "
         "grows by whole CT pixels)";
}

Result<ContourSet> readStructureSet(const std::filesystem::path& path, const ReadOptions& options) {
  RtStructOptions rtOptions;
  rtOptions.roiPatterns = options.roiPatterns;
  SCANSURF_ASSIGN_OR_RETURN(RtStructure rt, readRtStruct(path, rtOptions));
  ContourSet contours = std::move(rt.contours);
  contours.warnings = std::move(rt.warnings);
  int surfaced = 0;
  for (const RoiInfo& roi : rt.rois) surfaced += roi.feature >= 0;
  contours.notes.push_back("RTSTRUCT \"" + rt.label + "\": " + std::to_string(rt.rois.size()) + " ROIs, " +
                           std::to_string(surfaced) + " with closed contours surfaced (patient LPS coordinates, mm)");
  if (options.referenceSeries.empty()) return contours;
  const std::string ctDir = options.referenceSeries.string();
  SCANSURF_ASSIGN_OR_RETURN(const CtSeries ct, readCtSeries(options.referenceSeries));
  SCANSURF_TRY(checkReference(rt, ct, path.string(), ctDir, contours.warnings));
  SCANSURF_TRY(placeOnCtSlices(contours, ct, rtOptions.sliceTolerance));
  contours.reference = gridReferenceOf(ct);
  contours.notes.push_back(describeReference(ct, ctDir));
  return contours;
}

Result<ContourSet> readAny(const std::filesystem::path& path, const ReadOptions& options) {
  if (detectInputFormat(path) == InputFormat::RtStruct) return readStructureSet(path, options);
  if (!options.roiPatterns.empty() || !options.referenceSeries.empty())
    return makeError(Errc::InvalidArgument,
                     "ROI selection and a reference series apply to DICOM RTSTRUCT input, not to " + path.string());
  return readContoursJson(path);
}

}  // namespace

InputFormat detectInputFormat(const std::filesystem::path& path) {
  if (hasDicomPreamble(path)) return InputFormat::RtStruct;
  if (lower(path.extension().string()) == ".json") return InputFormat::ContoursJson;
  std::ifstream in(path, std::ios::binary);
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
  }
  return in && c == '{' ? InputFormat::ContoursJson : InputFormat::RtStruct;
}

Result<ContourSet> readContours(const std::filesystem::path& path, const ReadOptions& options) {
  return guarded("reading " + path.string(), [&] { return readAny(path, options); });
}

Result<StructureSetInfo> listRois(const std::filesystem::path& path, const std::vector<std::string>& roiPatterns) {
  if (detectInputFormat(path) != InputFormat::RtStruct)
    return makeError(Errc::InvalidArgument, "listing ROIs applies to DICOM RTSTRUCT input, not to " + path.string());
  RtStructOptions options;
  options.roiPatterns = roiPatterns;
  options.requireFeatures = false;
  return guarded("reading " + path.string(), [&]() -> Result<StructureSetInfo> {
    SCANSURF_ASSIGN_OR_RETURN(RtStructure rt, readRtStruct(path, options));
    return StructureSetInfo{std::move(rt.label), std::move(rt.rois)};
  });
}

Result<void> writeContours(const ContourSet& contours, const std::filesystem::path& path) {
  return writeContoursJson(contours, path);
}

}  // namespace scansurf
