// scansurf: the version of the library linked (scansurf/version.h has the headers').
#include "scansurf/version.h"

namespace scansurf {

const char* version() noexcept { return SCANSURF_VERSION_STRING; }

}  // namespace scansurf
