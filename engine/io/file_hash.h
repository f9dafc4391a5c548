// scansurf io: SHA-256 of a file (OpenSSL's EVP digest), for the report's input hashes.
#pragma once

#include <filesystem>
#include <string>

#include "scansurf/result.h"

namespace scansurf {

// The file's SHA-256 as 64 lower-case hex digits. Errors: Errc::Io naming the path.
Result<std::string> sha256OfFile(const std::filesystem::path& path);

}  // namespace scansurf
