// scansurf: the terminology 3D Slicer files carry for each segment (seg.nrrd's Segment{i}_Tags,
// .seg.vtm's Segment_Tags): SNOMED CT 85756007 "Tissue" as category and type, the codes the
// DICOM SEG gives every segment, in Slicer's TerminologyEntry form (seven '~'-separated fields,
// codes as scheme^value^meaning).
#pragma once

#include <string>

namespace scansurf {

inline std::string slicerTerminology() {
  return "Segmentation category and type - 3D Slicer General Anatomy list~SCT^85756007^Tissue~SCT^85756007^Tissue~^^~"
         "Anatomic codes - DICOM master list~^^~^^";
}

// The tags value: "TerminologyEntry:<entry>|" (each tag ends with '|', as Slicer parses them).
inline std::string slicerTags(const std::string& entry = slicerTerminology()) { return "TerminologyEntry:" + entry + "|"; }

}  // namespace scansurf
