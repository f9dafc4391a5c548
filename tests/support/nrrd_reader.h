// scansurf tests: a small NRRD reader (header fields and gzip-decoded data), enough to read
// back what the label volume writer writes.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace scansurf::test {

struct Nrrd {
  std::map<std::string, std::string> fields;  // "sizes", "Segment0_Layer", ...
  std::string data;                           // decoded voxels
};

// Reads the file; a malformed one gives empty fields and data.
Nrrd readNrrd(const std::filesystem::path& path);

// The numbers of a field such as "(1,0,0) (0,1,0)" or "3 512 512 5" ("none" is skipped).
std::vector<double> nrrdNumbers(std::string field);

}  // namespace scansurf::test
