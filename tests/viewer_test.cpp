// The offscreen viewer: both backends draw the same picture of a solved Cornell box, the picture
// shows what the scene holds (red left wall, green right wall, the light brightest), flat shading
// shows each element's own value, and bad input is reported as the CLI contract says.
//
// Input: tests/data/cornell_coarse_result.ply, a coarse Cornell result kept as a file (made once by
// `radiosity solve scenes/cornell.json --max-element-edge 80 --max-patch-edge 160`), so that the
// viewer's tests and golden images do not change with the solver. Remake it only on purpose (a
// change of the result file's contract), and the golden images with it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>

#include "display/raster/raster.h"
#include "display/viewer/viewer.h"
#include "mesh/base/color.h"
#include "mesh/base/error.h"
#include "mesh/base/ply_writer.h"
#include "mesh/results/result_file.h"
#include "mesh/scene/readers/scene_loader.h"
#include "tests/support.h"

namespace rad::viewer {
namespace {

constexpr double kPi = 3.14159265358979323846;

class ViewerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    mesh_ = new ResultFile(readResultFile(RAD_VIEWER_INPUT));
  }
  static void TearDownTestSuite() {
    delete mesh_;
    mesh_ = nullptr;
  }
  static RenderOptions options(Backend backend, Shading shade, int size = 256) {
    RenderOptions o;
    o.width = o.height = size;
    o.backend = backend;
    o.shade = shade;
    return o;
  }
  static const ResultFile& mesh() { return *mesh_; }
  static ResultFile* mesh_;
};
ResultFile* ViewerTest::mesh_ = nullptr;

struct Agreement {
  double meanAbs = 0;     // per channel, in units of 1/255
  double shareOver4 = 0;  // pixels with some channel differing by more than 4/255
  double shareAny = 0;    // pixels differing at all
  int maxDiff = 0;
};

Agreement compare(const Image& a, const Image& b) {
  Agreement r;
  size_t over = 0, pixels = size_t(a.width) * a.height;
  for (size_t p = 0; p < pixels; ++p) {
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      int d = std::abs(int(a.rgb[p * 3 + c]) - int(b.rgb[p * 3 + c]));
      r.meanAbs += d;
      worst = std::max(worst, d);
    }
    over += worst > 4;
    r.shareAny += worst > 0;
    r.maxDiff = std::max(r.maxDiff, worst);
  }
  r.shareAny /= pixels;
  r.meanAbs /= 3.0 * pixels;
  r.shareOver4 = double(over) / pixels;
  return r;
}

TEST_F(ViewerTest, ReadsTheResultFile) {
  EXPECT_GT(mesh().faces.size(), 500u);
  ASSERT_TRUE(mesh().camera.has_value());
  EXPECT_DOUBLE_EQ(mesh().camera->eye.z, -800);
  EXPECT_NEAR(mesh().camera->fovYDeg, 39.3077, 1e-9);
  ASSERT_TRUE(mesh().exposure.has_value());
  EXPECT_GT(*mesh().exposure, 0);
}

TEST_F(ViewerTest, BackendsDrawTheSamePicture) {
  for (Shading shade : {Shading::Smooth, Shading::Flat}) {
    Image gl = render(mesh(), options(Backend::OsMesa, shade));
    Image sw = render(mesh(), options(Backend::Software, shade));
    Agreement a = compare(gl, sw);
    const char* name = shade == Shading::Smooth ? "smooth" : "flat";
    std::printf("[ viewer   ] %s 256x256: mean |difference| %.5f/255 per channel, %.4f%% of pixels "
                "> 4/255, %.4f%% differ at all, largest %d/255\n",
                name, a.meanAbs, 100 * a.shareOver4, 100 * a.shareAny, a.maxDiff);
    EXPECT_LE(a.meanAbs, 1.0) << name;
    EXPECT_LE(a.shareOver4, 0.005) << name;
  }
}

TEST_F(ViewerTest, SupersampledBackendsAgree) {
  RenderOptions o = options(Backend::OsMesa, Shading::Smooth, 128);
  o.ssaa = 3;
  Image gl = render(mesh(), o);
  o.backend = Backend::Software;
  Image sw = render(mesh(), o);
  Agreement a = compare(gl, sw);
  EXPECT_LE(a.meanAbs, 1.0);
  EXPECT_LE(a.shareOver4, 0.005);
  // Supersampling only smooths: on average it stays close to the plain picture.
  Image plain = render(mesh(), options(Backend::Software, Shading::Smooth, 128));
  EXPECT_LE(compare(plain, sw).meanAbs, 2.0);
}

/// Mean display colour over the pixels whose face satisfies `pick`, and the pixel count.
template <class Pick>
std::pair<glm::dvec3, size_t> regionMean(const ResultFile& mesh, const Image& image,
                                         const std::vector<uint32_t>& ids, Pick pick) {
  glm::dvec3 sum(0.0);
  size_t n = 0;
  for (size_t p = 0; p < ids.size(); ++p) {
    if (ids[p] == raster::kNoItem || !pick(mesh.faces[ids[p]])) continue;
    sum += glm::dvec3(image.rgb[p * 3], image.rgb[p * 3 + 1], image.rgb[p * 3 + 2]);
    ++n;
  }
  return {n ? sum / double(n) : sum, n};
}

TEST_F(ViewerTest, PictureShowsRedAndGreenWallsAndTheLight) {
  const ResultFile& m = mesh();
  auto all = [&](auto test) {
    return [&m, test](const std::array<int, 3>& f) {
      return test(m.positions[f[0]]) && test(m.positions[f[1]]) && test(m.positions[f[2]]);
    };
  };
  auto redWall = all([](glm::vec3 p) { return p.x > 540; });   // x ≈ 552..556, left in the image
  auto greenWall = all([](glm::vec3 p) { return p.x < 1; });   // x = 0, right in the image
  auto light = all([](glm::vec3 p) {
    return p.y > 548 && p.x >= 212.9f && p.x <= 343.1f && p.z >= 226.9f && p.z <= 332.1f;
  });
  auto ceiling = all([](glm::vec3 p) { return p.y > 548; });
  auto floor = all([](glm::vec3 p) { return p.y < 0.5f; });
  auto back = all([](glm::vec3 p) { return p.z > 559; });
  for (Backend backend : {Backend::OsMesa, Backend::Software}) {
    RenderOptions o = options(backend, Shading::Smooth);
    Image image = render(m, o);
    std::vector<uint32_t> ids = renderFaceIds(m, o);
    auto [red, nRed] = regionMean(m, image, ids, redWall);
    auto [green, nGreen] = regionMean(m, image, ids, greenWall);
    auto [lamp, nLamp] = regionMean(m, image, ids, light);
    ASSERT_GT(nRed, 1000u);
    ASSERT_GT(nGreen, 1000u);
    ASSERT_GT(nLamp, 50u);
    EXPECT_GT(red.r, 1.5 * red.g);
    EXPECT_GT(red.r, 1.5 * red.b);
    EXPECT_GT(green.g, 1.2 * green.r);
    EXPECT_GT(green.g, 1.5 * green.b);
    // The red wall is on the left half of the picture, the green one on the right.
    double redX = 0, greenX = 0;
    for (size_t p = 0; p < ids.size(); ++p) {
      if (ids[p] == raster::kNoItem) continue;
      if (redWall(m.faces[ids[p]])) redX += double(p % o.width) / nRed;
      if (greenWall(m.faces[ids[p]])) greenX += double(p % o.width) / nGreen;
    }
    EXPECT_LT(redX, o.width / 2);
    EXPECT_GT(greenX, o.width / 2);
    // The light is the brightest region: saturated white, above every other surface.
    auto lum = [](glm::dvec3 c) { return luminance(c); };
    EXPECT_GT(lamp.r, 250);
    EXPECT_GT(lamp.g, 250);
    EXPECT_GT(lamp.b, 250);
    auto notLight = [&](const std::array<int, 3>& f) { return ceiling(f) && !light(f); };
    for (auto region : {regionMean(m, image, ids, redWall), regionMean(m, image, ids, greenWall),
                        regionMean(m, image, ids, notLight), regionMean(m, image, ids, floor),
                        regionMean(m, image, ids, back)}) {
      ASSERT_GT(region.second, 100u);
      EXPECT_GT(lum(lamp), lum(region.first) + 20);
    }
  }
}

