// Text taken from a file or the command line, made safe to quote in a one-line error message: a corrupt
// header can put newlines, control bytes or megabytes of garbage where a field value should be.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

#include <glm/glm.hpp>

namespace fcc::io {

// `text` in double quotes, non-printable bytes as \xNN, cut to `maxChars` characters with "...".
inline std::string quotedText(std::string_view text, size_t maxChars = 48) {
  std::string out = "\"";
  for (size_t i = 0; i < text.size(); ++i) {
    if (i == maxChars) {
      out += "...";
      break;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '"' && c != '\\') {
      out += static_cast<char>(c);
    } else {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", c);
      out += escaped;
    }
  }
  return out + "\"";
}

// A double in the shortest familiar form ("0.5", "1e+20", "nan"), unlike std::to_string's "0.500000".
inline std::string numberText(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

// "256,256,128": dims as the command line spells them.
inline std::string commaList(const glm::ivec3& v) {
  return std::to_string(v.x) + "," + std::to_string(v.y) + "," + std::to_string(v.z);
}

}  // namespace fcc::io
