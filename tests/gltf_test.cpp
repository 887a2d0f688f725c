// glTF 2.0 scenes: the reader (node transforms, materials, modes, bad files) on small files
// written here, and the Cornell box exported to glTF (tests/data/cornell_gltf.py) solved as
// `radiosity solve` solves it, against the JSON scene it came from.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>

#include <glm/geometric.hpp>

#include "mesh/results/reference_points.h"
#include "mesh/scene/geometry.h"
#include "mesh/scene/readers/coplanar_faces.h"
#include "mesh/scene/readers/gltf_reader.h"
#include "mesh/scene/readers/scene_loader.h"
#include "radiosity/true_error.h"
#include "tests/solve_support.h"

namespace rad {
namespace {

/// Positions read back from float storage and moved by double transforms: this close (units).
constexpr double kPositionTolerance = 1e-5;
/// A corner of the Cornell box (mm, up to 560) stored as float and moved back by its node: this
/// close to the JSON's.
constexpr double kCornerTolerance = 1e-3;
/// Colours computed two ways in double precision: this close (relative).
constexpr double kColourTolerance = 1e-12;
/// The glTF Cornell box shows the JSON one's light within this RMS (relative, issue 15's
/// target) at the reference points.
constexpr double kSameLight = 0.01;
/// ... and its true error (against the path-traced reference) is the JSON one's within this.
constexpr double kSameTrueError = 0.0025;
/// Channels of the JSON solve below this share of its brightest shown value are not compared
/// (as the true error skips near-black ones).
constexpr double kDarkShare = 0.01;

/// Base64 of `bytes` (RFC 4648, padded), for data URIs.
std::string base64(const std::string& bytes) {
  static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t v = 0;
    for (size_t k = 0; k < 3; ++k) v = v << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? digits[(v >> (18 - 6 * k)) & 63] : '=';
  }
  return out;
}

/// A 2 x 2 PNG: red, green / blue, grey 128 (sRGB bytes).
const std::string kPng2x2 =
    "iVBORw0KGgoAAAANSUhEUgAAAAIAAAACCAIAAAD91JpzAAAAE0lEQVR4nGP4z8DAAMIM/xsaGgAc9AR+KYBA2AAAAABJRU5ErkJggg==";

/// The linear value of an sRGB byte (IEC 61966-2-1), written out here as the oracle.
double linearOf(int byte) {
  const double x = byte / 255.0;
  return x <= 0.04045 ? x / 12.92 : std::pow((x + 0.055) / 1.055, 2.4);
}

/// A small glTF file: one mesh "tri" of one primitive (float positions, unsigned short indices,
/// material 0) under the nodes given, its buffer a data URI.
struct SmallGltf {
  std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};  // a right triangle facing +z
  std::vector<uint16_t> indices = {0, 1, 2};
  int mode = 4;
  std::string nodes = R"([{"name": "part", "mesh": 0}])";
  std::string materials =
      R"([{"name": "paint", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1], "metallicFactor": 0}}])";
  std::string extra;  ///< more top-level members, each followed by a comma

  /// The file's JSON text.
  std::string text() const {
    std::string buffer(positions.size() * 4 + indices.size() * 2, '\0');
    std::memcpy(&buffer[0], positions.data(), positions.size() * 4);
    std::memcpy(&buffer[positions.size() * 4], indices.data(), indices.size() * 2);
    const std::string n = std::to_string(positions.size() / 3), m = std::to_string(indices.size());
    const std::string p = std::to_string(positions.size() * 4), q = std::to_string(indices.size() * 2);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}], )" + extra +
           R"("nodes": )" + nodes + R"(, "materials": )" + materials +
           R"(, "meshes": [{"name": "tri", "primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": )" +
           std::to_string(mode) + R"(, "material": 0}]}], )" +
           R"("accessors": [{"bufferView": 0, "componentType": 5126, "count": )" + n + R"(, "type": "VEC3"}, )" +
           R"({"bufferView": 1, "componentType": 5123, "count": )" + m + R"(, "type": "SCALAR"}], )" +
           R"("bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": )" + p + R"(}, )" +
           R"({"buffer": 0, "byteOffset": )" + p + R"(, "byteLength": )" + q + R"(}], )" +
           R"("buffers": [{"byteLength": )" + std::to_string(buffer.size()) +
           R"(, "uri": "data:application/octet-stream;base64,)" + base64(buffer) + R"("}]})";
  }
};

