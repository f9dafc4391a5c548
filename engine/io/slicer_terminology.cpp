// scansurf: segment terminology from the RT ROI Interpreted Type (slicer_terminology.h).
#include "io/slicer_terminology.h"

#include <utility>

namespace scansurf {
namespace {

constexpr const char* kGeneralAnatomy = "Segmentation category and type - 3D Slicer General Anatomy list";
constexpr const char* kDicomMaster = "Segmentation category and type - DICOM master list";
constexpr Code kTissue{"85756007", "SCT", "Tissue"};
constexpr Code kAnatomicalStructure{"123037004", "SCT", "Anatomical Structure"};
constexpr Code kRtTarget{"130041", "DCM", "RT Target"};

}  // namespace

SegmentTerminology terminologyOf(const std::string& type) {
  static const std::pair<const char*, SegmentTerminology> kTable[] = {
      {"PTV", {kRtTarget, {"228793007", "SCT", "PTV"}, kDicomMaster}},
      {"CTV", {kRtTarget, {"228792002", "SCT", "CTV"}, kDicomMaster}},
      {"GTV", {kRtTarget, {"228791009", "SCT", "GTV"}, kDicomMaster}},
      {"TREATED_VOLUME", {kRtTarget, {"130059", "DCM", "Treated Volume"}, kDicomMaster}},
      {"IRRAD_VOLUME", {kRtTarget, {"228790005", "SCT", "Irradiated Volume"}, kDicomMaster}},
      {"EXTERNAL", {{"130047", "DCM", "External Body Model"}, {"130067", "DCM", "Patient Anatomy Model"}, kDicomMaster}},
      {"ORGAN", {kAnatomicalStructure, kTissue, kDicomMaster}},
      {"OAR", {kAnatomicalStructure, kTissue, kDicomMaster}},
  };
  for (const auto& [name, terminology] : kTable)
    if (type == name) return terminology;
  return {kTissue, kTissue, kGeneralAnatomy};
}

std::string slicerTerminology(const SegmentTerminology& t) {
  const auto code = [](const Code& c) { return std::string(c.scheme) + "^" + c.value + "^" + c.meaning; };
  return std::string(t.slicerContext) + "~" + code(t.category) + "~" + code(t.type) +
         "~^^~Anatomic codes - DICOM master list~^^~^^";
}

}  // namespace scansurf
