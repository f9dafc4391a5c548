// scansurf: the native contour set JSON format (version 1, /work/shared/formats/contours-json.md).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "scansurf/contours.h"
#include "scansurf/result.h"

namespace scansurf {

// Reads and validates a contour set file (validateAndNormalize is applied). source is set to
// the path as given. Errors: Errc::Io when the file cannot be read; Errc::InvalidInput for
// malformed or inconsistent content, naming the file, feature, slice and contour.
Result<ContourSet> readContoursJson(const std::filesystem::path& path);

// As readContoursJson for text already in memory; source names it in messages.
Result<ContourSet> parseContoursJson(std::string_view text, std::string source);

// Serializes a contour set as version 1 JSON (every double written so it reads back exactly).
std::string formatContoursJson(const ContourSet& contours);

// Writes formatContoursJson(contours) to path through a temporary file in the same directory
// renamed over it, so a failure never leaves a partial file. Errors: Errc::InvalidArgument for
// a non-finite value or an order index out of range; Errc::Io when writing fails.
Result<void> writeContoursJson(const ContourSet& contours, const std::filesystem::path& path);

}  // namespace scansurf