/// A file in the test's temporary folder with this text; its path.
std::string writeFile(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "gltf_test_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// The text with `from` (which must be there) replaced by `to`.
std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) ADD_FAILURE() << "'" << from << "' not in the file";
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

/// The groups of a glTF file with this text, and the reader's warnings.
struct Read {
  std::vector<MeshFileGroup> groups;
  std::vector<std::string> warnings;
};
Read readText(const std::string& name, const std::string& text) {
  Read r;
  r.groups = readGltfFile(writeFile(name, text), r.warnings);
  return r;
}

/// Expects a and b within kPositionTolerance.
void expectNear(const glm::dvec3& a, const glm::dvec3& b) {
  EXPECT_LE(glm::length(a - b), kPositionTolerance) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x
                                                    << ", " << b.y << ", " << b.z << ")";
}

/// The distance from q to the nearest of the points.
double nearestDistance(const glm::dvec3& q, const std::vector<glm::dvec3>& points) {
  double nearest = HUGE_VAL;
  for (const auto& p : points) nearest = std::min(nearest, glm::length(q - p));
  return nearest;
}

/// Whether some warning contains every part.
bool warned(const std::vector<std::string>& warnings, std::initializer_list<std::string> parts) {
  for (const auto& w : warnings) {
    bool all = true;
    for (const auto& p : parts) all = all && w.find(p) != std::string::npos;
    if (all) return true;
  }
  return false;
}

TEST(GltfReaderTest, OneTriangleWithItsMaterial) {
  const Read r = readText("one.gltf", SmallGltf().text());
  ASSERT_EQ(r.groups.size(), 1u);
  EXPECT_EQ(r.groups[0].material, "part/paint");
  ASSERT_EQ(r.groups[0].faces.size(), 1u);
  expectNear(r.groups[0].faces[0].outer[1], {1, 0, 0});
  EXPECT_EQ(*r.groups[0].kd, glm::dvec3(0.5, 0.25, 0.125));
  EXPECT_EQ(*r.groups[0].ke, glm::dvec3(0.0));
  EXPECT_TRUE(r.warnings.empty()) << r.warnings[0];
}

// The hierarchy:  parent (translation (10, 0, 0), scale 2)
//                   └ child (rotation 90° about z)  ─ the triangle (0,0,0) (1,0,0) (0,1,0)
// so (1,0,0) -> (0,1,0) -> (0,2,0) -> (10,2,0), and (0,1,0) -> (-1,0,0) -> (-2,0,0) -> (8,0,0).
TEST(GltfReaderTest, NodeTransformsComposeDownTheHierarchy) {
  SmallGltf g;
  const double h = std::sqrt(0.5);
  const std::string quaternion = "[0, 0, " + std::to_string(h) + ", " + std::to_string(h) + "]";
  g.nodes = R"([{"name": "parent", "translation": [10, 0, 0], "scale": [2, 2, 2], "children": [1]},
                {"name": "child", "rotation": )" + quaternion + R"(, "mesh": 0}])";
  const Read r = readText("hierarchy.gltf", g.text());
  ASSERT_EQ(r.groups.size(), 1u);
  EXPECT_EQ(r.groups[0].material, "child/paint");
  const Ring& t = r.groups[0].faces.at(0).outer;
  expectNear(t[0], {10, 0, 0});
  expectNear(t[1], {10, 2, 0});
  expectNear(t[2], {8, 0, 0});
}

// A column-major matrix moving by (1, 2, 3) and mirroring x: the winding flips back so that
// the face still faces +z (glTF 2.0 §3.7.4).
TEST(GltfReaderTest, MatrixAndMirrorKeepTheFacing) {
  SmallGltf g;
  g.nodes = R"([{"name": "m", "mesh": 0, "matrix": [-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1]}])";
  const Read r = readText("matrix.gltf", g.text());
  const Ring& t = r.groups.at(0).faces.at(0).outer;
  for (const auto& p : {glm::dvec3(1, 2, 3), glm::dvec3(0, 2, 3), glm::dvec3(1, 3, 3)})
    EXPECT_LE(nearestDistance(p, t), kPositionTolerance);
  EXPECT_GT(newellNormal(t).z, 0) << "a mirrored node must not turn its faces around";
}