/// Distance in the floor plane from (x, z) to a block's footprint (0 inside).
double footprintDistance(glm::dvec2 p, const std::vector<glm::dvec2>& quad) {
  bool inside = true;
  double best = HUGE_VAL;
  for (size_t k = 0; k < quad.size(); ++k) {
    glm::dvec2 a = quad[k], b = quad[(k + 1) % quad.size()], d = b - a;
    double cross = d.x * (p.y - a.y) - d.y * (p.x - a.x);
    inside = inside && cross <= 0;  // both footprints are listed clockwise seen from above (+y)
    double t = std::clamp(glm::dot(p - a, d) / glm::dot(d, d), 0.0, 1.0);
    best = std::min(best, glm::length(a + t * d - p));
  }
  return inside ? 0.0 : best;
}

// The floor around the blocks' bases (occluded and in their shadow) is darker than the open floor.
TEST_F(ViewerTest, FloorAroundTheBlocksIsDarkerThanTheOpenFloor) {
  const ResultFile& m = mesh();
  const std::vector<glm::dvec2> shortBlock = {{130, 65}, {82, 225}, {240, 272}, {290, 114}};
  const std::vector<glm::dvec2> tallBlock = {{423, 247}, {265, 296}, {314, 456}, {472, 406}};
  auto nearest = [&](const std::array<int, 3>& f) {
    glm::vec3 c = (m.positions[f[0]] + m.positions[f[1]] + m.positions[f[2]]) / 3.0f;
    glm::dvec2 p(c.x, c.z);
    return std::min(footprintDistance(p, shortBlock), footprintDistance(p, tallBlock));
  };
  auto onFloor = [&](const std::array<int, 3>& f) {
    return m.positions[f[0]].y < 0.5f && m.positions[f[1]].y < 0.5f && m.positions[f[2]].y < 0.5f;
  };
  auto aroundBases = [&](const std::array<int, 3>& f) {
    double d = nearest(f);
    return onFloor(f) && d > 0 && d < 40;
  };
  auto openFloor = [&](const std::array<int, 3>& f) { return onFloor(f) && nearest(f) > 120; };
  for (Backend backend : {Backend::OsMesa, Backend::Software}) {
    RenderOptions o = options(backend, Shading::Smooth);
    Image image = render(m, o);
    std::vector<uint32_t> ids = renderFaceIds(m, o);
    auto [around, nAround] = regionMean(m, image, ids, aroundBases);
    auto [open, nOpen] = regionMean(m, image, ids, openFloor);
    ASSERT_GT(nAround, 100u);
    ASSERT_GT(nOpen, 100u);
    EXPECT_LT(luminance(around) + 10, luminance(open));
  }
}

TEST_F(ViewerTest, FlatShadingShowsEachElementsOwnValue) {
  const ResultFile& m = mesh();
  const double k = *m.exposure;
  for (Backend backend : {Backend::Software, Backend::OsMesa}) {
    RenderOptions o = options(backend, Shading::Flat);
    Image image = render(m, o);
    std::vector<uint32_t> ids = renderFaceIds(m, o);
    size_t inside = 0, exact = 0, off = 0;
    std::map<uint32_t, std::array<uint8_t, 3>> seen;
    for (int y = 1; y + 1 < o.height; ++y)
      for (int x = 1; x + 1 < o.width; ++x) {
        size_t p = size_t(y) * o.width + x;
        uint32_t id = ids[p];
        if (id == raster::kNoItem) continue;
        bool interior = true;  // the 3x3 neighbourhood sees the same element
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) interior &= ids[p + dy * o.width + dx] == id;
        if (!interior) continue;
        ++inside;
        const glm::dvec3& b = m.faceRadiosity[id];
        std::array<uint8_t, 3> want = {displayByte(b.x, k), displayByte(b.y, k), displayByte(b.z, k)};
        std::array<uint8_t, 3> got = {image.rgb[p * 3], image.rgb[p * 3 + 1], image.rgb[p * 3 + 2]};
        if (got == want) ++exact;
        int worst = 0;
        for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(got[c]) - int(want[c])));
        off += worst > 1;
        // One colour per element.
        auto [it, fresh] = seen.emplace(id, got);
        if (!fresh) {
          EXPECT_EQ(it->second, got) << "element " << id;
        }
      }
    ASSERT_GT(inside, 10000u);
    if (backend == Backend::Software)
      EXPECT_EQ(exact, inside);
    else
      EXPECT_EQ(off, 0u);
    EXPECT_GT(seen.size(), 300u);
  }
}

TEST_F(ViewerTest, RadianceIsRadiosityOverPi) {
  const ResultFile& m = mesh();
  RenderOptions o = options(Backend::Software, Shading::Flat, 128);
  o.radiance = true;
  Image sw = render(m, o);
  std::vector<uint32_t> ids = renderFaceIds(m, o);
  o.backend = Backend::OsMesa;
  Image gl = render(m, o);
  ASSERT_EQ(sw.radiance.size(), size_t(128 * 128 * 3));
  ASSERT_EQ(gl.radiance.size(), sw.radiance.size());
  size_t checked = 0, agree = 0;
  for (size_t p = 0; p < ids.size(); ++p) {
    if (ids[p] == raster::kNoItem) continue;
    for (int c = 0; c < 3; ++c) {
      double want = m.faceRadiosity[ids[p]][c] / kPi;
      EXPECT_NEAR(sw.radiance[p * 3 + c], want, 1e-5 * (1 + want));
      agree += std::abs(gl.radiance[p * 3 + c] - want) <= 1e-4 * (1 + want);
      ++checked;
    }
  }
  EXPECT_GT(checked, 30000u);
  EXPECT_GE(agree, size_t(0.995 * checked));  // edge pixels may see a neighbour
}

