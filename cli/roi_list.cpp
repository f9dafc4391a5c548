// scansurf CLI: --list-rois and --list-objects.
#include "roi_list.h"

#include "safe_text.h"

#include <algorithm>
#include <cstdio>

#include "scansurf/input.h"

namespace scansurf::cli {

namespace {

std::string formatZ(double z) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", z);
  return buffer;
}

}  // namespace

// A 3D Slicer segmentation's segments, as the RTSTRUCT listing gives ROIs: each one's contours,
// planes and z range, and whether the patterns select it (one that matches none is an error).
Result<void> printSegmentList(const std::string& path, const std::vector<std::string>& roiPatterns) {
  SCANSURF_ASSIGN_OR_RETURN(const ContourSet all, readContours(path));
  ReadOptions options;
  options.roiPatterns = roiPatterns;
  SCANSURF_ASSIGN_OR_RETURN(const ContourSet chosen, readContours(path, options));
  std::printf("%s: 3D Slicer segmentation, %zu segments (z in %s, patient coordinates)\n", path.c_str(), all.features.size(),
              printable(all.units).c_str());
  std::printf("  %6s  %-24s %9s %9s  %-20s %s\n", "index", "name", "contours", "slices", "z range", "selected");
  for (std::size_t i = 0; i < all.features.size(); ++i) {
    const Feature& f = all.features[i];
    std::size_t contours = 0;
    for (const FeatureSlice& slice : f.slices) contours += slice.contours.size();
    const std::string range = f.slices.empty() ? "-" : formatZ(f.slices.front().z) + " .. " + formatZ(f.slices.back().z);
    const bool selected =
        std::any_of(chosen.features.begin(), chosen.features.end(), [&](const Feature& c) { return c.name == f.name; });
    std::printf("  %6zu  %-24s %9zu %9zu  %-20s %s\n", i + 1, printable(f.name).c_str(), contours, f.slices.size(), range.c_str(),
                selected ? "yes" : "no");
  }
  return {};
}

Result<void> printRoiList(const std::string& path, const std::vector<std::string>& roiPatterns) {
  const InputFormat format = detectInputFormat(path);
  if (format == InputFormat::SlicerSegmentation) return printSegmentList(path, roiPatterns);
  if (format != InputFormat::RtStruct && format != InputFormat::Unknown)  // Unknown: listRois says why
    return makeError(
        Errc::InvalidArgument,
        std::string("--list-rois applies to DICOM RTSTRUCT and 3D Slicer segmentation input, not to ") + inputFormatName(format) +
            " " + path +
            (format == InputFormat::ReconstructSeries || format == InputFormat::ImodModel ? " (use --list-objects)" : ""));
  SCANSURF_ASSIGN_OR_RETURN(const StructureSetInfo rt, listRois(path, roiPatterns));
  std::printf("%s: RT Structure Set \"%s\", %zu ROIs (z in mm, patient coordinates)\n", path.c_str(), printable(rt.label).c_str(),
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
    std::printf("  %6d  %-24s %-12s %-28s %6d  %-20s %s\n", roi.number, printable(roi.name).c_str(),
                roi.interpretedType.empty() ? std::string("-").c_str() : printable(roi.interpretedType).c_str(), contours.c_str(),
                roi.slices, range.c_str(), roi.selected ? (roi.feature >= 0 ? "yes" : "yes (nothing to surface)") : "no");
  }
  return {};
}

Result<void> printObjectList(const std::string& path, const std::vector<std::string>& objectPatterns) {
  const InputFormat format = detectInputFormat(path);
  if (format == InputFormat::RtStruct || format == InputFormat::ContoursJson)
    return makeError(Errc::InvalidArgument, std::string("--list-objects applies to Reconstruct and IMOD input, not to ") +
                                                inputFormatName(format) + " " + path +
                                                (format == InputFormat::RtStruct ? " (use --list-rois)" : ""));
  SCANSURF_ASSIGN_OR_RETURN(const ObjectListing listing, listObjects(path, objectPatterns));
  for (const std::string& w : listing.warnings) std::fprintf(stderr, "scansurf: warning: %s\n", printable(w).c_str());
  const char* planes = listing.format == InputFormat::ReconstructSeries ? "sections" : "slices";
  std::printf("%s: %s, %zu objects (x, y, z in %s)\n", path.c_str(), printable(listing.description).c_str(),
              listing.objects.size(), printable(listing.units).c_str());
  std::printf("  %6s  %-24s %9s %9s %9s  %-20s %s\n", "number", "name", "contours", "skipped", planes, "z range", "selected");
  for (const ObjectInfo& object : listing.objects) {
    const std::string range = object.slices > 0 ? formatZ(object.zMin) + " .. " + formatZ(object.zMax) : "-";
    std::printf("  %6d  %-24s %9d %9d %9d  %-20s %s\n", object.number, printable(object.name).c_str(), object.contours,
                object.skipped, object.slices, range.c_str(),
                object.selected ? (object.feature >= 0 ? "yes" : "yes (nothing to surface)") : "no");
  }
  return {};
}

}  // namespace scansurf::cli
