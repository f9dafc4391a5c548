// scansurf: how deeply a DICOM file nests its sequences, found without recursion, so that a
// hostile file cannot overflow the stack of DCMTK's recursive parser.
#pragma once

#include <cstdint>
#include <filesystem>

#include "scansurf/result.h"

namespace scansurf {

// Real RT Structure Sets and CT images nest sequences 4 to 6 deep; DCMTK's parser spends a few
// stack frames per level. 64 leaves room for any real object and little stack.
inline constexpr int kMaxDicomNesting = 64;

// Walks the file's elements (Part 10 or bare data set; implicit or explicit VR, little or big
// endian; deflated data sets inflated in memory), stopping at Pixel Data when stopAtPixelData,
// and fails with Errc::InvalidInput naming the file and the depth when sequences nest deeper
// than maxDepth. Bytes it cannot make sense of end the walk quietly: judging them is DCMTK's job.
// A deflated data set that inflates to more than inflateLimit bytes (0: a quarter of the
// memory available, as for a file read whole) fails with Errc::ResourceLimit naming the file.
Result<void> checkDicomNesting(const std::filesystem::path& path, bool stopAtPixelData, int maxDepth = kMaxDicomNesting,
                               std::uint64_t inflateLimit = 0);

}  // namespace scansurf