TEST(GltfReaderTest, BaseColourTextureMeanTimesFactor) {
  SmallGltf g;
  g.materials = R"([{"name": "tex", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.5, 1, 1],
                    "baseColorTexture": {"index": 0}, "metallicFactor": 0}}])";
  g.extra = R"("textures": [{"source": 0}], "images": [{"uri": "data:image/png;base64,)" + kPng2x2 + R"("}], )";
  const Read r = readText("texture.gltf", g.text());
  const double grey = linearOf(128);
  const glm::dvec3 mean = glm::dvec3(1 + grey, 1 + grey, 1 + grey) / 4.0;  // red, green, blue, grey
  const glm::dvec3 kd = *r.groups.at(0).kd, expected = mean * glm::dvec3(0.5, 0.5, 1);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(kd[c], expected[c], kColourTolerance * expected[c]);
  EXPECT_TRUE(warned(r.warnings, {"'tex'", "mean colour of the base-colour texture"}));
}

TEST(GltfReaderTest, EmissionIsFactorTimesStrength) {
  SmallGltf g;
  g.materials = R"([{"name": "lamp", "emissiveFactor": [1, 0.5, 0], "pbrMetallicRoughness": {"metallicFactor": 0},
                    "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": 8}}}])";
  EXPECT_EQ(*readText("lamp.gltf", g.text()).groups.at(0).ke, glm::dvec3(8, 4, 0));
  g.materials = R"([{"name": "dim", "emissiveFactor": [1, 0.5, 0], "pbrMetallicRoughness": {"metallicFactor": 0}}])";
  EXPECT_EQ(*readText("dim.gltf", g.text()).groups.at(0).ke, glm::dvec3(1, 0.5, 0)) << "no strength: 1";
}

TEST(GltfReaderTest, MetalsGlassAndWhiteAreSaidOnce) {
  SmallGltf g;
  g.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  g.indices = {0, 1, 2, 2, 1, 3};
  g.materials = R"([{"name": "chrome", "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1}}}])";
  const Read r = readText("chrome.gltf", g.text());
  EXPECT_TRUE(warned(r.warnings, {"2 faces", "'chrome (metallic)'", "'chrome (transmissive)'", "treated as diffuse"}));
  EXPECT_TRUE(warned(r.warnings, {"'chrome'", "white", "0.95"}));
  EXPECT_EQ(*r.groups.at(0).kd, glm::dvec3(0.95)) << "glTF's default base colour, 1, capped";
  EXPECT_EQ(r.warnings.size(), 2u);
}

// A strip 0 1 2 3 makes (0 1 2) and (2 1 3); a fan 0 1 3 2 makes (1 3 0) and (3 2 0). Corner 3 is
// raised off the plane of the others so that the two triangles stay two: both face up (+z).
TEST(GltfReaderTest, StripsAndFansKeepTheirWinding) {
  SmallGltf g;
  g.positions = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1};
  g.indices = {0, 1, 2, 3};
  g.mode = 5;
  const Read strip = readText("strip.gltf", g.text());
  ASSERT_EQ(strip.groups.at(0).faces.size(), 2u);
  for (const auto& f : strip.groups[0].faces) EXPECT_GT(newellNormal(f.outer).z, 0);
  g.indices = {0, 1, 3, 2};
  g.mode = 6;
  const Read fan = readText("fan.gltf", g.text());
  ASSERT_EQ(fan.groups.at(0).faces.size(), 2u);
  for (const auto& f : fan.groups[0].faces) EXPECT_GT(newellNormal(f.outer).z, 0);
}

/// A triangle of three corners.
Polygon triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) { return Polygon{{a, b, c}, {}}; }

// 3 ── 2     The unit square as two triangles (0 1 2) and (0 2 3): one quad again.
// │  ╱ │
// 0 ── 1
TEST(CoplanarFacesTest, TwoTrianglesOfAQuadMergeIntoIt) {
  const glm::dvec3 p0(0, 0, 0), p1(1, 0, 0), p2(1, 1, 0), p3(0, 1, 0);
  const std::vector<Polygon> merged = mergeCoplanarFaces({triangle(p0, p1, p2), triangle(p0, p2, p3)});
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(merged[0].outer.size(), 4u);
  EXPECT_NEAR(polygonArea(merged[0]), 1.0, kColourTolerance);
  EXPECT_GT(newellNormal(merged[0].outer).z, 0);
}

