#pragma once
// What the tests share: where the scenes are and the lists of scenes (tests/solve_support.h
// adds a scene solved as `radiosity solve` solves it).
#include <algorithm>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mesh/scene.h"

namespace rad::test {

inline const std::string kSourceDir = RAD_SOURCE_DIR;
/// The project's scenes, scenes/NAME.
inline const std::string kScenes = kSourceDir + "/scenes/";
/// The tests' own files, tests/data/NAME.
inline const std::string kData = kSourceDir + "/tests/data/";

/// The .json files of a folder of the source tree ("scenes/stress"), sorted.
inline std::vector<std::string> sceneFiles(const std::string& folder) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::directory_iterator(kSourceDir + "/" + folder))
    if (e.path().extension() == ".json") out.push_back(e.path().string());
  std::sort(out.begin(), out.end());
  return out;
}

/// A scene file's name without folder and extension, for test names.
inline std::string sceneName(const std::string& path) { return std::filesystem::path(path).stem().string(); }

}  // namespace rad::test
