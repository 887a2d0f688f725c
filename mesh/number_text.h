#pragma once
// Numbers as text: the two ways files and messages write them.
#include <cstdio>
#include <sstream>
#include <string>

namespace rad {

/// The shortest text of a number (six significant digits), as the messages show it.
inline std::string shortNumberText(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

/// A number with all 17 significant digits, so that it reads back exactly.
inline std::string exactNumberText(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

}  // namespace rad