TEST_F(ViewerTest, WritesPngAndHdrAtomically) {
  RenderOptions o = options(Backend::Software, Shading::Smooth, 32);
  o.radiance = true;
  Image image = render(mesh(), o);
  const std::string png = std::string(RAD_VIEWER_OUT) + "/unit.png", hdr = std::string(RAD_VIEWER_OUT) + "/unit.hdr";
  writePng(png, image);
  writeHdr(hdr, image);
  EXPECT_GT(std::filesystem::file_size(png), 100u);
  EXPECT_GT(std::filesystem::file_size(hdr), 100u);
  const std::string nowhere = std::string(RAD_VIEWER_OUT) + "/no_such_folder/x.png";
  test::expectError([&] { writePng(nowhere, image); },
                    {nowhere + ": expected an output file in an existing folder", "found no folder"});
}

TEST_F(ViewerTest, WireframeDarkensThePicture) {
  for (Backend backend : {Backend::OsMesa, Backend::Software}) {
    RenderOptions o = options(backend, Shading::Smooth, 64);
    o.wireframe = true;
    Image wire = render(mesh(), o);
    o.wireframe = false;
    Image plain = render(mesh(), o);
    // Edges darken the picture.
    double sumWire = 0, sumPlain = 0;
    for (size_t i = 0; i < wire.rgb.size(); ++i) {
      sumWire += wire.rgb[i];
      sumPlain += plain.rgb[i];
    }
    EXPECT_LT(sumWire, 0.95 * sumPlain) << (backend == Backend::OsMesa ? "osmesa" : "software");
  }
}

TEST_F(ViewerTest, WireframeBackendsAgree) {
  for (int size : {128, 256}) {
    RenderOptions o = options(Backend::OsMesa, Shading::Smooth, size);
    o.wireframe = true;
    Image gl = render(mesh(), o);
    o.backend = Backend::Software;
    Image sw = render(mesh(), o);
    Agreement a = compare(gl, sw);
    // Share of pixels of the wireframe colour in each picture (how much is line).
    size_t linesGl = 0, linesSw = 0;
    for (size_t p = 0; p < gl.rgb.size() / 3; ++p) {
      linesGl += gl.rgb[p * 3] == detail::kWireByte && gl.rgb[p * 3 + 1] == detail::kWireByte;
      linesSw += sw.rgb[p * 3] == detail::kWireByte && sw.rgb[p * 3 + 1] == detail::kWireByte;
    }
    std::printf("[ viewer   ] wireframe %dx%d: %.3f%% of pixels > 4/255, mean |difference| %.3f/255; "
                "line pixels %.2f%% (osmesa) %.2f%% (software)\n",
                size, size, 100 * a.shareOver4, a.meanAbs, 100.0 * linesGl / (gl.rgb.size() / 3),
                100.0 * linesSw / (sw.rgb.size() / 3));
    EXPECT_LE(a.shareOver4, 0.01) << size;  // measured: 0.44 % at 128, 0.24 % at 256
  }
}

// ---- Hybrid: radiosity diffuse plus fixed-function specular ----------------------------------

Scene cornellScene() { return loadScene(std::string(RAD_SCENES) + "/cornell.json"); }

int materialIndexOf(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == name) return int(i);
  ADD_FAILURE() << "no material " << name;
  return 0;
}

TEST_F(ViewerTest, HybridWithoutSpecularIsTheRadiosityPicture) {
  ASSERT_EQ(mesh().faceSurface.size(), mesh().faces.size());
  ASSERT_EQ(mesh().vertexNormal.size(), mesh().positions.size());
  const Scene scene = cornellScene();  // no material has a specular colour
  for (Shading shade : {Shading::Smooth, Shading::Flat}) {
    const RenderOptions o = options(Backend::OsMesa, shade, 128);
    Agreement a = compare(renderHybrid(mesh(), scene, o), render(mesh(), o));
    EXPECT_LE(a.maxDiff, 1) << (shade == Shading::Smooth ? "smooth" : "flat");
  }
}

TEST_F(ViewerTest, HybridAddsAHighlightWhereTheMaterialIsSpecular) {
  Scene shiny = cornellScene();
  Material& white = shiny.materials[size_t(materialIndexOf(shiny, "white"))];
  white.specular = glm::dvec4(1, 1, 1, 1);
  white.shininess = 30;
  const RenderOptions o = options(Backend::OsMesa, Shading::Smooth, 128);
  const Image plain = render(mesh(), o), hybrid = renderHybrid(mesh(), shiny, o);
  // Where the highlight should be: on the back wall behind the light (infinite viewer).
  const glm::mat4 mvp = viewProjection(mesh(), effectiveCamera(mesh(), o), o.width, o.height);
  const glm::vec4 c = mvp * glm::vec4(278, 530, 559.2f, 1);
  const int hx = int(std::floor((c.x / c.w * 0.5 + 0.5) * o.width));
  const int hy = o.height - 1 - int(std::floor((c.y / c.w * 0.5 + 0.5) * o.height));
  int darker = 0, peak = 0;
  for (int y = 0; y < o.height; ++y)
    for (int x = 0; x < o.width; ++x) {
      const size_t p = (size_t(y) * o.width + x) * 3;
      int gain = 0;
      for (int k = 0; k < 3; ++k) {
        const int d = int(hybrid.rgb[p + k]) - int(plain.rgb[p + k]);
        darker += d < -1;
        gain += d;
      }
      if (std::abs(x - hx) <= 3 && std::abs(y - hy) <= 3) peak = std::max(peak, gain);
    }
  std::printf("[ viewer   ] hybrid highlight: +%d (sum of channels) near the back wall behind the light\n", peak);
  EXPECT_EQ(darker, 0) << "the specular term only adds";
  EXPECT_GT(peak, 60) << "no highlight on the back wall behind the light";
}

/// What hybrid mode and the ladder both refuse, `mode` as their messages name it: the software
/// backend, the radiance image and a result without the face property `surface`.
template <class Draw>
void expectCommonRefusals(Draw draw, const ResultFile& mesh, const std::string& mode) {
  RenderOptions osmesa;
  osmesa.width = osmesa.height = 16;
  RenderOptions software = osmesa, radiance = osmesa;
  software.backend = Backend::Software;
  test::expectError([&] { draw(mesh, software); }, {mode + ": expected --backend osmesa", "found --backend software"});
  radiance.radiance = true;
  test::expectError([&] { draw(mesh, radiance); }, {mode + ": expected no --hdr", "found --hdr"});
  ResultFile noSurfaces = mesh;
  noSurfaces.faceSurface.clear();
  test::expectError([&] { draw(noSurfaces, osmesa); },
                   {mesh.path + ": expected a result with the face property `surface` (for " + mode + ")", "found none"});
}

TEST_F(ViewerTest, HybridRefusesWhatItCannotDraw) {
  const Scene scene = cornellScene();
  expectCommonRefusals([&](const ResultFile& m, const RenderOptions& o) { renderHybrid(m, scene, o); },
                       mesh(), "--mode hybrid");
  const RenderOptions o = options(Backend::OsMesa, Shading::Smooth, 16);
  Scene fewer = scene;
  fewer.surfaces.resize(2);
  test::expectError([&] { renderHybrid(mesh(), fewer, o); },
                   {mesh().path + ": face ", ": surface: expected a surface index of " + scene.path + " (0..1)"});
  Scene dark = scene;
  dark.lights.clear();
  test::expectError([&] { renderHybrid(mesh(), dark, o); },
                   {scene.path + ": expected a scene with lights for --mode hybrid, found none"});
}

