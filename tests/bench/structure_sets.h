// Deterministic synthetic structure sets at clinical scale for the benchmarks (issue 6):
// "pelvis" (~30 structures, 512 x 512 pixels at ~1 mm, 200 slices at 2 mm), "head-neck"
// (~80 structures, many small beside large ones) and "em-cells" (~2000 small branching
// objects over 300 serial sections). Shapes are built from ellipsoids, tubes along paths,
// branching tubes, shells and shared chords, so nesting, abutting, holes and branching all
// occur at scale.
#pragma once

#include <string>
#include <vector>

#include "scansurf/contours.h"

namespace scansurf::bench {

struct StructureSetSpec {
  std::string name;
  ContourSet contours;
};

// The names of the available sets.
std::vector<std::string> structureSetNames();
// Builds a set by name; empty contours for an unknown name.
StructureSetSpec makeStructureSet(const std::string& name);

}  // namespace scansurf::bench
