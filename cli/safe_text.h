// scansurf CLI: text from input files (feature and ROI names, units) printed to a terminal.
// Control characters are escaped so a name can neither forge a "scansurf: error:" line nor
// move the cursor or clear the screen.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace scansurf::cli {

// s with every byte below 0x20 (tab included) and DEL written as \xNN; other bytes unchanged.
inline std::string printable(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  for (unsigned char c : s) {
    if (c >= 0x20 && c != 0x7F) {
      out += static_cast<char>(c);
      continue;
    }
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
    out += escaped;
  }
  return out;
}

}  // namespace scansurf::cli
