#include "mesh/reference_points.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "mesh/error.h"
#include "mesh/input_file.h"
#include "mesh/output_file.h"

namespace rad {
namespace {

/// A normal whose length is this far from 1 is not a unit normal.
constexpr double kUnitTolerance = 1e-3;
constexpr int kColumns = 15;

/// Surface names and tags as CSV fields (RFC 4180): quoted when they hold a comma or a quote,
/// quotes doubled. A line break, which would need multi-line records, becomes a space.
std::string cell(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  if (s.find_first_of(",\"") == std::string::npos) return s;
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

/// The fields of one CSV line, quoted fields unquoted; false on an unterminated quote.
bool splitColumns(const std::string& line, std::vector<std::string>& out) {
  out.assign(1, "");
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted && c == '"' && i + 1 < line.size() && line[i + 1] == '"') out.back() += '"', ++i;
    else if (c == '"') quoted = !quoted;
    else if (c == ',' && !quoted) out.emplace_back();
    else out.back() += c;
  }
  return !quoted;
}

double number(const std::string& text, const std::string& where, const char* column) {
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(v))
    throw inputError(where + ": " + column, "a finite number", "'" + text + "'");
  return v;
}

ReferencePoint parsePoint(const std::vector<std::string>& f, const std::string& where) {
  static const char* names[] = {"x", "y", "z", "nx", "ny", "nz", "surface", "tag", "B_r", "B_g",
                                "B_b", "se_r", "se_g", "se_b", "paths"};
  double v[kColumns] = {};
  for (int k = 0; k < kColumns; ++k)
    if (k != 6 && k != 7) v[k] = number(f[size_t(k)], where, names[k]);
  ReferencePoint p;
  p.position = {v[0], v[1], v[2]};
  p.normal = {v[3], v[4], v[5]};
  p.surface = f[6];
  p.tag = f[7];
  p.B = {v[8], v[9], v[10]};
  p.standardError = {v[11], v[12], v[13]};
  if (!(v[14] >= 0 && v[14] <= 4e18 && v[14] == std::floor(v[14])))
    throw inputError(where + ": paths", "a whole number of paths >= 0", f[14]);
  p.paths = long(v[14]);
  const double length = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
  if (std::abs(length - 1) > kUnitTolerance)
    throw inputError(where + ": nx,ny,nz", "a unit normal", "length " + std::to_string(length));
  for (int k = 8; k < kColumns; ++k)
    if (v[k] < 0) throw inputError(where + ": " + names[k], "a value >= 0", f[size_t(k)]);
  return p;
}

}  // namespace

void writeReferenceFile(const std::string& path, const ReferenceFile& file) {
  writeFileAtomically(path, [&](std::ostream& out) {
    for (const auto& h : file.header) out << "# " << h << "\n";
    out << kReferenceColumns << "\n";
    char buf[64];
    auto put = [&](double v) {
      std::snprintf(buf, sizeof buf, "%.17g", v);
      out << buf;
    };
    for (const auto& p : file.points) {
      for (const glm::dvec3* v : {&p.position, &p.normal})
        for (int k = 0; k < 3; ++k) put((*v)[k]), out << ",";
      out << cell(p.surface) << "," << cell(p.tag);
      for (const glm::dvec3* v : {&p.B, &p.standardError})
        for (int k = 0; k < 3; ++k) out << ",", put((*v)[k]);
      out << "," << p.paths << "\n";
    }
  });
}

ReferenceFile readReferenceFile(const std::string& path) {
  std::istringstream in(readInputFile(path, "a readable reference file (CSV)"));
  ReferenceFile file;
  std::string line;
  int lineNo = 0;
  bool columns = false;
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::string where = path + ": line " + std::to_string(lineNo);
    if (line.rfind("#", 0) == 0) {
      file.header.push_back(line.substr(line.size() > 1 && line[1] == ' ' ? 2 : 1));
      continue;
    }
    if (line.empty()) continue;
    if (!columns) {
      if (line != kReferenceColumns)
        throw inputError(where, std::string("the column names '") + kReferenceColumns + "'",
                         "'" + line.substr(0, 80) + "'");
      columns = true;
      continue;
    }
    std::vector<std::string> f;
    if (!splitColumns(line, f)) throw inputError(where, "a closing quote", "none");
    if (f.size() != kColumns)
      throw inputError(where, std::to_string(kColumns) + " comma-separated columns",
                       std::to_string(f.size()));
    file.points.push_back(parsePoint(f, where));
  }
  if (!columns) throw inputError(path, "a reference file (CSV with the column line)", "none");
  if (file.points.empty()) throw inputError(path, "at least one reference point", "none");
  return file;
}

}  // namespace rad
