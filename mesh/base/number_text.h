#pragma once
// Numbers as text: the two ways files and messages write them, and a whole word read as one.
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

/// printf's text of the format and arguments (at most 511 characters).
template <class... Args>
std::string formatted(const char* format, Args... args) {
  char text[512];
  std::snprintf(text, sizeof text, format, args...);
  return text;
}

/// A finite number filling the whole word into v, or false.
inline bool finiteNumber(const std::string& word, double& v) {
  char* end = nullptr;
  v = std::strtod(word.c_str(), &end);
  return !word.empty() && *end == '\0' && std::isfinite(v);
}

}  // namespace rad
