#include "outputs.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>

#include "io/ply_writer.h"

namespace fs = std::filesystem;

namespace scansurf::cli {

std::string fileStem(const std::string& name, std::vector<std::string>& used) {
  std::string stem;
  for (unsigned char c : name) stem += (std::isalnum(c) || c == '-' || c == '_' || c == '.') ? static_cast<char>(c) : '_';
  if (stem.empty() || stem.front() == '.') stem = "feature" + stem;
  std::string unique = stem;
  for (int n = 2; std::find(used.begin(), used.end(), unique) != used.end(); ++n) unique = stem + "_" + std::to_string(n);
  used.push_back(unique);
  return unique;
}

Result<std::vector<fs::path>> writeOutputs(const fs::path& outDir, const ContourSet& contours, const Surfaces& surfaces) {
  const fs::path staging = outDir / (".scansurf-staging-" + std::to_string(::getpid()));
  std::error_code ec;
  fs::remove_all(staging, ec);
  if (!fs::create_directory(staging, ec))
    return makeError(Errc::Io, "cannot create " + staging.string() + ": " + ec.message());
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  } cleanup{staging};

  std::vector<std::string> names;
  std::vector<std::string> used{"multilabel"};
  for (std::size_t f = 0; f < contours.features.size(); ++f) {
    const std::string name = fileStem(contours.features[f].name, used) + ".ply";
    SCANSURF_TRY(writeSurfacePly(staging / name, surfaces.mesh, surfaces.features[f]));
    names.push_back(name);
  }
  SCANSURF_TRY(writeMultiLabelPly(staging / "multilabel.ply", surfaces.mesh));
  names.push_back("multilabel.ply");

  std::vector<fs::path> written;
  for (const std::string& name : names) {
    fs::rename(staging / name, outDir / name, ec);
    if (ec) return makeError(Errc::Io, "cannot move " + name + " into " + outDir.string() + ": " + ec.message());
    written.push_back(outDir / name);
  }
  return written;
}

}  // namespace scansurf::cli
