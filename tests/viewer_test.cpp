// The offscreen viewer: both backends draw the same picture of a solved Cornell box, the picture
// shows what the scene holds (red left wall, green right wall, the light brightest), flat shading
// shows each element's own value, and bad input is reported as the CLI contract says.
//
// Input: the coarse Cornell result made by the CTest fixture viewer.make_input (or, when run by
// hand without it, by running the same `radiosity solve` here).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "display/raster.h"
#include "display/viewer.h"
#include "mesh/color.h"
#include "mesh/error.h"
#include "mesh/ply_writer.h"

namespace rad::viewer {
namespace {

constexpr double kPi = 3.14159265358979323846;

class ViewerTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    if (!std::filesystem::exists(RAD_VIEWER_INPUT)) {
      std::string command = std::string(RAD_VIEWER_SOLVE) + " 2>/dev/null";
      ASSERT_EQ(std::system(command.c_str()), 0) << command;
    }
    mesh_ = new ResultMesh(loadResult(RAD_VIEWER_INPUT));
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
  static const ResultMesh& mesh() { return *mesh_; }
  static ResultMesh* mesh_;
};
ResultMesh* ViewerTest::mesh_ = nullptr;

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

TEST_F(ViewerTest, ReadsTheResultMesh) {
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
std::pair<glm::dvec3, size_t> regionMean(const ResultMesh& mesh, const Image& image,
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
  const ResultMesh& m = mesh();
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

TEST_F(ViewerTest, FlatShadingShowsEachElementsOwnValue) {
  const ResultMesh& m = mesh();
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
  const ResultMesh& m = mesh();
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
  EXPECT_THROW(writePng(std::string(RAD_VIEWER_OUT) + "/no_such_folder/x.png", image), InputError);
}

TEST_F(ViewerTest, WireframeIsOpenGlOnly) {
  RenderOptions o = options(Backend::Software, Shading::Smooth, 64);
  o.wireframe = true;
  EXPECT_THROW(render(mesh(), o), InputError);
  o.backend = Backend::OsMesa;
  Image wire = render(mesh(), o);
  o.wireframe = false;
  Image plain = render(mesh(), o);
  // Edges darken the picture.
  double sumWire = 0, sumPlain = 0;
  for (size_t i = 0; i < wire.rgb.size(); ++i) {
    sumWire += wire.rgb[i];
    sumPlain += plain.rgb[i];
  }
  EXPECT_LT(sumWire, 0.95 * sumPlain);
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
    loadResult(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": expected a radiosity result (vertex and face properties radiosity_r, "
                     "radiosity_g, radiosity_b, as `radiosity solve` writes), found a PLY without "
                     "vertex radiosity_r, vertex radiosity_b, face radiosity_r, face radiosity_g, "
                     "face radiosity_b");
  }
  EXPECT_THROW(loadResult(std::string(RAD_VIEWER_OUT) + "/nowhere.ply"), InputError);
}

TEST(ViewerInput, CameraText) {
  ViewCamera base;
  base.eye = {0, 0, -5};
  ViewCamera c = parseCamera("eye=1,2,3,target=4,5,6,up=0,0,1,fov=30", base);
  EXPECT_EQ(c.eye, glm::dvec3(1, 2, 3));
  EXPECT_EQ(c.target, glm::dvec3(4, 5, 6));
  EXPECT_EQ(c.up, glm::dvec3(0, 0, 1));
  EXPECT_EQ(c.fovYDeg, 30);
  ViewCamera partial = parseCamera("fov=60", base);
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
  ResultMesh mesh = loadResult(RAD_VIEWER_INPUT);
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
