// scansurf: the length units inputs name, as multiples of a metre.
#pragma once

#include <string>

namespace scansurf {

// Metres in one `units` ("mm", "cm", "m", "um"/"µm"/"micron", "nm"; any case); 0 for a unit
// of unknown length (pixels, or a name scansurf does not know).
double metresPerUnit(const std::string& units);

}  // namespace scansurf
