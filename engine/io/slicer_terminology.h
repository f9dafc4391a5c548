// scansurf: what each segment is, in codes: the category and type the DICOM SEG gives a segment
// (Segmented Property Category / Type Code Sequences) and 3D Slicer's files carry as terminology
// (seg.nrrd's Segment{i}_Tags, .seg.vtm's Segment_Tags), from the RTSTRUCT's RT ROI Interpreted
// Type (DICOM PS3.3 C.8.8.8): targets from CID 9534 under "RT Target" (CID 9580), EXTERNAL as an
// External Body Model (CID 9507), ORGAN and OAR as anatomical structures; anything else, and
// input that has no type, SNOMED CT 85756007 "Tissue".
#pragma once

#include <string>

namespace scansurf {

struct Code {
  const char* value;
  const char* scheme;  // "SCT" (SNOMED CT) or "DCM" (DICOM)
  const char* meaning;
};

struct SegmentTerminology {
  Code category;
  Code type;
  const char* slicerContext;  // the Slicer terminology context that lists the pair
};

SegmentTerminology terminologyOf(const std::string& interpretedType);

// Slicer's TerminologyEntry: seven '~'-separated fields, codes as scheme^value^meaning.
std::string slicerTerminology(const SegmentTerminology& t);

// The tags value: "TerminologyEntry:<entry>|" (each tag ends with '|', as Slicer parses them).
inline std::string slicerTags(const std::string& entry) { return "TerminologyEntry:" + entry + "|"; }

}  // namespace scansurf
