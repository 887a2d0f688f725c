#pragma once
// What the tests share: where the scenes are and the lists of scenes (tests/solve_support.h
// adds a scene solved as `radiosity solve` solves it).
#include <algorithm>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/base/error.h"

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

/// Expects f() to throw an E whose message contains every one of `parts` (where, what was
/// expected, what was found), and prints the message when it does not.
template <class E = InputError, class F>
void expectError(F&& f, std::initializer_list<std::string> parts) {
  try {
    f();
    ADD_FAILURE() << "no error thrown; expected one saying: " << *parts.begin();
  } catch (const E& e) {
    for (const auto& part : parts)
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << "message: " << e.what() << "\nlacks: " << part;
  }
}

}  // namespace rad::test