// The square [0, 4]² with the hole [1, 3]², as the 8 triangles of the quads joining corner i
// of each ring: one polygon with one hole.
TEST(CoplanarFacesTest, AFrameOfTrianglesMergesIntoAPolygonWithAHole) {
  const std::vector<glm::dvec3> o = {{0, 0, 0}, {4, 0, 0}, {4, 4, 0}, {0, 4, 0}};
  const std::vector<glm::dvec3> h = {{1, 1, 0}, {3, 1, 0}, {3, 3, 0}, {1, 3, 0}};
  std::vector<Polygon> faces;
  for (size_t i = 0; i < 4; ++i) {
    const size_t j = (i + 1) % 4;
    faces.push_back(triangle(o[i], o[j], h[j]));
    faces.push_back(triangle(o[i], h[j], h[i]));
  }
  const std::vector<Polygon> merged = mergeCoplanarFaces(faces);
  ASSERT_EQ(merged.size(), 1u);
  EXPECT_EQ(merged[0].outer.size(), 4u);
  ASSERT_EQ(merged[0].holes.size(), 1u);
  EXPECT_NEAR(polygonArea(merged[0]), 16.0 - 4.0, kColourTolerance);
}

// Two triangles folded along their shared edge, or facing opposite ways, stay two.
TEST(CoplanarFacesTest, FoldedOrOppositeTrianglesStayApart) {
  const glm::dvec3 p0(0, 0, 0), p1(1, 0, 0), p2(1, 1, 0), p3(0, 1, 0), up(0, 1, 1);
  EXPECT_EQ(mergeCoplanarFaces({triangle(p0, p1, p2), triangle(p0, p2, up)}).size(), 2u);
  EXPECT_EQ(mergeCoplanarFaces({triangle(p0, p1, p2), triangle(p0, p3, p2)}).size(), 2u);
}

TEST(GltfReaderTest, LinesAreLeftOutWithAWarning) {
  SmallGltf g;
  g.mode = 1;
  const Read r = readText("lines.gltf", g.text());
  EXPECT_TRUE(r.groups.empty());
  EXPECT_TRUE(warned(r.warnings, {"left out 1 primitives", "points or lines", "'tri'"}));
}

/// Expects reading a glTF file `name` of this text to throw an InputError naming the file and
/// saying every one of `parts`.
void expectBad(const std::string& name, const std::string& text, std::initializer_list<std::string> parts) {
  const std::string path = writeFile(name, text);
  std::vector<std::string> warnings;
  test::expectError([&] { readGltfFile(path, warnings); }, {path});
  test::expectError([&] { readGltfFile(path, warnings); }, parts);
}

TEST(GltfReaderTest, MalformedJsonIsAnError) {
  expectBad("bad.gltf", R"({"asset": {"version": "2.0"}, "nodes": [)", {"expected a glTF 2.0 file (JSON)"});
  expectBad("v1.gltf", R"({"asset": {"version": "1.0"}})", {"asset.version", "2.0", "'1.0'"});
}

TEST(GltfReaderTest, AccessorBeyondItsBufferViewIsAnError) {
  const std::string text =
      replaced(SmallGltf().text(), R"("count": 3, "type": "SCALAR")", R"("count": 30, "type": "SCALAR")");
  expectBad("beyond.gltf", text, {"indices accessor 1", "30 elements of 2 bytes", "a view of 6 bytes"});
}

TEST(GltfReaderTest, IndexPastTheVerticesIsAnError) {
  SmallGltf g;
  g.indices = {0, 1, 7};
  expectBad("index.gltf", g.text(), {"mesh 'tri': primitive 0", "index 2", "a vertex from 0 to 2", "found 7"});
}

TEST(GltfReaderTest, NanPositionIsAnError) {
  SmallGltf g;
  g.positions[4] = std::nanf("");
  expectBad("nan.gltf", g.text(), {"POSITION accessor 0: vertex 1", "finite coordinates"});
}

TEST(GltfReaderTest, MissingBufferIsAnError) {
  expectBad("nobin.gltf", R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 4, "uri": "absent.bin"}]})",
            {"whose buffers load", "absent.bin"});
}

