// Scene loading: the format of DESIGN.md, materials, mesh files and transforms.
#include <cmath>
#include <filesystem>
#include <map>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "mesh/base/error.h"
#include "mesh/patch_mesh.h"
#include "mesh/scene/readers/scene_loader.h"
#include "tests/support.h"

namespace rad {
namespace {

const std::string& kSource = test::kSourceDir;
constexpr double kExact = 1e-12;

Scene parse(const std::string& text) { return parseScene(text, "test.json", kSource + "/tests/data"); }

/// A valid minimal scene with `extra` spliced into its top-level object.
std::string sceneWith(const std::string& materials, const std::string& surfaces,
                      const std::string& extra = "") {
  return R"({"version": 1, "materials": )" + materials + R"(, "surfaces": )" + surfaces +
         (extra.empty() ? "" : ", " + extra) + "}";
}
const std::string kSquare =
    R"([{"name": "sq", "material": "m", "polygon": [[0,0,0],[1,0,0],[1,1,0],[0,1,0]]}])";

TEST(SceneTest, EveryShippedSceneLoadsAndMeshes) {
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kSource + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    ++count;
    Scene scene = loadScene(entry.path().string());
    EXPECT_TRUE(scene.hasEmitter()) << entry.path();
    // Every scene names its camera but the one-line scene of a downloaded OBJ, as users write it.
    if (entry.path().stem() != "cornell_original") {
      EXPECT_TRUE(scene.camera.has_value()) << entry.path();
    }
    PatchMesh mesh = buildPatchMesh(scene, {scene.diagonal() / 10, scene.diagonal() / 5});
    EXPECT_GT(mesh.elementCount(), 0) << entry.path();
  }
  EXPECT_GE(count, 5);
}

TEST(SceneTest, CornellMaterialsAndCameraAreTheReferenceOnes) {
  Scene s = loadScene(kSource + "/scenes/cornell.json");
  ASSERT_EQ(s.surfaces.size(), 16u);
  EXPECT_EQ(s.materials[0].name, "white");  // file order is kept
  EXPECT_EQ(s.materials[0].reflectance, glm::dvec3(0.725, 0.71, 0.68));
  const Material& light = s.materials[s.surfaces[2].material];
  EXPECT_NEAR(light.emission.x, M_PI * 17, 1e-5);
  EXPECT_NEAR(light.emission.y, M_PI * 12, 1e-5);
  EXPECT_NEAR(light.emission.z, M_PI * 4, 1e-5);
  EXPECT_EQ(s.camera->eye, glm::dvec3(278, 273, -800));
  EXPECT_EQ(s.camera->fovYDeg, 39.3077);
  EXPECT_EQ(s.surfaces[1].polygons[0].holes.size(), 1u);
}

TEST(SceneTest, PresetGivesTheOpenGLMaterialAndItsDiffuseAsReflectance) {
  Scene s = parse(sceneWith(R"({"m": {"preset": "brass", "emission": [1, 1, 1]}})", kSquare));
  const Material& m = s.materials[0];
  EXPECT_EQ(m.preset, "brass");
  EXPECT_NEAR(m.reflectance.x, 0.780392, kExact);
  EXPECT_NEAR(m.specular.y, 0.941176, kExact);
  EXPECT_NEAR(m.shininess, 27.8974, kExact);
  // An explicit reflectance wins over the preset's diffuse colour.
  s = parse(sceneWith(R"({"m": {"preset": "gold", "reflectance": [0.1, 0.2, 0.3]}})", kSquare));
  EXPECT_EQ(s.materials[0].reflectance, glm::dvec3(0.1, 0.2, 0.3));
  EXPECT_NEAR(s.materials[0].diffuse.x, 0.75164, kExact);
}

TEST(SceneTest, ObjMaterialGroupsBecomeSurfacesWithPiTimesKe) {
  Scene s = parse(sceneWith(R"({"m": {"reflectance": [0.5, 0.5, 0.5]}})",
                            R"([{"name": "tiles", "mesh": "two_materials.obj"}])"));
  ASSERT_EQ(s.surfaces.size(), 2u);
  std::map<std::string, const Surface*> byName;
  for (const auto& surface : s.surfaces) byName[surface.name] = &surface;
  ASSERT_TRUE(byName.count("tiles/paint"));
  ASSERT_TRUE(byName.count("tiles/glow"));
  const Material& paint = s.materials[byName["tiles/paint"]->material];
  const Material& glow = s.materials[byName["tiles/glow"]->material];
  EXPECT_EQ(paint.reflectance, glm::dvec3(0.5, 0.25, 0.125));
  EXPECT_FALSE(paint.emits());
  EXPECT_NEAR(glow.emission.x, 2 * M_PI, kExact);
  EXPECT_NEAR(glow.emission.z, 0.5 * M_PI, kExact);
}

TEST(SceneTest, MeshTransformScalesThenRotatesXYZThenTranslates) {
  Scene s = parse(sceneWith(R"({"m": {"reflectance": [0.5, 0.5, 0.5]}})",
                            R"([{"name": "t", "material": "m", "mesh": "tetra.off",
                                 "transform": {"scale": [2, 3, 4], "rotate_deg": [0, 90, 0],
                                               "translate": [10, 0, 0]}}])"));
  ASSERT_EQ(s.surfaces.size(), 1u);
  EXPECT_EQ(s.surfaces[0].polygons.size(), 4u);
  // Vertex (1, 0, 0) scales to (2, 0, 0); 90 degrees about y takes +x to -z; then +10 in x.
  bool found = false;
  for (const auto& p : s.surfaces[0].polygons)
    for (const auto& q : p.outer)
      found = found || glm::length(q - glm::dvec3(10, 0, -2)) < 1e-12;
  EXPECT_TRUE(found);
}