// ---- The realism ladder -------------------------------------------------------------------------

TEST_F(ViewerTest, LadderIsAGridOfDistinctTiles) {
  const Scene scene = cornellScene();
  RenderOptions o = options(Backend::OsMesa, Shading::Smooth, 0);
  o.width = 64;
  o.height = 48;
  const Image grid = renderLadder(mesh(), scene, o);
  ASSERT_EQ(grid.width, 64 * kLadderColumns);
  ASSERT_EQ(grid.height, 48 * 2);
  ASSERT_EQ(grid.rgb.size(), size_t(grid.width) * grid.height * 3);
  auto tile = [&](int cell) {
    Image t;
    t.width = o.width;
    t.height = o.height;
    const int x0 = (cell % kLadderColumns) * o.width, y0 = (cell / kLadderColumns) * o.height;
    for (int y = 0; y < o.height; ++y)
      t.rgb.insert(t.rgb.end(), &grid.rgb[(size_t(y0 + y) * grid.width + x0) * 3],
                   &grid.rgb[(size_t(y0 + y) * grid.width + x0 + o.width) * 3]);
    return t;
  };
  std::vector<Image> tiles;
  for (int i = 0; i < kLadderTiles; ++i) tiles.push_back(tile(i));
  for (int i = 0; i < kLadderTiles; ++i) {
    double mean = 0;
    for (uint8_t b : tiles[size_t(i)].rgb) mean += b;
    EXPECT_GT(mean / tiles[size_t(i)].rgb.size(), 10.0) << "tile " << i << " is (nearly) black";
    for (int j = i + 1; j < kLadderTiles; ++j) {
      const Agreement a = compare(tiles[size_t(i)], tiles[size_t(j)]);
      EXPECT_GT(a.shareOver4, 0.01) << "tiles " << i << " and " << j << " are (nearly) the same";
    }
  }
  // The empty cell stays black; the radiosity tiles are the plain renders.
  const Image empty = tile(kLadderTiles);
  EXPECT_TRUE(std::all_of(empty.rgb.begin(), empty.rgb.end(), [](uint8_t b) { return b == 0; }));
  RenderOptions flat = o;
  flat.shade = Shading::Flat;
  EXPECT_EQ(compare(tiles[5], render(mesh(), flat)).maxDiff, 0);
  EXPECT_EQ(compare(tiles[6], render(mesh(), o)).maxDiff, 0);
}

TEST_F(ViewerTest, LadderRefusesWhatItCannotDraw) {
  const Scene scene = cornellScene();
  expectCommonRefusals([&](const ResultFile& m, const RenderOptions& o) { renderLadder(m, scene, o); },
                       mesh(), "--ladder");
  RenderOptions o = options(Backend::OsMesa, Shading::Smooth, 16);
  o.wireframe = true;
  test::expectError([&] { renderLadder(mesh(), scene, o); }, {"--ladder: expected no --wireframe", "found --wireframe"});
}

// ---- Back-face culling (--cull back) -----------------------------------------------------------

/// Behind the box, looking at the outside of its back wall.
Camera behindTheBox() { return Camera{{278, 273, 1200}, {278, 273, 0}, {0, 1, 0}, 39.3}; }

bool onBackWall(const ResultFile& mesh, uint32_t face) {
  for (int v : mesh.faces[face])
    if (std::abs(mesh.positions[size_t(v)].z - 559.2f) > 0.5f) return false;
  return true;
}

TEST_F(ViewerTest, CullingChangesNothingFromInsideTheBox) {
  // From the file's camera every visible face is a front face (counter-clockwise on screen).
  for (Backend backend : {Backend::OsMesa, Backend::Software}) {
    RenderOptions o = options(backend, Shading::Smooth, 128);
    Image all = render(mesh(), o);
    o.cullBack = true;
    Agreement a = compare(all, render(mesh(), o));
    EXPECT_LT(a.shareAny, 0.002) << (backend == Backend::OsMesa ? "osmesa" : "software");
  }
}

TEST_F(ViewerTest, CullingRemovesTheOutsideOfTheBackWall) {
  RenderOptions o = options(Backend::Software, Shading::Smooth, 128);
  o.camera = behindTheBox();
  const size_t centre = size_t(64) * 128 + 64;
  std::vector<uint32_t> all = renderFaceIds(mesh(), o);
  ASSERT_NE(all[centre], raster::kNoItem);
  EXPECT_TRUE(onBackWall(mesh(), all[centre])) << "without culling the back wall hides the inside";
  o.cullBack = true;
  std::vector<uint32_t> culled = renderFaceIds(mesh(), o);
  size_t backWall = 0, seen = 0;
  for (uint32_t id : culled) {
    if (id == raster::kNoItem) continue;
    ++seen;
    backWall += onBackWall(mesh(), id);
  }
  EXPECT_EQ(backWall, 0u) << "the back wall's outside is drawn with culling";
  EXPECT_GT(seen, culled.size() / 4) << "the inside of the box is seen through the back wall";
  // And the pictures: both backends draw the inside, alike.
  Image software = render(mesh(), o);
  o.backend = Backend::OsMesa;
  Image osmesa = render(mesh(), o);
  Agreement a = compare(osmesa, software);
  EXPECT_LE(a.meanAbs, 1.0);
  EXPECT_LE(a.shareOver4, 0.005);
  o.cullBack = false;
  EXPECT_GT(compare(osmesa, render(mesh(), o)).shareOver4, 0.1) << "culling changed little";
}

TEST_F(ViewerTest, CulledWireframeBackendsAgree) {
  RenderOptions o = options(Backend::Software, Shading::Smooth, 128);
  o.camera = behindTheBox();
  o.cullBack = o.wireframe = true;
  Image software = render(mesh(), o);
  o.backend = Backend::OsMesa;
  Image osmesa = render(mesh(), o);
  Agreement a = compare(osmesa, software);
  EXPECT_LE(a.shareOver4, 0.01) << "mean " << a.meanAbs;
}

TEST(ViewerInput, MissingRadiosityPropertiesAreNamed) {
  PlyMesh ply;
  ply.vertex = {{"x", PlyColumn::Type::Float, {0, 1, 0}},
                {"y", PlyColumn::Type::Float, {0, 0, 1}},
                {"z", PlyColumn::Type::Float, {0, 0, 0}},
                {"radiosity_g", PlyColumn::Type::Float, {1, 1, 1}}};
  ply.faces = {{0, 1, 2}};
  ply.face = {{"surface", PlyColumn::Type::Int, {0}}};
  const std::string path = std::string(RAD_VIEWER_OUT) + "/unit_mesh_only.ply";
  writePly(path, ply);
  try {
    readResultFile(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": expected a radiosity result (vertex and face properties radiosity_r, "
                     "radiosity_g, radiosity_b, as `radiosity solve` writes), found a PLY without "
                     "vertex radiosity_r, vertex radiosity_b, face radiosity_r, face radiosity_g, "
                     "face radiosity_b");
  }
  const std::string nowhere = std::string(RAD_VIEWER_OUT) + "/nowhere.ply";
  test::expectError([&] { readResultFile(nowhere); }, {nowhere + ": expected", "found no such file"});
}

