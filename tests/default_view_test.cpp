// What a user sees of a scene without a camera, through the shipping commands with their
// defaults: `radiosity solve` (whose result carries the default camera, mesh/results/default_camera.h)
// then `radview`. The Cornell box must be seen from inside: its red wall in the left half of the
// picture, its green wall in the right half, a lit centre; not the back of its back wall.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "display/viewer/viewer.h"
#include "tests/support.h"

namespace rad::viewer {
namespace {

const std::string kOut = std::string(RAD_VIEWER_OUT) + "/default_view/";
/// A wall's colour dominates a pixel when its channel exceeds each other channel this many times
/// (sRGB bytes: the warm light leaves the green wall's green only about 1.5 times its red).
constexpr double kDominance = 1.25;
/// Each side wall's colour dominates at least this share of its half of the picture: about 80 %
/// (red, with its light on the floor and ceiling) and 35 % (green) seen through the opening of the
/// box, none from behind its back wall.
constexpr double kWallShare = 0.10;
/// The centre pixel's mean channel is at least this (display bytes): the lit inside.
constexpr double kLitCentre = 60;

/// Runs a command line, its output to `log`; expects exit 0.
void run(const std::string& command, const std::string& log) {
  const int code = std::system((command + " > '" + log + "' 2>&1").c_str());
  ASSERT_EQ(code, 0) << command << "\nsee " << log;
}

/// scenes/cornell.json without its camera, turned half a turn about the vertical (x, z to -x, -z)
/// when `turned`, written to kOut/NAME.json; returns its path.
std::string cornellWithoutCamera(const std::string& name, bool turned) {
  std::ifstream in(test::kScenes + "cornell.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  scene.erase("camera");
  const auto turn = [](nlohmann::json& ring) {
    for (auto& p : ring) p = nlohmann::json::array({-p[0].get<double>(), p[1], -p[2].get<double>()});
  };
  if (turned)
    for (auto& surface : scene["surfaces"]) {
      turn(surface["polygon"]);
      if (surface.contains("holes"))
        for (auto& hole : surface["holes"]) turn(hole);
    }
  std::filesystem::create_directories(kOut);
  const std::string path = kOut + name + ".json";
  std::ofstream file(path);
  file << scene.dump(1);
  EXPECT_TRUE(file.good()) << "could not write " << path;
  return path;
}

/// The picture `radview` draws of the result `radiosity solve` makes of the scene, both with
/// their defaults; result, picture and logs in kOut/NAME.*.
Image defaultView(const std::string& scene, const std::string& name) {
  std::filesystem::create_directories(kOut);
  const std::string out = kOut + name, result = out + ".ply", picture = out + ".png";
  run(std::string(RAD_RADIOSITY_CLI) + " solve '" + scene + "' -o '" + result + "'", out + ".solve.log");
  run(std::string(RAD_RADVIEW_CLI) + " '" + result + "' -o '" + picture + "'", out + ".radview.log");
  return readPng(picture);
}

/// The share of the pixels in columns [first, last) whose channel `c` dominates.
double dominatedShare(const Image& image, int c, int first, int last) {
  int count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = first; x < last; ++x) {
      const uint8_t* p = &image.rgb[3 * (size_t(y) * image.width + x)];
      if (p[c] > kDominance * p[(c + 1) % 3] && p[c] > kDominance * p[(c + 2) % 3]) ++count;
    }
  return double(count) / (image.height * (last - first));
}

/// The mean channel of the centre pixel.
double centreBrightness(const Image& image) {
  const uint8_t* p = &image.rgb[3 * (size_t(image.height / 2) * image.width + image.width / 2)];
  return (p[0] + p[1] + p[2]) / 3.0;
}

/// The picture shows the inside of the Cornell box (red wall left, green wall right, lit centre).
void expectInsideOfTheBox(const Image& image, const std::string& picture) {
  ASSERT_GT(image.width, 1);
  const int half = image.width / 2;
  EXPECT_GE(dominatedShare(image, 0, 0, half), kWallShare) << "red wall in the left half of " << picture;
  EXPECT_GE(dominatedShare(image, 1, half, image.width), kWallShare) << "green wall in the right half of " << picture;
  EXPECT_GE(centreBrightness(image), kLitCentre) << picture;
}

TEST(DefaultViewTest, CornellWithoutCameraIsSeenFromItsOpenSide) {
  const std::string scene = cornellWithoutCamera("cornell_no_camera", false);
  expectInsideOfTheBox(defaultView(scene, "cornell_no_camera"), kOut + "cornell_no_camera.png");
}

// Open at +z (as McGuire's box is): the camera that looked along +z saw the back of its back wall.
TEST(DefaultViewTest, TurnedCornellWithoutCameraIsSeenFromItsOpenSide) {
  const std::string scene = cornellWithoutCamera("cornell_turned", true);
  expectInsideOfTheBox(defaultView(scene, "cornell_turned"), kOut + "cornell_turned.png");
}

// McGuire's CornellBox-Original with its one-line scene, as a user downloads it (open at +z).
TEST(DefaultViewTest, CornellOriginalIsSeenFromItsOpenSide) {
  const Image image = defaultView(test::kScenes + "cornell_original.json", "cornell_original");
  expectInsideOfTheBox(image, kOut + "cornell_original.png");
}

}  // namespace
}  // namespace rad::viewer
