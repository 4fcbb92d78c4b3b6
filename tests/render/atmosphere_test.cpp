// The atmosphere (render/atmosphere_pass.h, shaders/common/atmosphere_model.glsl): the CPU model
// against closed forms, the GPU's LUTs against brute-force integrations of the same atmosphere
// (render/atmosphere_model.h), and the light it gives at noon and at dusk.

#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "gpu_test_fixture.h"
#include "render/atmosphere_model.h"
#include "render/atmosphere_pass.h"

namespace vegstream::render::testing {
namespace {
namespace atm = vegstream::render::atmosphere;

double relativeError(const glm::vec3& a, const glm::vec3& b) {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(double(a[c]) - b[c]) / std::max(std::abs(double(b[c])), 1e-6));
  return worst;
}

float lutU(uint32_t i, uint32_t n) { return float(i) / float(n - 1); }

// Straight up from sea level the optical depth has a closed form: each exponential layer gives
// β H (1 − e^(−100 / H)), the ozone tent its area, 15 km × its peak.
TEST(AtmosphereModel, ZenithTransmittanceMatchesTheClosedForm) {
  const glm::dvec3 rayleigh(5.802e-3, 13.558e-3, 33.1e-3), ozone(0.650e-3, 1.881e-3, 0.085e-3);
  const double top = 100.0;
  glm::dvec3 depth = rayleigh * 8.0 * (1.0 - std::exp(-top / 8.0)) +
                     glm::dvec3(4.440e-3 * 1.2 * (1.0 - std::exp(-top / 1.2))) + ozone * 15.0;
  const glm::vec3 expected(glm::exp(-depth));
  EXPECT_LT(relativeError(atm::transmittanceToTopMarched(atm::kBottomRadiusKm, 1.0f, 4000), expected), 2e-4);
}

// Low sun: longer paths through the air take more blue than red (the sunset's colour), and less
// of everything.
TEST(AtmosphereModel, ALowSunIsRedderAndDimmer) {
  const float r = atm::kBottomRadiusKm + 0.5f;
  const glm::vec3 high = atm::sunTransmittance(r, std::cos(glm::radians(30.0f)));
  const glm::vec3 low = atm::sunTransmittance(r, std::cos(glm::radians(88.0f)));
  EXPECT_GT(high.b, 0.6f);
  EXPECT_LT(low.g, 0.5f * high.g);
  EXPECT_GT(low.r / low.b, 2.0f * high.r / high.b);
  EXPECT_EQ(atm::sunTransmittance(r, -0.2f), glm::vec3(0.0f));  // below the horizon: the earth's shadow
}

// A clear sky is blue at the zenith (Rayleigh), brighter towards the horizon away from the sun.
TEST(AtmosphereModel, TheSkyIsBlueOverheadAndPalerAtTheHorizon) {
  const float r = atm::kBottomRadiusKm + 1.5f, muS = std::sin(glm::radians(40.0f));
  auto luminance = [&](float zenithDeg, float azimuthDeg) {
    const float mu = std::cos(glm::radians(zenithDeg));
    const float nu = std::sin(glm::radians(zenithDeg)) * std::cos(glm::radians(azimuthDeg)) *
                         std::sqrt(1.0f - muS * muS) + mu * muS;
    return atm::skyLuminanceMarched(atm::AtmosphereRay{r, mu, muS, nu}, 64, false);
  };
  const glm::vec3 zenith = luminance(0.0f, 0.0f), horizon = luminance(88.0f, 180.0f);
  EXPECT_GT(zenith.b, zenith.g);
  EXPECT_GT(zenith.g, zenith.r);
  EXPECT_GT(horizon.r / horizon.b, zenith.r / zenith.b);  // whiter
  EXPECT_GT(horizon.g, zenith.g);
}

class AtmosphereGpuTest : public GpuTest {
 protected:
  // One frame with nothing in it, the camera `heightM` up, the sun `elevationDeg` above the
  // horizon in the east; its LUTs read back.
  AtmosphereLuts render(double heightM, double elevationDeg) {
    auto r = makeRenderer(64, 36, 1);
    EXPECT_TRUE(r);
    if (!r) return {};
    FrameRequest req;
    req.cameraHeightMsl = heightM;
    req.camera.position = {0.0, 0.0, heightM};
    const double e = glm::radians(elevationDeg);
    req.lighting.sunDirection = {std::cos(e), 0.0, std::sin(e)};
    EXPECT_TRUE(r->renderFrame(req).ok());
    auto luts = r->readAtmosphere();
    EXPECT_TRUE(luts.ok()) << (luts.ok() ? "" : luts.error().message);
    return luts.ok() ? *luts : AtmosphereLuts{};
  }
};

TEST_F(AtmosphereGpuTest, TheLutsMatchBruteForceIntegrationsOfTheSameAtmosphere) {
  const double heightM = 1500.0, elevationDeg = 30.0;
  const AtmosphereLuts luts = render(heightM, elevationDeg);
  ASSERT_EQ(luts.transmittance.width, kTransmittanceLutSize.width);
  // Transmittance: 40 steps on the GPU in half floats against 2000.
  for (uint32_t y : {0u, 13u, 40u, 63u})
    for (uint32_t x : {0u, 50u, 128u, 200u, 255u}) {
      const glm::vec2 rMu = atm::transmittanceRMuFromUv(glm::vec2(lutU(x, 256), lutU(y, 64)));
      const glm::vec3 expected = atm::transmittanceToTopMarched(rMu.x, rMu.y, 2000);
      // Half floats: a relative 1 %, or 2e-4 where the transmittance itself is nearly 0.
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(luts.transmittance.at(x, y)[c], expected[c], 0.01 * expected[c] + 2e-4) << x << "," << y;
    }
  // Ψ_ms: the GPU's (transmittance from its LUT) against the sun's transmittance marched, same
  // directions; then, in the air vegstream flies in (the lowest 3 km), against twice the
  // directions and three times the steps (Hillaire's few directions converge slowly higher up).
  for (uint32_t x : {4u, 16u, 28u})
    for (uint32_t y : {0u, 1u, 10u}) {
      const glm::vec2 rMuS = atm::multiScatteringRMuSFromUv(glm::vec2(lutU(x, 32), lutU(y, 32)));
      const glm::vec3 gpu(luts.multiScattering.at(x, y));
      EXPECT_LT(relativeError(gpu, atm::multiScatteringTransfer(rMuS.x, rMuS.y, kMultiScatteringDirections, 20)), 0.03)
          << x << "," << y;
      if (y <= 1) {
        EXPECT_LT(relativeError(gpu, atm::multiScatteringTransfer(rMuS.x, rMuS.y, 2 * kMultiScatteringDirections, 60)),
                  0.12) << x << "," << y;
      }
    }
  // Sky view: the zenith, the horizon towards and away from the sun, 20° up at 90° from it,
  // against 48-step marches whose multiple scattering is itself integrated.
  const float r = atmosphereCameraRadiusKm(heightM), muS = float(std::sin(glm::radians(elevationDeg)));
  for (const glm::uvec2 texel : {glm::uvec2(0, 0), glm::uvec2(0, 53), glm::uvec2(191, 53), glm::uvec2(96, 25)}) {
    const glm::vec2 dir = atm::skyViewDirectionFromUv(r, glm::vec2(lutU(texel.x, 192), lutU(texel.y, 108)));
    const float sinV = std::sqrt(std::max(1.0f - dir.x * dir.x, 0.0f));
    const atm::AtmosphereRay ray{r, dir.x, muS, sinV * std::cos(dir.y) * std::sqrt(1.0f - muS * muS) + dir.x * muS};
    const glm::vec3 expected = atm::skyLuminanceMarched(ray, 48, true);
    EXPECT_LT(relativeError(glm::vec3(luts.skyView.at(texel.x, texel.y)), expected), 0.05)
        << texel.x << "," << texel.y << " expected " << expected.r << " " << expected.g << " " << expected.b;
  }
  // The sun's illuminance at the camera is the model's, through the air.
  const glm::vec3 sun = atm::kSunIlluminance * atm::sunTransmittance(r, muS);
  EXPECT_LT(relativeError(glm::vec3(luts.skyLight[0]), sun), 0.01);
  // The clear sky's diffuse share of the light on the ground at 30°: 10–35 % of the sun's.
  const float direct = sun.g * muS, diffuse = luts.skyLight[1].g;
  EXPECT_GT(diffuse / direct, 0.10f);
  EXPECT_LT(diffuse / direct, 0.35f);
}

// Far air takes the sky's colour: the aerial volume's last slice towards the horizon lets
// little through and holds light of the sky's hue; its first slice is nearly clear.
TEST_F(AtmosphereGpuTest, DistantAirTakesTheSkysColour) {
  const AtmosphereLuts luts = render(1500.0, 30.0);
  ASSERT_EQ(luts.aerial.depth, kAerialLutSize[2]);
  const uint32_t x = 16, horizonRow = 32;  // v = 0.5: the horizon
  const glm::vec4 nearest = luts.aerial.at(x, horizonRow, 0), farthest = luts.aerial.at(x, horizonRow, 31);
  EXPECT_GT(nearest.a, 0.99f);
  EXPECT_LT(farthest.a, 0.5f);
  EXPECT_GT(farthest.b, farthest.r);  // bluish haze
  const glm::vec4 sky = luts.skyView.at(96, 53);
  EXPECT_GT(farthest.b, 0.3f * sky.b);
}

// Dawn and dusk: a sun 2° up lights the ground with far less, far redder light than at noon.
TEST_F(AtmosphereGpuTest, ALowSunReddensAndDimsTheLight) {
  const glm::vec4 noon = render(1500.0, 70.0).skyLight[0], dusk = render(1500.0, 2.0).skyLight[0];
  EXPECT_LT(dusk.g, 0.6f * noon.g);
  EXPECT_GT(dusk.r / dusk.b, 2.0f * noon.r / noon.b);
  const AtmosphereLuts night = render(1500.0, -10.0);
  EXPECT_EQ(night.skyLight[0].g, 0.0f);
}

}  // namespace
}  // namespace vegstream::render::testing