// The one reader and the one writer agree byte for byte: what the reader keeps is all the
// writer writes.
TEST(ViewerInput, ResultFileRoundTripsByteForByte) {
  const ResultFile read = readResultFile(RAD_VIEWER_INPUT);
  const std::string path = std::string(RAD_VIEWER_OUT) + "/unit_round_trip.ply";
  writeResultFile(path, read);
  auto bytes = [](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  const std::string original = bytes(RAD_VIEWER_INPUT), written = bytes(path);
  EXPECT_GT(original.size(), 1000u);
  EXPECT_TRUE(original == written) << path << " differs from " << RAD_VIEWER_INPUT;
}

TEST(ViewerInput, CameraText) {
  Camera base;
  base.eye = {0, 0, -5};
  base.target = {0, 0, 1};
  Camera c = parseCamera("eye=1,2,3,target=4,5,6,up=0,0,1,fov=30", base);
  EXPECT_EQ(c.eye, glm::dvec3(1, 2, 3));
  EXPECT_EQ(c.target, glm::dvec3(4, 5, 6));
  EXPECT_EQ(c.up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(c.fovYDeg, 30);
  Camera partial = parseCamera("fov=60", base);
  EXPECT_EQ(partial.eye, base.eye);
  EXPECT_EQ(partial.fovYDeg, 60);
  for (const char* bad : {"", "eye=1,2", "eye=1,2,3,4", "pos=1,2,3", "1,2,3", "eye=1,x,3", "fov=0",
                          "fov=180", "eye=0,0,1", "up=0,0,1", "fov=30,fov=40", "eye=1,2,nan"}) {
    try {
      parseCamera(bad, base);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("--camera: expected ", 0), 0u) << e.what();
    }
  }
}

}  // namespace
}  // namespace rad::viewer

namespace rad::viewer {
namespace {

// A converged result's stored colours are exactly sRGB(clamp(K·B)), so drawing them or
// computing them gives the same list; an unconverged result's carry the ambient term too.
TEST(ViewerColours, StoredColoursAreTheComputedOnesOnceConverged) {
  ResultFile mesh = readResultFile(RAD_VIEWER_INPUT);
  ASSERT_FALSE(mesh.vertexColour.empty());
  ASSERT_TRUE(mesh.exposure.has_value());
  auto stored = detail::buildDrawList(mesh, Shading::Smooth, *mesh.exposure, true);
  auto computed = detail::buildDrawList(mesh, Shading::Smooth, *mesh.exposure, false);
  ASSERT_EQ(stored.display.size(), computed.display.size());
  int differing = 0;
  for (size_t i = 0; i < stored.display.size(); ++i)
    differing += glm::length(stored.display[i] - computed.display[i]) > 1.5f / 255;
  EXPECT_EQ(differing, 0);
}

}  // namespace
}  // namespace rad::viewer

// ---- Local-illumination mode: the scene lit by OpenGL's fixed-function model ------------------
namespace rad::viewer {
namespace {

constexpr int kLocalSize = 128;

RenderOptions localOptions(int size = kLocalSize) {
  RenderOptions o;
  o.width = o.height = size;
  return o;
}

/// Mean colour (0-255 per channel) of the (2r+1)² pixels around (x, y), top row first.
glm::dvec3 meanAround(const Image& image, int x, int y, int r = 2) {
  glm::dvec3 sum(0.0);
  int n = 0;
  for (int j = y - r; j <= y + r; ++j)
    for (int i = x - r; i <= x + r; ++i) {
      if (i < 0 || j < 0 || i >= image.width || j >= image.height) continue;
      const uint8_t* p = &image.rgb[(size_t(j) * image.width + i) * 3];
      sum += glm::dvec3(p[0], p[1], p[2]);
      ++n;
    }
  return n ? sum / double(n) : sum;
}

/// The pixel (x, y, top row first) where the world point p lands in a render of `local`.
glm::ivec2 pixelOf(const LocalScene& local, const RenderOptions& o, const glm::dvec3& p) {
  ResultFile bounds;
  bounds.boundsMin = local.boundsMin;
  bounds.boundsMax = local.boundsMax;
  glm::mat4 mvp = viewProjection(bounds, effectiveCamera(local, o), o.width, o.height);
  glm::vec4 c = mvp * glm::vec4(glm::vec3(p), 1.0f);
  double x = (c.x / c.w * 0.5 + 0.5) * o.width, y = (c.y / c.w * 0.5 + 0.5) * o.height;
  return {int(std::floor(x)), o.height - 1 - int(std::floor(y))};
}

int materialIndex(const Scene& scene, const std::string& name) {
  for (size_t i = 0; i < scene.materials.size(); ++i)
    if (scene.materials[i].name == name) return int(i);
  ADD_FAILURE() << "no material " << name;
  return 0;
}

class LocalTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    cornell_ = new LocalScene(loadLocalScene(std::string(RAD_SCENES) + "/cornell.json"));
    empty_ = new LocalScene(loadLocalScene(std::string(RAD_SCENES) + "/cornell_empty.json"));
  }
  static void TearDownTestSuite() {
    delete cornell_;
    delete empty_;
    cornell_ = empty_ = nullptr;
  }
  static LocalScene* cornell_;
  static LocalScene* empty_;
};
LocalScene* LocalTest::cornell_ = nullptr;
LocalScene* LocalTest::empty_ = nullptr;

TEST_F(LocalTest, CornellShowsRedAndGreenWallsLitByThePointLight) {
  const RenderOptions o = localOptions();
  Image image = renderLocal(*cornell_, o);
  ASSERT_EQ(image.rgb.size(), size_t(kLocalSize) * kLocalSize * 3);
  // Every pixel inside the box's opening (all but a few border rows and columns, where the
  // black background shows) is lit, at least by the global ambient term.
  double mean = 0;
  size_t black = 0;
  const int border = kLocalSize / 16;
  for (int y = border; y < kLocalSize - border; ++y)
    for (int x = border; x < kLocalSize - border; ++x) {
      size_t p = (size_t(y) * kLocalSize + x) * 3;
      int sum = image.rgb[p] + image.rgb[p + 1] + image.rgb[p + 2];
      mean += sum / 3.0;
      black += sum == 0;
    }
  mean /= double(kLocalSize - 2 * border) * (kLocalSize - 2 * border);
  EXPECT_GT(mean, 40) << "the picture is nearly black";
  EXPECT_EQ(black, 0u) << "black pixels inside the box";

  // Red wall x = 556 (left in the picture), green wall x = 0 (right), halfway up and deep.
  glm::ivec2 red = pixelOf(*cornell_, o, {555, 274, 400});
  glm::ivec2 green = pixelOf(*cornell_, o, {1, 274, 400});
  EXPECT_LT(red.x, kLocalSize / 4);
  EXPECT_GT(green.x, 3 * kLocalSize / 4);
  glm::dvec3 r = meanAround(image, red.x, red.y), g = meanAround(image, green.x, green.y);
  EXPECT_GT(r.x, 2 * r.y) << "red wall " << r.x << " " << r.y << " " << r.z;
  EXPECT_GT(r.x, 2 * r.z);
  EXPECT_GT(r.x, 60);
  EXPECT_GT(g.y, 1.5 * g.x) << "green wall " << g.x << " " << g.y << " " << g.z;
  EXPECT_GT(g.y, 1.5 * g.z);
  EXPECT_GT(g.y, 60);
}

