#include "io/length_units.h"

#include <cctype>

namespace scansurf {

double metresPerUnit(const std::string& units) {
  std::string u;
  for (unsigned char c : units) u += static_cast<char>(std::tolower(c));
  if (u == "mm") return 1e-3;
  if (u == "cm") return 1e-2;
  if (u == "m") return 1;
  if (u == "um" || u == "\u00b5m" || u == "\u03bcm" || u == "micron" || u == "microns") return 1e-6;
  if (u == "nm") return 1e-9;
  return 0;
}

}  // namespace scansurf
