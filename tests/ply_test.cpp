// The PLY writer and reader agree, and the reader says what is wrong with a bad file.
#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>

#include "mesh/base/error.h"
#include "mesh/base/ply_reader.h"
#include "mesh/base/ply_writer.h"
#include "tests/support.h"

namespace rad {
namespace {

std::string tempPath(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("rad_ply_test_" + name)).string();
}

TEST(PlyTest, WhatIsWrittenIsReadBack) {
  PlyMesh m;
  m.comments = {"camera eye 1 2 3", "exposure 0.5"};
  m.vertex = {{"x", PlyColumn::Type::Float, {0, 1, 0, 1}},
              {"y", PlyColumn::Type::Float, {0, 0, 1, 1}},
              {"z", PlyColumn::Type::Float, {0.25, 0.5, 0.75, 1}},
              {"red", PlyColumn::Type::UChar, {0, 128, 255, 7}}};
  m.faces = {{0, 1, 2}, {1, 3, 2}};
  m.face = {{"surface", PlyColumn::Type::Int, {3, -4}},
            {"radiosity_r", PlyColumn::Type::Float, {1.5, 2.25}}};
  std::string path = tempPath("roundtrip.ply");
  writePly(path, m);
  PlyMesh r = readPly(path);
  EXPECT_EQ(r.comments, m.comments);
  EXPECT_EQ(r.faces, m.faces);
  ASSERT_EQ(r.vertex.size(), 4u);
  ASSERT_EQ(r.face.size(), 2u);
  for (size_t c = 0; c < m.vertex.size(); ++c) EXPECT_EQ(r.vertex[c].values, m.vertex[c].values);
  for (size_t c = 0; c < m.face.size(); ++c) EXPECT_EQ(r.face[c].values, m.face[c].values);
  EXPECT_NE(findColumn(r.face, "radiosity_r"), nullptr);
  EXPECT_EQ(findColumn(r.face, "radiosity_g"), nullptr);
  std::filesystem::remove(path);
}

TEST(PlyTest, TruncatedAndForeignFilesAreClearErrors) {
  std::string path = tempPath("bad.ply");
  std::ofstream(path) << "ply\nformat ascii 1.0\nend_header\n";
  test::expectError([&] { readPly(path); },
                    {path + ": expected binary_little_endian PLY, found format ascii"});
  std::ofstream(path) << "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nend_header\nab";
  test::expectError([&] { readPly(path); },
                    {path + ": element vertex: expected at most the 0 records", "a truncated file"});
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace rad
