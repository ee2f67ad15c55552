// "X,Y,Z" flag values (--dims, --spacing, --eye, ...).
#pragma once

#include <glm/glm.hpp>

#include <sstream>
#include <string>

namespace fcc::cli {

// Parses three comma-separated numbers; false if `text` is not exactly that.
template <class T>
bool parseTriple(const std::string& text, glm::vec<3, T>& out) {
  std::istringstream in(text);
  char c1 = 0, c2 = 0;
  T a, b, c;
  if (!(in >> a >> c1 >> b >> c2 >> c) || c1 != ',' || c2 != ',') return false;
  in >> std::ws;
  if (!in.eof()) return false;
  out = glm::vec<3, T>(a, b, c);
  return true;
}

}  // namespace fcc::cli