// A texture missing beside a downloaded file (as an OBJ's map_Kd): its factor alone, said once.
TEST(GltfReaderTest, MissingTextureLeavesTheFactorWithAWarning) {
  SmallGltf g;
  g.materials = R"([{"name": "tex", "pbrMetallicRoughness": {"baseColorFactor": [0.5, 0.25, 0.125, 1],
                    "baseColorTexture": {"index": 0}, "metallicFactor": 0}}])";
  g.extra = R"("textures": [{"source": 0}], "images": [{"uri": "absent.png"}], )";
  const Read r = readText("missing_texture.gltf", g.text());
  EXPECT_EQ(*r.groups.at(0).kd, glm::dvec3(0.5, 0.25, 0.125));
  EXPECT_TRUE(warned(r.warnings, {"'tex'", "'absent.png'", "baseColorFactor alone"}));
  g.extra = R"("textures": [{"source": 7}], "images": [{"uri": "absent.png"}], )";
  expectBad("bad_source.gltf", g.text(), {"texture 0: source", "image index from 0 to 0", "found 7"});
}

TEST(GltfReaderTest, TruncatedGlbIsAnError) {
  std::ifstream in(test::kData + "cornell.glb", std::ios::binary);
  const std::string glb((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_GT(glb.size(), 1000u);
  expectBad("cut.glb", glb.substr(0, glb.size() / 2), {"expected a binary glTF 2.0 file (.glb)"});
}

// The scene loader: a bad glTF stops it with the scene's place, then the file's.
TEST(GltfReaderTest, SceneWithABadGltfIsAnInputError) {
  SmallGltf nan;
  nan.positions[0] = std::nanf("");
  writeFile("scene_nan.gltf", nan.text());
  const std::string scene = writeFile("scene_nan.json", R"({"version": 1, "materials": {},
      "surfaces": [{"name": "thing", "mesh": "gltf_test_scene_nan.gltf"}]})");
  test::expectError([&] { loadScene(scene); }, {"surfaces[0].mesh", "scene_nan.gltf", "finite coordinates"});
}

/// The Cornell box's glTF surface of JSON surface `name`: "cornell/<name>/<material>".
int gltfSurface(const Scene& gltf, const std::string& name) {
  for (size_t s = 0; s < gltf.surfaces.size(); ++s)
    if (gltf.surfaces[s].name.rfind("cornell/" + name + "/", 0) == 0) return int(s);
  return -1;
}

/// Every corner of the surface's polygons and holes.
std::vector<glm::dvec3> cornersOf(const Surface& s) {
  std::vector<glm::dvec3> out;
  for (const auto& p : s.polygons) {
    out.insert(out.end(), p.outer.begin(), p.outer.end());
    for (const auto& hole : p.holes) out.insert(out.end(), hole.begin(), hole.end());
  }
  return out;
}

/// The surface's total area.
double areaOf(const Surface& s) {
  double area = 0;
  for (const auto& p : s.polygons) area += polygonArea(p);
  return area;
}

// Every JSON surface comes back with its area, its corners (the blocks through their nodes'
// translation + rotation and matrix) and its material; the .glb holds the same.
TEST(GltfCornellTest, SameSurfacesAndMaterialsAsTheJsonScene) {
  const Scene json = loadScene(test::kScenes + "cornell.json");
  const Scene gltf = loadScene(test::kData + "cornell_gltf.json"), glb = loadScene(test::kData + "cornell_glb.json");
  ASSERT_EQ(gltf.surfaces.size(), json.surfaces.size());
  for (const Surface& s : json.surfaces) {
    const int g = gltfSurface(gltf, s.name);
    ASSERT_GE(g, 0) << s.name;
    const Surface& t = gltf.surfaces[size_t(g)];
    EXPECT_NEAR(areaOf(t), areaOf(s), kPositionTolerance * areaOf(s)) << s.name;
    for (const auto& q : cornersOf(t))
      EXPECT_LE(nearestDistance(q, cornersOf(s)), kCornerTolerance) << s.name << ": a glTF corner not the JSON's";
    if (s.name != "left_wall") {  // bent: two triangles; every other surface one polygon, as in the JSON
      EXPECT_EQ(t.polygons.size(), s.polygons.size()) << s.name << ": its triangles merged back";
    }
    EXPECT_EQ(t.polygons.at(0).holes.size(), s.polygons.at(0).holes.size()) << s.name;
    const Material &a = json.materials[size_t(s.material)], &b = gltf.materials[size_t(t.material)];
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(b.reflectance[c], a.reflectance[c], kColourTolerance) << s.name;
      EXPECT_NEAR(b.emission[c], a.emission[c], kColourTolerance * a.emission[c]) << s.name;
    }
    const Surface& u = glb.surfaces.at(size_t(g));
    ASSERT_EQ(u.polygons.size(), t.polygons.size());
    for (size_t k = 0; k < t.polygons.size(); ++k) EXPECT_EQ(u.polygons[k].outer, t.polygons[k].outer) << u.name;
  }
}

