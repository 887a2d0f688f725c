// Direct light by rays (radiosity/direct_light.h): the lights of a point share its rays by
// what each brings. A lone light still casts every sample; several lights cast fewer rays and
// show the same light as every sample of every light does.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "mesh/color.h"
#include "radiosity/direct_light.h"
#include "radiosity/solve.h"
#include "tests/support.h"

namespace rad {
namespace {

/// As many rays per point as any scene has samples: every sample of every light.
constexpr int kEverySample = 1 << 30;
/// Shared rays against every sample, at the vertices of tests/data/four_lamps.json (a room lit
/// by four lamps of different size and power, a block casting their penumbrae), relative to
/// the every-sample light: RMS over the vertices, and the worst vertex lit to at least
/// kLitShare of the mean. Measured: 0.08 % and 1.4 % (4.2 % while a light's rays followed
/// only its unoccluded share: in a shadow, the light that does arrive was under-sampled).
constexpr double kSharedRaysRms = 0.003;
constexpr double kSharedRaysWorst = 0.03;
constexpr double kLitShare = 0.1;
/// ...for at most this share of the rays (measured: 0.34).
constexpr double kSharedRaysCost = 0.5;

/// The scene meshed as `radiosity solve` meshes it (adaptive refinement and all).
MeshedScene meshed(const std::string& path) {
  Scene scene = loadScene(path);
  const Settings settings = resolveSettings(scene, {});
  return meshScene(std::move(scene), settings);
}

/// The direct light at every vertex of `mesh` by `raysPerPoint`; the rays cast in `rays`.
std::vector<glm::dvec3> directLight(const MeshedScene& s, int raysPerPoint, long& rays) {
  DirectLight light(s.mesh, s.scene.diagonal(), kDefaultLightSamples, raysPerPoint);
  light.update(s.mesh);
  rays = light.rays();
  return light.radiosity();
}

TEST(DirectLightTest, ALoneLightCastsEverySample) {
  const MeshedScene s = meshed(test::kScenes + "cornell.json");
  long shared = 0, every = 0;
  const auto a = directLight(s, kRaysPerPoint, shared), b = directLight(s, kEverySample, every);
  EXPECT_EQ(shared, every);
  EXPECT_EQ(a, b);
}

TEST(DirectLightTest, SeveralLightsShareTheRaysAndShowTheSameLight) {
  const MeshedScene s = meshed(test::kData + "four_lamps.json");
  long shared = 0, every = 0;
  const auto a = directLight(s, kRaysPerPoint, shared), b = directLight(s, kEverySample, every);
  ASSERT_EQ(a.size(), b.size());
  double mean = 0;
  for (const glm::dvec3& v : b) mean += luminance(v) / double(b.size());
  double sum2 = 0, worst = 0;
  for (size_t v = 0; v < a.size(); ++v) {
    const double exact = luminance(b[v]), d = luminance(a[v]) - exact;
    sum2 += d * d;
    if (exact >= kLitShare * mean) worst = std::max(worst, std::abs(d) / exact);
  }
  const double rms = std::sqrt(sum2 / double(a.size())) / mean;
  std::printf("four lamps: %ld rays shared against %ld every sample (%.2f); RMS %.3f %% of the mean, worst lit "
              "vertex %.2f %%\n", shared, every, double(shared) / double(every), 100 * rms, 100 * worst);
  EXPECT_LE(double(shared), kSharedRaysCost * double(every));
  EXPECT_LE(rms, kSharedRaysRms);
  EXPECT_LE(worst, kSharedRaysWorst);
}

}  // namespace
}  // namespace rad
