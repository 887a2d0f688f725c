#include "mesh/results/reference_points.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "mesh/base/error.h"
#include "mesh/base/input_file.h"
#include "mesh/base/number_text.h"
#include "mesh/base/output_file.h"

namespace rad {
namespace {

/// A normal whose length is this far from 1 is not a unit normal.
constexpr double kUnitTolerance = 1e-3;
constexpr int kColumns = 15;

/// The text in quotes, its own quotes doubled.
std::string quotedCell(const std::string& s) {
  std::string quoted = "\"";
  for (char c : s) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

/// Surface names and tags as CSV fields (RFC 4180): quoted when they hold a comma or a quote,
/// quotes doubled. A line break, which would need multi-line records, becomes a space.
std::string cell(std::string s) {
  for (char& c : s)
    if (c == '\n' || c == '\r') c = ' ';
  return s.find_first_of(",\"") == std::string::npos ? s : quotedCell(s);
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

/// The field as a finite number (`column` names it in messages).
double number(const std::string& text, const std::string& where, const char* column) {
  double v;
  if (!finiteNumber(text, v)) throw inputError(where + ": " + column, "a finite number", "'" + text + "'");
  return v;
}

/// The columns' names, for messages.
constexpr const char* kColumnNames[kColumns] = {"x", "y", "z", "nx", "ny", "nz", "surface", "tag",
                                                "B_r", "B_g", "B_b", "se_r", "se_g", "se_b", "paths"};

/// The paths column (v[14], written as f[14]) holds a whole number of paths.
void checkPaths(const double (&v)[kColumns], const std::vector<std::string>& f, const std::string& where) {
  if (!(v[14] >= 0 && v[14] <= 4e18 && v[14] == std::floor(v[14])))
    throw inputError(where + ": paths", "a whole number of paths >= 0", f[14]);
}

/// nx, ny, nz (v[3..5]) make a unit normal.
void checkUnitNormal(const double (&v)[kColumns], const std::string& where) {
  const double length = std::sqrt(v[3] * v[3] + v[4] * v[4] + v[5] * v[5]);
  if (std::abs(length - 1) > kUnitTolerance)
    throw inputError(where + ": nx,ny,nz", "a unit normal", "length " + std::to_string(length));
}

/// The values are a point's: a whole number of paths, a unit normal, B and errors >= 0.
void checkPoint(const double (&v)[kColumns], const std::vector<std::string>& f,
                const std::string& where) {
  checkPaths(v, f, where);
  checkUnitNormal(v, where);
  for (int k = 8; k < kColumns; ++k)
    if (v[k] < 0) throw inputError(where + ": " + kColumnNames[k], "a value >= 0", f[size_t(k)]);
}

/// The numeric fields into v (surface and tag, columns 6 and 7, left at 0), each finite.
void readNumbers(const std::vector<std::string>& f, const std::string& where, double (&v)[kColumns]) {
  for (int k = 0; k < kColumns; ++k)
    if (k != 6 && k != 7) v[k] = number(f[size_t(k)], where, kColumnNames[k]);
}

/// The fields of a data line as a point, checked.
ReferencePoint parsePoint(const std::vector<std::string>& f, const std::string& where) {
  double v[kColumns] = {};
  readNumbers(f, where, v);
  checkPoint(v, f, where);
  ReferencePoint p;
  p.position = {v[0], v[1], v[2]};
  p.normal = {v[3], v[4], v[5]};
  p.surface = f[6];
  p.tag = f[7];
  p.B = {v[8], v[9], v[10]};
  p.standardError = {v[11], v[12], v[13]};
  p.paths = long(v[14]);
  return p;
}

/// The first line that is neither a comment nor empty names the columns.
void checkColumnLine(const std::string& line, const std::string& where) {
  if (line != kReferenceColumns)
    throw inputError(where, std::string("the column names '") + kReferenceColumns + "'",
                     "'" + line.substr(0, 80) + "'");
}

/// A data line as a point.
ReferencePoint pointOfLine(const std::string& line, const std::string& where) {
  std::vector<std::string> f;
  if (!splitColumns(line, f)) throw inputError(where, "a closing quote", "none");
  if (f.size() != kColumns)
    throw inputError(where, std::to_string(kColumns) + " comma-separated columns",
                     std::to_string(f.size()));
  return parsePoint(f, where);
}

/// One point as a CSV row.
void writeRow(std::ostream& out, const ReferencePoint& p) {
  for (const glm::dvec3* v : {&p.position, &p.normal})
    for (int k = 0; k < 3; ++k) out << exactNumberText((*v)[k]) << ",";
  out << cell(p.surface) << "," << cell(p.tag);
  for (const glm::dvec3* v : {&p.B, &p.standardError})
    for (int k = 0; k < 3; ++k) out << "," << exactNumberText((*v)[k]);
  out << "," << p.paths << "\n";
}

/// A comment line's text: after the '#' and one space, if there is one.
std::string commentText(const std::string& line) {
  return line.substr(line.size() > 1 && line[1] == ' ' ? 2 : 1);
}

/// One line (`where`): a header comment, nothing, the column line (once: `columns`), or a point.
void readLine(const std::string& line, const std::string& where, bool& columns, ReferenceFile& file) {
  if (line.rfind("#", 0) == 0)
    file.header.push_back(commentText(line));
  else if (line.empty())
    return;
  else if (!columns)
    checkColumnLine(line, where), columns = true;
  else
    file.points.push_back(pointOfLine(line, where));
}

/// The file, read to its end, had the column line and at least one point.
void checkComplete(const ReferenceFile& file, bool columns, const std::string& path) {
  if (!columns) throw inputError(path, "a reference file (CSV with the column line)", "none");
  if (file.points.empty()) throw inputError(path, "at least one reference point", "none");
}

}  // namespace

void writeReferenceFile(const std::string& path, const ReferenceFile& file) {
  writeFileAtomically(path, [&](std::ostream& out) {
    for (const auto& h : file.header) out << "# " << h << "\n";
    out << kReferenceColumns << "\n";
    for (const auto& p : file.points) writeRow(out, p);
  });
}

ReferenceFile readReferenceFile(const std::string& path) {
  std::istringstream in(readInputFile(path, "a readable reference file (CSV)"));
  ReferenceFile file;
  std::string line;
  bool columns = false;
  for (int lineNo = 1; std::getline(in, line); ++lineNo) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    readLine(line, path + ": line " + std::to_string(lineNo), columns, file);
  }
  checkComplete(file, columns, path);
  return file;
}

}  // namespace rad