TEST_F(LocalTest, PointLightLightsTheFloorCentreMoreThanItsCorners) {
  // The empty box: nothing stands on the floor. The light is at (278, 540, 279.6).
  const RenderOptions o = localOptions();
  Image image = renderLocal(*empty_, o);
  glm::ivec2 centre = pixelOf(*empty_, o, {278, 0, 279.6});
  glm::ivec2 farLeft = pixelOf(*empty_, o, {500, 0, 500});
  glm::ivec2 farRight = pixelOf(*empty_, o, {50, 0, 500});
  double c = meanAround(image, centre.x, centre.y, 1).x;
  double l = meanAround(image, farLeft.x, farLeft.y, 1).x;
  double r = meanAround(image, farRight.x, farRight.y, 1).x;
  EXPECT_GT(c, l + 10) << "centre " << c << ", far left " << l;
  EXPECT_GT(c, r + 10) << "centre " << c << ", far right " << r;
}

TEST_F(LocalTest, SmoothAndFlatShadingBothDrawTheScene) {
  RenderOptions o = localOptions();
  Image smooth = renderLocal(*cornell_, o);
  o.shade = Shading::Flat;
  Image flat = renderLocal(*cornell_, o);
  // Same geometry and lighting: the pictures agree closely on average but are not identical.
  Agreement a = compare(smooth, flat);
  EXPECT_LT(a.meanAbs, 4.0);
  EXPECT_GT(a.shareAny, 0.01);
}

TEST_F(LocalTest, LinearFogLerpsDistantPixelsTowardsTheFogColour) {
  const RenderOptions o = localOptions();
  LocalScene fogged = *empty_;
  Fog fog;
  fog.mode = Fog::Mode::Linear;
  fog.color = glm::dvec4(0.2, 0.4, 0.9, 1.0);
  fog.start = 850;  // eye distance along the view axis; the camera is at z = -800
  fog.end = 1450;
  fogged.scene.fog = fog;
  Image clear = renderLocal(*empty_, o), foggy = renderLocal(fogged, o);
  // Back wall (eye depth 1359.2): fog factor f = (end - z) / (end - start).
  glm::ivec2 back = pixelOf(*empty_, o, {278, 420, 559.2});
  const double f = (fog.end - 1359.2) / (fog.end - fog.start);
  glm::dvec3 before = meanAround(clear, back.x, back.y, 1), after = meanAround(foggy, back.x, back.y, 1);
  for (int c = 0; c < 3; ++c) {
    double expect = f * before[c] + (1 - f) * 255 * fog.color[c];
    EXPECT_NEAR(after[c], expect, 8) << "channel " << c << ": before " << before[c];
  }
  // Near pixels (the front edge of the floor, eye depth about 810) keep their colour.
  glm::ivec2 near = pixelOf(*empty_, o, {278, 0, 10});
  glm::dvec3 n0 = meanAround(clear, near.x, near.y, 0), n1 = meanAround(foggy, near.x, near.y, 0);
  EXPECT_LT(glm::length(n0 - n1), 3.0) << "near floor " << n0.x << " vs " << n1.x;
}

TEST_F(LocalTest, SpecularHighlightOnlyWithSpecularMaterial) {
  const RenderOptions o = localOptions();
  // The Cornell materials have no specular colour: switching the light's specular off changes
  // nothing.
  LocalScene noLightSpecular = *cornell_;
  noLightSpecular.scene.lights[0].specular = glm::dvec4(0, 0, 0, 1);
  Image plain = renderLocal(*cornell_, o);
  EXPECT_EQ(compare(plain, renderLocal(noLightSpecular, o)).maxDiff, 0);
  // A shiny white material: a highlight appears on the back wall behind the light (infinite
  // viewer: the half vector meets the back wall's normal where the light is straight in front).
  LocalScene shiny = *cornell_;
  Material& white = shiny.scene.materials[size_t(materialIndex(shiny.scene, "white"))];
  white.specular = glm::dvec4(1, 1, 1, 1);
  white.shininess = 30;
  Image highlighted = renderLocal(shiny, o);
  // (The ceiling also catches a grazing highlight near the front: N·L is barely positive there
  // and the half vector is almost its normal, as fixed-function OpenGL computes it.)
  const glm::ivec2 behindLight = pixelOf(*cornell_, o, {278, 530, 559.2});
  const glm::ivec2 backCentre = pixelOf(*cornell_, o, {400, 300, 559.2});
  int darker = 0, peak = 0;
  for (int y = 0; y < kLocalSize; ++y)
    for (int x = 0; x < kLocalSize; ++x) {
      size_t p = (size_t(y) * kLocalSize + x) * 3;
      int gain = 0;
      for (int c = 0; c < 3; ++c) {
        int d = int(highlighted.rgb[p + c]) - int(plain.rgb[p + c]);
        darker += d < -1;
        gain += d;
      }
      if (std::abs(x - behindLight.x) <= 3 && std::abs(y - behindLight.y) <= 3) peak = std::max(peak, gain);
    }
  EXPECT_EQ(darker, 0) << "specular light only adds";
  EXPECT_GT(peak, 120) << "no highlight on the back wall behind the light";
  // Lower on the back wall, away from the mirror direction, the highlight has faded.
  glm::dvec3 lower0 = meanAround(plain, backCentre.x, backCentre.y, 1);
  glm::dvec3 lower1 = meanAround(highlighted, backCentre.x, backCentre.y, 1);
  EXPECT_LT(lower1.x - lower0.x, 0.5 * peak / 3);
}

// ---- Lights, attenuation, fog and the light model, on in-memory variants of the empty box -------

/// The global ambient term alone on a white surface (light model ambient 0.2 × material ambient,
/// the reflectance): the byte a surface shows that no light reaches.
double ambientByte(const LocalScene& local, int channel = 0) {
  const Material& white = local.scene.materials[size_t(materialIndex(local.scene, "white"))];
  return 255 * local.scene.lightModel.ambient[channel] * white.reflectance[channel];
}

Light whiteLight(Light::Type type) {
  Light l;
  l.type = type;
  l.diffuse = glm::dvec4(1, 1, 1, 1);
  l.specular = glm::dvec4(0, 0, 0, 1);
  return l;
}

TEST_F(LocalTest, DirectionalLightLightsSurfacesFacingIt) {
  const RenderOptions o = localOptions();
  const glm::ivec2 floor = pixelOf(*empty_, o, {278, 0, 280});
  const glm::ivec2 ceiling = pixelOf(*empty_, o, {278, 548.8, 120});
  const double ambient = ambientByte(*empty_);
  for (double up : {1.0, -1.0}) {
    LocalScene lit = *empty_;
    Light sun = whiteLight(Light::Type::Directional);
    sun.direction = glm::dvec3(0, up, 0);  // towards the light: above (up = 1) or below
    lit.scene.lights = {sun};
    Image image = renderLocal(lit, o);
    const double f = meanAround(image, floor.x, floor.y, 1).x;
    const double c = meanAround(image, ceiling.x, ceiling.y, 1).x;
    const double facing = up > 0 ? f : c, away = up > 0 ? c : f;
    // Facing the light: ambient + full diffuse (N·L = 1); facing away: the ambient term only.
    EXPECT_NEAR(facing, ambient + 255 * 0.725, 3) << "up " << up;
    EXPECT_NEAR(away, ambient, 2) << "up " << up;
  }
}