TEST(SceneTest, PlyFacesKeepTheirPolygonsAndArea) {
  Scene s = parse(sceneWith(R"({"m": {"reflectance": [0.5, 0.5, 0.5]}})",
                            R"([{"name": "q", "material": "m", "mesh": "quad.ply",
                                 "transform": {"scale": 3}}])"));
  ASSERT_EQ(s.surfaces.size(), 1u);
  ASSERT_EQ(s.surfaces[0].polygons.size(), 1u);
  EXPECT_EQ(s.surfaces[0].polygons[0].outer.size(), 4u);
  PatchMesh m = buildPatchMesh(s, {1.0, 2.0});
  EXPECT_NEAR(m.surfaces[0].area, 2 * 1 * 9, 1e-9);
}

TEST(SceneTest, DegenerateMeshFacesAreDroppedAndSaid) {
  Scene s = parse(sceneWith(R"({"m": {"reflectance": [0.5, 0.5, 0.5]}})",
                            R"([{"name": "d", "material": "m", "mesh": "with_degenerate.obj"}])"));
  ASSERT_EQ(s.surfaces.size(), 1u);
  EXPECT_EQ(s.surfaces[0].polygons.size(), 1u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("dropped 1 degenerate faces"), std::string::npos) << s.warnings[0];
}

TEST(SceneTest, LightsFogAndLightModelFollowOpenGL) {
  Scene s = parse(sceneWith(R"({"m": {"reflectance": [0.5, 0.5, 0.5]}})", kSquare,
                            R"("light_model": {"ambient": [0.1, 0.1, 0.1], "two_sided": true},
                               "lights": [{"type": "directional", "direction": [0, 1, 0]},
                                          {"type": "spot", "position": [0, 2, 0],
                                           "direction": [0, -1, 0], "cutoff_deg": 30,
                                           "exponent": 4, "attenuation": [1, 0.1, 0.01]}],
                               "fog": {"mode": "linear", "start": 1, "end": 5})"));
  ASSERT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.lights[0].type, Light::Type::Directional);
  EXPECT_EQ(s.lights[0].diffuse, glm::dvec4(1.0));  // a declared light shines white by default
  EXPECT_EQ(s.lights[1].cutoffDeg, 30);
  EXPECT_EQ(s.lights[1].attenuation, glm::dvec3(1, 0.1, 0.01));
  EXPECT_TRUE(s.lightModel.twoSided);
  EXPECT_FALSE(s.lightModel.localViewer);
  ASSERT_TRUE(s.fog.has_value());
  EXPECT_EQ(s.fog->mode, Fog::Mode::Linear);
  EXPECT_EQ(s.fog->end, 5);
}

