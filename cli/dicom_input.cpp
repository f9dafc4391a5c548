// scansurf CLI: input readers, ROI listing and the reference CT.
#include "dicom_input.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "io/contours_json.h"
#include "io/ct_series.h"
#include "io/rtstruct_reader.h"

namespace scansurf::cli {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string formatZ(double z) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", z);
  return buffer;
}

}  // namespace

bool isDicomInput(const std::string& path) {
  if (hasDicomPreamble(path)) return true;
  if (lower(std::filesystem::path(path).extension().string()) == ".json") return false;
  std::ifstream in(path, std::ios::binary);
  char c = 0;
  while (in.get(c) && std::isspace(static_cast<unsigned char>(c))) {
  }
  return !(in && c == '{');
}

Result<Input> readInput(const std::string& path, const InputOptions& options) {
  Input input;
  input.dicom = isDicomInput(path);
  if (!input.dicom) {
    if (!options.roiPatterns.empty() || !options.reference.empty())
      return makeError(Errc::InvalidArgument, "--roi and --reference apply to DICOM RTSTRUCT input, not to " + path);
    SCANSURF_ASSIGN_OR_RETURN(input.contours, readContoursJson(path));
    return input;
  }
  RtStructOptions rtOptions;
  rtOptions.roiPatterns = options.roiPatterns;
  SCANSURF_ASSIGN_OR_RETURN(RtStructure rt, readRtStruct(path, rtOptions));
  input.warnings = std::move(rt.warnings);
  int withContours = 0;
  for (const RoiInfo& roi : rt.rois) withContours += roi.feature >= 0;
  input.notes.push_back("RTSTRUCT \"" + rt.label + "\": " + std::to_string(rt.rois.size()) + " ROIs, " +
                        std::to_string(withContours) + " with closed contours surfaced (patient LPS coordinates, mm)");
  if (!options.reference.empty()) {
    SCANSURF_ASSIGN_OR_RETURN(const CtSeries ct, readCtSeries(options.reference));
    if (!rt.frameOfReferenceUid.empty() && !ct.frameOfReferenceUid.empty() && rt.frameOfReferenceUid != ct.frameOfReferenceUid)
      return makeError(Errc::InvalidInput, path + ": frame of reference " + rt.frameOfReferenceUid +
                                               " differs from the reference series' (" + ct.frameOfReferenceUid + " in " +
                                               options.reference + "): the coordinates are not comparable");
    if (!rt.referencedSeriesUids.empty() &&
        std::find(rt.referencedSeriesUids.begin(), rt.referencedSeriesUids.end(), ct.seriesUid) == rt.referencedSeriesUids.end())
      input.warnings.push_back(path + ": the contours reference series " + rt.referencedSeriesUids.front() + ", not " +
                               ct.seriesUid + " (" + options.reference + "); using it as the reference grid anyway");
    SCANSURF_TRY(placeOnCtSlices(rt.contours, ct, rtOptions.sliceTolerance));
    input.reference = gridReferenceOf(ct);
    char line[256];
    std::snprintf(line, sizeof line, "%d x %d pixels of %g x %g mm, %zu slices z %s .. %s", ct.columns, ct.rows, ct.spacingX,
                  ct.spacingY, ct.sliceZ.size(), formatZ(ct.sliceZ.front()).c_str(), formatZ(ct.sliceZ.back()).c_str());
    input.notes.push_back("reference " + (ct.modality.empty() ? std::string("series") : ct.modality) + " " + options.reference +
                          ": " + line + "; CT voxel (i, j, k) is grid voxel (i+1, j+1, k+1) unless the contours reach "
                          "beyond the CT (the grid then grows by whole CT pixels)");
  }
  input.contours = std::move(rt.contours);
  return input;
}

Result<void> printRoiList(const std::string& path, const std::vector<std::string>& roiPatterns) {
  if (!isDicomInput(path))
    return makeError(Errc::InvalidArgument, "--list-rois applies to DICOM RTSTRUCT input, not to " + path);
  RtStructOptions options;
  options.roiPatterns = roiPatterns;
  options.requireFeatures = false;
  SCANSURF_ASSIGN_OR_RETURN(const RtStructure rt, readRtStruct(path, options));
  std::printf("%s: RT Structure Set \"%s\", %zu ROIs (z in mm, patient coordinates)\n", path.c_str(), rt.label.c_str(),
              rt.rois.size());
  std::printf("  %6s  %-24s %-12s %-28s %6s  %-20s %s\n", "number", "name", "type", "contours", "slices", "z range", "selected");
  for (const RoiInfo& roi : rt.rois) {
    std::string contours;
    int total = 0;
    for (const auto& [type, count] : roi.contoursByType) {
      contours += (contours.empty() ? "" : ", ") + std::to_string(count) + " " + type;
      total += count;
    }
    if (contours.empty()) contours = "none";
    const std::string range = total > 0 ? formatZ(roi.zMin) + " .. " + formatZ(roi.zMax) : "-";
    std::printf("  %6d  %-24s %-12s %-28s %6d  %-20s %s\n", roi.number, roi.name.c_str(),
                roi.interpretedType.empty() ? "-" : roi.interpretedType.c_str(), contours.c_str(), roi.slices, range.c_str(),
                roi.selected ? (roi.feature >= 0 ? "yes" : "yes (nothing to surface)") : "no");
  }
  return {};
}

}  // namespace scansurf::cli