/// The reference points of the Cornell box, named after the glTF scene's surfaces.
std::vector<ReferencePoint> gltfPoints(const std::vector<ReferencePoint>& points, const Scene& gltf) {
  std::vector<ReferencePoint> out = points;
  for (auto& p : out) {
    const int s = gltfSurface(gltf, p.surface);
    if (s >= 0) p.surface = gltf.surfaces[size_t(s)].name;
  }
  return out;
}

/// Whether each point lies on an emitting surface of the scene.
std::vector<bool> onEmitters(const std::vector<ReferencePoint>& points, const Scene& scene) {
  std::vector<bool> out;
  for (const auto& p : points)
    out.push_back(std::any_of(scene.surfaces.begin(), scene.surfaces.end(), [&](const Surface& s) {
      return s.name == p.surface && scene.materials[size_t(s.material)].emits();
    }));
  return out;
}

/// The relative differences of `shown` from `base` at each point: their sum of squares and how
/// many channels, over the channels where `base` is above kDarkShare of its brightest off the
/// emitters (near-black ones skipped, as the true error does).
std::vector<std::pair<double, int>> squaredDifferences(const std::vector<glm::dvec3>& base,
                                                        const std::vector<glm::dvec3>& shown,
                                                        const std::vector<bool>& emitting) {
  glm::dvec3 brightest(0.0);
  for (size_t i = 0; i < base.size(); ++i)
    if (!emitting[i]) brightest = glm::max(brightest, base[i]);
  std::vector<std::pair<double, int>> out(base.size(), {0.0, 0});
  for (size_t i = 0; i < base.size(); ++i)
    for (int c = 0; c < 3; ++c)
      if (base[i][c] > kDarkShare * brightest[c])
        out[i].first += std::pow((shown[i][c] - base[i][c]) / base[i][c], 2), ++out[i].second;
  return out;
}

/// The RMS over the points' channels, leaving point `except` out (-1: none).
double rmsOf(const std::vector<std::pair<double, int>>& squares, int except = -1) {
  double sum = 0;
  int used = 0;
  for (size_t i = 0; i < squares.size(); ++i)
    if (int(i) != except) sum += squares[i].first, used += squares[i].second;
  return std::sqrt(sum / std::max(used, 1));
}

// Issue 15's target: solved at defaults, the glTF export shows the JSON scene's light at the
// reference points (what a viewer shows there, Gouraud-interpolated). Measured: 0.70 % RMS over
// 831 channels (1.57 % while the bent left wall's two triangles were split by their lattice
// instead of meshed as the JSON's polygon is); against the path-traced reference the true
// errors are 1.56 % (JSON) and 1.57 % (glTF).
TEST(GltfCornellTest, SolvesToTheLightOfTheJsonScene) {
  const auto json = test::solveLikeCli(test::kScenes + "cornell.json");
  const auto gltf = test::solveLikeCli(test::kData + "cornell_gltf.json");
  const std::string reference = test::kReferences + "cornell_reference.csv";
  const std::vector<ReferencePoint> points = readReferenceFile(reference).points;
  const TrueError atJson(json->meshed.mesh, json->meshed.scene, points, reference);
  const TrueError atGltf(gltf->meshed.mesh, gltf->meshed.scene, gltfPoints(points, gltf->meshed.scene), reference);
  const auto squares = squaredDifferences(atJson.shown(json->shown), atGltf.shown(gltf->shown),
                                          onEmitters(points, json->meshed.scene));
  const int worst = int(std::max_element(squares.begin(), squares.end()) - squares.begin());
  const double all = rmsOf(squares), allButWorst = rmsOf(squares, worst);
  const double errorJson = atJson.measure(json->shown).rms, errorGltf = atGltf.measure(gltf->shown).rms;
  EXPECT_LE(all, kSameLight) << "worst point " << worst + 1 << " (" << points[size_t(worst)].surface << ")";
  EXPECT_LE(errorGltf, errorJson + kSameTrueError) << "true errors against the reference";
  std::cout << "glTF vs JSON Cornell box: " << 100 * all << " % RMS (" << 100 * allButWorst << " % without point "
            << worst + 1 << " on " << points[size_t(worst)].surface << "); true error JSON " << 100 * errorJson
            << " %, glTF " << 100 * errorGltf << " %\n";
}

}  // namespace
}  // namespace rad