TEST_F(LocalTest, SpotLightLightsItsConeAndTheExponentConcentratesIt) {
  const RenderOptions o = localOptions();
  const glm::dvec3 lamp(278, 540, 279.6);
  const glm::ivec2 axis = pixelOf(*empty_, o, {278, 0, 279.6});
  // 12° off the axis (inside the 20° cone) and 30° off it (outside).
  const glm::ivec2 inside = pixelOf(*empty_, o, {278 + 540 * std::tan(12 * kPi / 180), 0, 279.6});
  const glm::ivec2 outside = pixelOf(*empty_, o, {500, 0, 500});
  const double ambient = ambientByte(*empty_);
  double share[2] = {0, 0};  // lit part 12° off the axis over the lit part on it
  const double exponents[2] = {0, 60};
  for (int k = 0; k < 2; ++k) {
    LocalScene lit = *empty_;
    Light spot = whiteLight(Light::Type::Spot);
    spot.position = lamp;
    spot.direction = glm::dvec3(0, -1, 0);
    spot.cutoffDeg = 20;
    spot.exponent = exponents[k];
    lit.scene.lights = {spot};
    Image image = renderLocal(lit, o);
    const double a = meanAround(image, axis.x, axis.y, 1).x;
    const double i = meanAround(image, inside.x, inside.y, 0).x;
    const double out = meanAround(image, outside.x, outside.y, 1).x;
    // On the axis: ambient + full diffuse (exponent 0; with exponent 60 Gouraud shading spreads
    // the steep fall-off of the vertices around it).
    if (k == 0) EXPECT_NEAR(a, ambient + 255 * 0.725, 4);
    else EXPECT_GT(a, ambient + 120);
    EXPECT_GT(i, ambient + 30) << "exponent " << exponents[k];
    EXPECT_NEAR(out, ambient, 2) << "outside the cone, exponent " << exponents[k];
    share[k] = (i - ambient) / (a - ambient);
  }
  // Exponent 0: only N·L = cos 12° (0.98); exponent 60: times cos⁶⁰ 12° (0.27).
  EXPECT_GT(share[0], 0.85);
  EXPECT_LT(share[1], 0.6 * share[0]) << "exponent 0: " << share[0] << ", 60: " << share[1];
}

TEST_F(LocalTest, QuadraticAttenuationDarkensFarSurfaces) {
  const RenderOptions o = localOptions();
  // A lamp 100 mm above the floor and 409 mm in front of the back wall, facing both squarely.
  const glm::dvec3 lamp(278, 100, 150);
  const glm::ivec2 near = pixelOf(*empty_, o, {278, 0, 150});
  const glm::ivec2 far = pixelOf(*empty_, o, {278, 100, 559.2});
  const double ambient = ambientByte(*empty_);
  const double kq = 1e-4;
  double n[2], f[2];
  for (int k = 0; k < 2; ++k) {
    LocalScene lit = *empty_;
    Light point = whiteLight(Light::Type::Point);
    point.position = lamp;
    point.attenuation = glm::dvec3(1, 0, k ? kq : 0);
    lit.scene.lights = {point};
    Image image = renderLocal(lit, o);
    n[k] = meanAround(image, near.x, near.y, 0).x;
    f[k] = meanAround(image, far.x, far.y, 0).x;
  }
  // kc only: both facing the lamp squarely, the same brightness.
  // (Gouraud shading: the vertices around the near point see the lamp slightly obliquely.)
  EXPECT_NEAR(n[0], ambient + 255 * 0.725, 8);
  EXPECT_NEAR(f[0], ambient + 255 * 0.725, 8);
  // 1 / (kc + kq d²): 0.5 at 100 mm, 0.056 at 409.2 mm.
  EXPECT_NEAR(n[1], ambient + 255 * 0.725 / (1 + kq * 100 * 100), 12);
  EXPECT_NEAR(f[1], ambient + 255 * 0.725 / (1 + kq * 409.2 * 409.2), 6);
  EXPECT_LT(f[1] / n[1], 0.6 * f[0] / n[0]);
}

TEST_F(LocalTest, ExpAndExp2FogFollowOpenGLsFormulas) {
  const RenderOptions o = localOptions();
  const glm::ivec2 back = pixelOf(*empty_, o, {278, 420, 559.2});  // eye depth 1359.2
  const glm::ivec2 front = pixelOf(*empty_, o, {278, 0, 10});      // eye depth 810
  const Image clear = renderLocal(*empty_, o);
  const glm::dvec3 back0 = meanAround(clear, back.x, back.y, 1);
  const glm::dvec3 front0 = meanAround(clear, front.x, front.y, 0);
  for (Fog::Mode mode : {Fog::Mode::Exp, Fog::Mode::Exp2}) {
    LocalScene fogged = *empty_;
    Fog fog;
    fog.mode = mode;
    fog.color = glm::dvec4(0.2, 0.4, 0.9, 1.0);
    fog.density = 0.8 / 1359.2;  // d·z = 0.8 on the back wall
    fogged.scene.fog = fog;
    const Image foggy = renderLocal(fogged, o);
    auto factor = [&](double z) {
      const double dz = fog.density * z;
      return mode == Fog::Mode::Exp ? std::exp(-dz) : std::exp(-dz * dz);
    };
    const char* name = mode == Fog::Mode::Exp ? "exp" : "exp2";
    const glm::dvec3 back1 = meanAround(foggy, back.x, back.y, 1);
    const glm::dvec3 front1 = meanAround(foggy, front.x, front.y, 0);
    for (int c = 0; c < 3; ++c) {
      const double fb = factor(1359.2), ff = factor(810);
      EXPECT_NEAR(back1[c], fb * back0[c] + (1 - fb) * 255 * fog.color[c], 8)
          << name << " back wall, channel " << c;
      EXPECT_NEAR(front1[c], ff * front0[c] + (1 - ff) * 255 * fog.color[c], 8)
          << name << " front of the floor, channel " << c;
    }
  }
}

TEST_F(LocalTest, TwoSidedLightingLightsBackFacesWithTheReversedNormal) {
  // From behind the box the back wall shows its back face. The point light is inside the box:
  // one-sided lighting uses the front normal (towards the light: lit); two-sided lighting
  // reverses it for back faces (away from the light: the ambient term only).
  RenderOptions o = localOptions();
  o.camera = Camera{{278, 273, 1400}, {278, 273, 0}, {0, 1, 0}, 39.3};
  const glm::ivec2 wall = pixelOf(*empty_, o, {278, 300, 559.2});
  double value[2];
  for (int twoSided = 0; twoSided < 2; ++twoSided) {
    LocalScene lit = *empty_;
    lit.scene.lightModel.twoSided = twoSided == 1;
    lit.scene.lights = {whiteLight(Light::Type::Point)};
    lit.scene.lights[0].position = glm::dvec3(278, 540, 279.6);
    value[twoSided] = meanAround(renderLocal(lit, o), wall.x, wall.y, 1).x;
  }
  EXPECT_GT(value[0], ambientByte(*empty_) + 50) << "one-sided";
  EXPECT_NEAR(value[1], ambientByte(*empty_), 2) << "two-sided";
}

