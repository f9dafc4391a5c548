// scansurf CLI: writing every output of a run, all or nothing.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scansurf/contours.h"
#include "scansurf/result.h"
#include "scansurf/surfaces.h"

namespace scansurf::cli {

// Writes OUTDIR/<feature>.ply for every feature and OUTDIR/multilabel.ply. Everything is
// written into a staging folder inside OUTDIR first and moved into place only when all of
// it succeeded, so a failure leaves no partial output and replaces no existing file.
// Returns the paths written.
Result<std::vector<std::filesystem::path>> writeOutputs(const std::filesystem::path& outDir, const ContourSet& contours,
                                                        const Surfaces& surfaces);

// A file name from a feature name: letters, digits, '.', '-' and '_' kept, the rest '_';
// made unique against `used` (and added to it).
std::string fileStem(const std::string& name, std::vector<std::string>& used);

}  // namespace scansurf::cli