/// Messages say where, what was expected and what was found.
void expectError(const std::string& text, const std::string& fragment) {
  SCOPED_TRACE(text);
  test::expectError([&] { parse(text); }, {fragment});
}

TEST(SceneTest, BadInputSaysWhereWhatAndFound) {
  const std::string m = R"({"m": {"reflectance": [0.5, 0.5, 0.5]}})";
  expectError(sceneWith(m, kSquare, R"("lights": [{"type": "spot", "position": [0,0,0],
              "direction": [0,1,0], "cutoff_deg": 95}])"),
              "test.json: lights[0].cutoff_deg: expected a number in [0, 90], found the number 95");
  expectError(sceneWith(m, kSquare, R"("solver": {"hemicube_resolution": 255})"),
              "test.json: solver.hemicube_resolution: expected an even whole number, found the number 255");
  expectError(sceneWith(m, kSquare, R"("solver": {"max_element_edge": 0})"),
              "test.json: solver.max_element_edge: expected a number in (0, inf), found the number 0");
  expectError(sceneWith(m, kSquare, R"("camera": {"eye": [0,0,0], "target": [0,0,0], "up": [0,1,0]})"),
              "test.json: camera.target: expected a target away from the eye, found the eye");
  expectError(sceneWith(m, R"([{"material": "m", "polygon": [[0,0,0],[2,0,0],[0,2,0]],
                                "holes": [[[0.5,0.5,0.5],[1,0.5,0.5],[0.5,1,0.5]]]}])"),
              "test.json: surfaces[0].holes[0][0]: expected a hole vertex in the plane of its polygon, found a point");
  expectError(sceneWith(m, R"([{"material": "m", "polygon": [[0,0,0],[1,1,0],[1,0,0],[0,1,0]]}])"),
              "test.json: surfaces[0].polygon: expected a polygon of non-zero area, found area");
  expectError(sceneWith(m, kSquare, R"("lights": [{"type": "point"}])"),
              "test.json: lights[0]: expected a \"position\" key for a point light, found none");
  expectError(sceneWith(m, R"([{"name": "a", "material": "m", "polygon": [[0,0,0],[1,0,0],[0,1,0]]},
                                {"name": "a", "material": "m", "polygon": [[0,0,0],[1,0,0],[0,1,0]]}])"),
              "test.json: surfaces[1].name: expected a name no other surface has, found the string \"a\"");
  expectError(sceneWith(R"({"m": {"emission": [1, 1, 1]}})", kSquare),
              "test.json: materials.m: expected \"reflectance\", \"diffuse\" or \"preset\", found none of them");
}

TEST(SceneTest, SelfCrossingPolygonIsRejectedWhenMeshed) {
  // A bow tie: edges cross. Its Newell area is zero when symmetric, so make it lopsided.
  Scene s = parse(sceneWith(R"({"m": {"reflectance": [0.5, 0.5, 0.5]}})",
                            R"([{"material": "m", "polygon": [[0,0,0],[3,0,0],[0,1,0],[1,2,0],[1,-1,0]]}])"));
  test::expectError([&] { buildPatchMesh(s, {0.5, 1.0}); },
                    {"test.json: surfaces[0]: ", "expected a simple polygon whose holes lie inside it",
                     "found edges that cross each other"});
}

}  // namespace
}  // namespace rad