TEST_F(LocalTest, LocalViewerMovesTheSpecularHighlight) {
  // Camera inside the box facing the back wall, a lamp off to one side near the front. Infinite
  // viewer (V = +z in the eye): the highlight is on the back wall straight behind the lamp
  // (x = 100); local viewer: at the mirror point between lamp and eye (x = 200). Either way the
  // other point's half vector is about 6° off the wall's normal (cos¹⁰⁰ 6° = 0.58).
  RenderOptions o = localOptions();
  o.camera = Camera{{278, 273, 200}, {278, 273, 559.2}, {0, 1, 0}, 60};
  const glm::ivec2 behindLamp = pixelOf(*empty_, o, {100, 273, 559.2});
  const glm::ivec2 mirror = pixelOf(*empty_, o, {200, 273, 559.2});
  ASSERT_GT(std::abs(behindLamp.x - mirror.x), 20);
  double gainBehind[2], gainMirror[2];
  for (int local = 0; local < 2; ++local) {
    LocalScene scene = *empty_;
    scene.scene.lightModel.localViewer = local == 1;
    Light lamp = whiteLight(Light::Type::Point);
    lamp.diffuse = glm::dvec4(0, 0, 0, 1);  // specular only: no saturation near the highlight
    lamp.position = glm::dvec3(100, 273, 100);
    scene.scene.lights = {lamp};
    const Image plain = renderLocal(scene, o);
    scene.scene.lights[0].specular = glm::dvec4(1, 1, 1, 1);
    Material& white = scene.scene.materials[size_t(materialIndex(scene.scene, "white"))];
    white.specular = glm::dvec4(1, 1, 1, 1);
    white.shininess = 100;
    const Image shiny = renderLocal(scene, o);
    auto gain = [&](glm::ivec2 p) {
      return meanAround(shiny, p.x, p.y, 1).z - meanAround(plain, p.x, p.y, 1).z;
    };
    gainBehind[local] = gain(behindLamp);
    gainMirror[local] = gain(mirror);
  }
  EXPECT_GT(gainBehind[0], gainMirror[0] + 20) << "infinite viewer";
  EXPECT_GT(gainMirror[1], gainBehind[1] + 20) << "local viewer";
}

TEST_F(LocalTest, OptionsAndScenesTheLocalModelRefuses) {
  RenderOptions o = localOptions(16);
  o.backend = Backend::Software;
  test::expectError([&] { renderLocal(*cornell_, o); },
                    {"--mode local: expected --backend osmesa", "found --backend software"});
  o = localOptions(16);
  o.radiance = true;
  test::expectError([&] { renderLocal(*cornell_, o); }, {"--mode local: expected no --hdr", "found --hdr"});
  Scene dark = cornell_->scene;
  dark.lights.clear();
  test::expectError([&] { prepareLocalScene(dark); }, {"expected a scene with lights for --mode local, found none"});
}

}  // namespace
}  // namespace rad::viewer

// ---- Golden images: 128×128 OSMesa renders compared with tests/golden/*.png -------------------
// A pixel is bad when some channel differs by more than 3/255; at most 0.5 % may be bad. On
// failure actual, expected and difference (|a - e| × 16) PNGs land in RAD_VIEWER_OUT/golden/.
// A missing golden fails. RAD_REGENERATE_GOLDEN=1 rewrites the goldens instead of comparing.
namespace rad::viewer {
namespace {

constexpr int kGoldenSize = 128;
constexpr int kGoldenTolerance = 3;
constexpr double kGoldenBadShare = 0.005;

void checkGolden(const std::string& name, const Image& actual) {
  namespace fs = std::filesystem;
  const std::string golden = std::string(RAD_GOLDEN_DIR) + "/" + name + ".png";
  const char* regenerate = std::getenv("RAD_REGENERATE_GOLDEN");
  if (regenerate && std::string(regenerate) == "1") {
    writePng(golden, actual);
    std::cout << "[ golden   ] wrote " << golden << "\n";
    return;
  }
  const fs::path outDir = fs::path(RAD_VIEWER_OUT) / "golden";
  fs::create_directories(outDir);
  const std::string actualPath = (outDir / (name + "_actual.png")).string();
  if (!fs::exists(golden)) {
    writePng(actualPath, actual);
    ADD_FAILURE() << "missing golden image " << golden << " (actual picture: " << actualPath
                  << "; set RAD_REGENERATE_GOLDEN=1 to create it)";
    return;
  }
  const Image expected = readPng(golden);
  if (expected.width != actual.width || expected.height != actual.height) {
    writePng(actualPath, actual);
    ADD_FAILURE() << golden << " is " << expected.width << "x" << expected.height << ", the render "
                  << actual.width << "x" << actual.height << " (actual: " << actualPath << ")";
    return;
  }
  Image difference = actual;
  size_t bad = 0, pixels = size_t(actual.width) * actual.height;
  int worst = 0;
  for (size_t p = 0; p < pixels; ++p) {
    int pixelWorst = 0;
    for (int c = 0; c < 3; ++c) {
      int d = std::abs(int(actual.rgb[p * 3 + c]) - int(expected.rgb[p * 3 + c]));
      difference.rgb[p * 3 + c] = uint8_t(std::min(255, d * 16));
      pixelWorst = std::max(pixelWorst, d);
    }
    bad += pixelWorst > kGoldenTolerance;
    worst = std::max(worst, pixelWorst);
  }
  const double share = double(bad) / pixels;
  if (share > kGoldenBadShare) {
    const std::string expectedPath = (outDir / (name + "_expected.png")).string();
    const std::string diffPath = (outDir / (name + "_difference.png")).string();
    writePng(actualPath, actual);
    writePng(expectedPath, expected);
    writePng(diffPath, difference);
    ADD_FAILURE() << name << ": " << bad << " pixels (" << 100 * share << " %) differ by more than "
                  << kGoldenTolerance << "/255 from " << golden << " (at most "
                  << 100 * kGoldenBadShare << " % may; worst " << worst << "/255). See " << actualPath
                  << ", " << expectedPath << ", " << diffPath;
  }
}

TEST_F(ViewerTest, GoldenCornellRadiositySmooth) {
  checkGolden("cornell_radiosity_smooth",
              render(mesh(), options(Backend::OsMesa, Shading::Smooth, kGoldenSize)));
}

TEST_F(ViewerTest, GoldenCornellRadiosityFlat) {
  checkGolden("cornell_radiosity_flat",
              render(mesh(), options(Backend::OsMesa, Shading::Flat, kGoldenSize)));
}

TEST_F(LocalTest, GoldenCornellLocal) {
  checkGolden("cornell_local", renderLocal(*cornell_, localOptions(kGoldenSize)));
}

}  // namespace
}  // namespace rad::viewer
