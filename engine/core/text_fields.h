// scansurf: names from files (feature and ROI names) inside the text of other formats: a
// comment, a header value, a quoted field. Each format gets the name on one line with every
// control character (below 0x20, and DEL) written as \xNN, so that a name can start no new
// line, statement or key, and can close no quote where the format has one.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

namespace scansurf {

// s on one line: control characters as \xNN, and each character of `quotes` as \xNN too.
inline std::string oneLineText(std::string_view s, std::string_view quotes = {}) {
  std::string out;
  out.reserve(s.size());
  for (unsigned char c : s) {
    if (c >= 0x20 && c != 0x7F && quotes.find(static_cast<char>(c)) == std::string_view::npos) {
      out += static_cast<char>(c);
      continue;
    }
    char escaped[8];
    std::snprintf(escaped, sizeof escaped, "\\x%02X", c);
    out += escaped;
  }
  return out;
}

}  // namespace scansurf
