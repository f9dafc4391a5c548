// scansurf CLI: --list-rois and --list-objects.
#include "roi_list.h"

#include "safe_text.h"

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

Result<void> printRoiList(const std::string& path, const std::vector<std::string>& roiPatterns) {
  const InputFormat format = detectInputFormat(path);
  const bool segments = format == InputFormat::SlicerSegmentation;
  if (format != InputFormat::RtStruct && !segments && format != InputFormat::Unknown)  // Unknown: listRois says why
    return makeError(
        Errc::InvalidArgument,
        std::string("--list-rois applies to DICOM RTSTRUCT and 3D Slicer segmentation input, not to ") + inputFormatName(format) +
            " " + path +
            (format == InputFormat::ReconstructSeries || format == InputFormat::ImodModel ? " (use --list-objects)" : ""));
  SCANSURF_ASSIGN_OR_RETURN(const StructureSetInfo rt, listRois(path, roiPatterns));
  if (segments)
    std::printf("%s: 3D Slicer segmentation, %zu segments (z in mm, patient coordinates)\n", path.c_str(), rt.rois.size());
  else
    std::printf("%s: RT Structure Set \"%s\", %zu ROIs (z in mm, patient coordinates)\n", path.c_str(),
                printable(rt.label).c_str(), rt.rois.size());
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
