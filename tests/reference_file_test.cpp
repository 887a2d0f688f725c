// The reference file (mesh/results/reference_points.h) and mesh files (mesh/scene/readers/mesh_file.h): what is
// written is read back (names with commas and quotes, every kind of line end); bad files are
// located errors.
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "mesh/base/error.h"
#include "mesh/results/reference_points.h"
#include "mesh/scene/readers/mesh_file.h"
#include "tests/support.h"

namespace rad {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("rad_reference_test_" + name)).string();
}

TEST(ReferenceFileTest, WhatIsWrittenIsReadBack) {
  ReferenceFile file;
  file.header = {"scene: a.json", "seed: 3"};
  file.points.push_back({{1, 2, 3}, {0, 1, 0}, "floor, left", "say \"edge\"", {0.5, 0.25, 0.125}, {1e-3, 2e-3, 3e-3}, 4096});
  file.points.push_back({{-1e-7, 2e9, 0.1}, {0, 0, -1}, "wall", "area", {0, 1e-300, 7}, {0, 0, 0.5}, 2});
  const std::string path = tempPath("roundtrip.csv");
  writeReferenceFile(path, file);
  const ReferenceFile read = readReferenceFile(path);
  EXPECT_EQ(read.header, file.header);
  ASSERT_EQ(read.points.size(), file.points.size());
  for (size_t i = 0; i < file.points.size(); ++i) {
    const auto &a = file.points[i], &b = read.points[i];
    EXPECT_EQ(a.position, b.position);
    EXPECT_EQ(a.normal, b.normal);
    EXPECT_EQ(a.surface, b.surface);
    EXPECT_EQ(a.tag, b.tag);
    EXPECT_EQ(a.B, b.B);
    EXPECT_EQ(a.standardError, b.standardError);
    EXPECT_EQ(a.paths, b.paths);
  }
  std::filesystem::remove(path);
}

/// Regression (found in review): a paths column of 1e300 was converted to long before it was
/// checked (undefined behaviour).
TEST(ReferenceFileTest, BadNumbersAreLocatedErrors) {
  const std::string path = tempPath("bad.csv");
  const std::string columns = kReferenceColumns;
  const std::pair<std::string, std::string> cases[] = {
      {"0,0,0,0,1,0,floor,area,1,1,1,0,0,0,1e300", "line 2: paths: expected a whole number of paths >= 0, found 1e300"},
      {"0,0,0,0,1,0,floor,area,1,1,1,0,0,0,2.5", "line 2: paths: expected a whole number of paths >= 0, found 2.5"},
      {"0,0,0,0,1,0,floor,area,nan,1,1,0,0,0,1", "line 2: B_r: expected a finite number, found 'nan'"},
      {"0,0,0,0,1,0,\"floor,area,1,1,1,0,0,0,1", "line 2: expected a closing quote, found none"},
      {"0,0,0,0,2,0,floor,area,1,1,1,0,0,0,1", "line 2: nx,ny,nz: expected a unit normal"},
  };
  for (const auto& [line, message] : cases) {
    std::ofstream(path) << columns << "\n" << line << "\n";
    SCOPED_TRACE(line);
    test::expectError([&] { readReferenceFile(path); }, {path + ": " + message});
  }
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rad

namespace rad {
namespace {

/// Mesh files whose lines end in CR alone (old Mac) or CRLF (Windows) read like any other.
TEST(MeshFileTest, LineEndsOfEveryKind) {
  const std::string& data = test::kData;
  const auto cr = readMeshFile(data + "cr_line_ends.obj", "test");
  ASSERT_EQ(cr.size(), 1u);
  ASSERT_EQ(cr[0].faces.size(), 1u);
  EXPECT_EQ(cr[0].faces[0].outer.size(), 4u);
  const auto crlf = readMeshFile(data + "crlf_line_ends.obj", "test");
  ASSERT_EQ(crlf.size(), 1u);
  EXPECT_EQ(crlf[0].faces[0].outer.size(), 3u);
}

}  // namespace
}  // namespace rad
