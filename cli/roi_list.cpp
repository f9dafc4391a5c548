// scansurf CLI: --list-rois.
#include "roi_list.h"

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
  if (detectInputFormat(path) != InputFormat::RtStruct)
    return makeError(Errc::InvalidArgument, "--list-rois applies to DICOM RTSTRUCT input, not to " + path);
  SCANSURF_ASSIGN_OR_RETURN(const StructureSetInfo rt, listRois(path, roiPatterns));
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
