// scansurf: names from files are bytes (an RTSTRUCT's ROI name may be Latin-1); formats that
// are UTF-8 by definition (glTF's JSON, the report) get them with every invalid sequence
// replaced by U+FFFD, so a name can never make a writer fail.
#pragma once

#include <string>
#include <string_view>

namespace scansurf {

// s with each byte that does not start or continue a valid UTF-8 sequence replaced by U+FFFD
// (overlong forms, surrogates and code points above U+10FFFF count as invalid).
inline std::string validUtf8(std::string_view s) {
  std::string out;
  out.reserve(s.size());
  const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(s[i]); };
  for (std::size_t i = 0; i < s.size();) {
    const unsigned char c = byte(i);
    int length = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
    bool ok = length > 0 && i + static_cast<std::size_t>(length) <= s.size();
    char32_t cp = length == 1 ? c : length == 2 ? (c & 0x1Fu) : length == 3 ? (c & 0x0Fu) : (c & 0x07u);
    for (int k = 1; ok && k < length; ++k) {
      ok = (byte(i + static_cast<std::size_t>(k)) & 0xC0) == 0x80;
      cp = (cp << 6) | (byte(i + static_cast<std::size_t>(k)) & 0x3Fu);
    }
    static constexpr char32_t kMin[5] = {0, 0, 0x80, 0x800, 0x10000};
    ok = ok && cp >= kMin[length] && cp <= 0x10FFFF && !(cp >= 0xD800 && cp <= 0xDFFF);
    if (ok) {
      out.append(s.substr(i, static_cast<std::size_t>(length)));
      i += static_cast<std::size_t>(length);
    } else {
      out += "\xEF\xBF\xBD";
      ++i;
    }
  }
  return out;
}

}  // namespace scansurf
