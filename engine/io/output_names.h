// scansurf: the small rules output names follow, shared by the output plan, the staging and
// the writers.
#pragma once

#include <filesystem>
#include <string>

namespace scansurf {

// The file name, lower-cased.
std::string lowerName(const std::filesystem::path& path);
// Whether the file name ends in ext (lower-case, with its dot), ignoring case.
bool hasExtension(const std::filesystem::path& path, const std::string& ext);
// Letters, digits, '.', '-' and '_' kept, every other byte '_'.
std::string sanitized(const std::string& name);

}  // namespace scansurf
