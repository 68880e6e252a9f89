// Every direction sampler against the density it claims, by a chi-square
// goodness-of-fit test as pbrt-v4 does: directions are binned over a cap
// around an axis (equal steps in cos theta and phi, equal solid angle), the
// expected count of each bin is the claimed pdf integrated over it, and the
// test fails when the histogram is too unlikely under that pdf. Bidirectional
// IR's weights and pt's MIS rest on these densities being exact.
#include <cmath>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "lighting/lights.h"
#include "material/bsdf.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/builtin_scenes.h"
#include "vpl/light_path.h"

namespace igi {
namespace {

constexpr int kThetaBins = 16, kPhiBins = 32;
constexpr int kSamples = 200000;
// Significance per test, with room for the dozen tests in this file.
constexpr double kSignificance = 0.01 / 12.0;

struct Cap {
  Onb frame;
  double cos_max;  // the cap spans cos theta in [cos_max, 1] around frame.n
  double bin_cos(int i) const { return 1.0 - (1.0 - cos_max) * i / kThetaBins; }
  glm::vec3 direction(double cos_theta, double phi) const {
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    return frame.to_world(glm::vec3(float(sin_theta * std::cos(phi)), float(sin_theta * std::sin(phi)), float(cos_theta)));
  }
  // The bin of `d`, or -1 outside the cap.
  int bin(glm::vec3 d) const {
    const glm::vec3 l = frame.to_local(d);
    if (l.z < cos_max) return -1;
    const int i = std::min(kThetaBins - 1, int((1.0 - l.z) / (1.0 - cos_max) * kThetaBins));
    double phi = std::atan2(double(l.y), double(l.x));
    if (phi < 0.0) phi += 2.0 * M_PI;
    const int j = std::min(kPhiBins - 1, int(phi / (2.0 * M_PI) * kPhiBins));
    return i * kPhiBins + j;
  }
};

// P(X >= x) for chi-square with k degrees of freedom (Wilson-Hilferty: the
// cube root of X / k is close to normal for the hundreds of bins here).
double chi_square_tail(double x, int k) {
  const double s = 2.0 / (9.0 * k);
  const double z = (std::cbrt(x / k) - (1.0 - s)) / std::sqrt(s);
  return 0.5 * std::erfc(z / std::sqrt(2.0));
}

using Sampler = std::function<std::optional<glm::vec3>(glm::vec2 u)>;
using Pdf = std::function<double(glm::vec3 direction)>;
using Binning = std::function<int(glm::vec3 direction)>;  // the bin of a direction, -1 outside every bin

// The p-value of the histogram of kSamples directions against `expected`
// counts per bin (samples that fail carry the mass the pdf leaves out; those
// outside every bin are not counted). Bins expected to hold under 5 samples
// are pooled into one, as pbrt does.
double chi_square_p_value(const Sampler& sample, const Binning& bin_of, const std::vector<double>& expected,
                          std::string& why) {
  std::vector<double> observed(expected.size(), 0.0);
  std::mt19937_64 rng(12345);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  int outside = 0;
  for (int n = 0; n < kSamples; ++n) {
    const std::optional<glm::vec3> d = sample({uniform(rng), uniform(rng)});
    if (!d) continue;
    const int b = bin_of(glm::normalize(*d));
    if (b < 0) ++outside; else observed[size_t(b)] += 1.0;
  }
  double chi2 = 0.0, pooled_observed = 0.0, pooled_expected = 0.0;
  int dof = -1;
  for (size_t b = 0; b < observed.size(); ++b) {
    if (expected[b] < 5.0) {
      pooled_observed += observed[b];
      pooled_expected += expected[b];
      continue;
    }
    chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
    ++dof;
  }
  if (pooled_observed > 0.0 || pooled_expected > 0.0) {
    // Samples where the pdf claims (almost) nothing are a failure on their own.
    const double e = std::max(pooled_expected, 1.0);
    chi2 += (pooled_observed - e) * (pooled_observed - e) / e;
    ++dof;
  }
  why = "chi2 " + std::to_string(chi2) + " over " + std::to_string(dof) + " degrees of freedom, " +
        std::to_string(outside) + " samples outside the bins";
  return dof > 0 ? chi_square_tail(chi2, dof) : 0.0;
}

// Expected counts over a cap: the pdf integrated over each bin by the
// midpoint rule on subdivisions x subdivisions points (d omega = d cos d phi).
std::vector<double> cap_expected(const Pdf& pdf, const Cap& cap, int subdivisions) {
  std::vector<double> expected(kThetaBins * kPhiBins, 0.0);
  for (int i = 0; i < kThetaBins; ++i)
    for (int j = 0; j < kPhiBins; ++j) {
      const double c0 = cap.bin_cos(i), c1 = cap.bin_cos(i + 1);
      const double dc = (c0 - c1) / subdivisions, dphi = 2.0 * M_PI / kPhiBins / subdivisions;
      double integral = 0.0;
      for (int a = 0; a < subdivisions; ++a)
        for (int b = 0; b < subdivisions; ++b)
          integral += pdf(cap.direction(c0 - (a + 0.5) * dc, (j + (b + 0.5) / subdivisions) * 2.0 * M_PI / kPhiBins));
      expected[size_t(i * kPhiBins + j)] = integral * dc * dphi * kSamples;
    }
  return expected;
}

void expect_fits(const Sampler& sample, const Pdf& pdf, const Cap& cap, const std::string& what,
                 int subdivisions = 6) {
  std::string why;
  const double p = chi_square_p_value(sample, [&cap](glm::vec3 d) { return cap.bin(d); },
                                      cap_expected(pdf, cap, subdivisions), why);
  EXPECT_GT(p, kSignificance) << what << ": " << why;
}

const Cap kHemisphere{Onb(glm::vec3(0, 0, 1)), 0.0};

TEST(SamplingPdf, CosineHemisphere) {
  expect_fits([](glm::vec2 u) { return cosine_hemisphere(u); },
              [](glm::vec3 d) { return d.z > 0.0f ? d.z / M_PI : 0.0; }, kHemisphere, "cosine hemisphere");
}

TEST(SamplingPdf, UniformCone) {
  for (float cos_max : {0.2f, 0.9f, 0.995f}) {
    const Cap cap{Onb(glm::vec3(0, 0, 1)), cos_max};
    expect_fits([cos_max](glm::vec2 u) { return uniform_cone(u, cos_max); },
                [cos_max](glm::vec3 d) { return d.z >= cos_max ? 1.0 / (2.0 * M_PI * (1.0 - cos_max)) : 0.0; }, cap,
                "cone cos_max " + std::to_string(cos_max));
  }
}

// A flat GGX conductor seen from `wo`: bsdf_sample's directions (visible
// normals, Heitz 2018) against bsdf_pdf.
TEST(SamplingPdf, GgxVisibleNormalsMatchBsdfPdf) {
  for (float alpha : {0.05f, 0.3f, 0.8f})
    for (float theta_o : {0.1f, 0.8f, 1.4f}) {
      Material metal;
      metal.type = MaterialType::Conductor;
      metal.alpha = alpha;
      SurfacePoint sp;
      sp.position = glm::vec3(0.0f);
      sp.geometric_normal = sp.shading_normal = glm::vec3(0, 0, 1);
      sp.material = &metal;
      sp.albedo = glm::vec3(1.0f);
      const glm::vec3 wo(std::sin(theta_o), 0.0f, std::cos(theta_o));
      // Around the mirror direction, wide enough for the whole lobe.
      const glm::vec3 mirror(-wo.x, -wo.y, wo.z);
      const Cap cap = alpha < 0.1f ? Cap{Onb(mirror), std::cos(0.6)} : kHemisphere;
      expect_fits(
          [&](glm::vec2 u) -> std::optional<glm::vec3> {
            auto s = bsdf_sample(sp, wo, u, 0.5f);
            if (!s) return std::nullopt;
            return s->wi;
          },
          [&](glm::vec3 wi) { return double(bsdf_pdf(sp, wo, wi)); }, cap,
          "GGX alpha " + std::to_string(alpha) + ", theta_o " + std::to_string(theta_o),
          alpha < 0.1f ? 96 : 6);  // the sharp lobe needs a finer rule (at 48, a grazing view fails on it alone)
    }
}

// Area lights: a 0.4 m square emitter (two triangles, each chosen by its
// power) seen head-on, from close by, and at 80 degrees from its normal
// (where pt once lost the light). Binned over the square's own parameters
// (s, t) so that no bin straddles its edge; a bin's expected count is the
// claimed solid-angle pdf times d omega / dA = cos_light / r^2 over it.
TEST(SamplingPdf, AreaLightSamplingMatchesItsSolidAnglePdf) {
  struct View { const char* name; glm::vec3 p; };
  constexpr int kSide = 22, kSub = 4;  // 484 bins over the square
  for (const View& view : {View{"head-on", {0.0f, -1.0f, 0.0f}}, View{"close", {0.1f, -0.15f, 0.05f}},
                           View{"grazing", {1.0f, -0.18f, 0.3f}}}) {
    Scene scene;
    Material lamp;
    lamp.emission = glm::vec3(1.0f);
    // In the plane y = 0, facing down (-y): corner o, edges eu and ev.
    const glm::vec3 o(-0.2f, 0, -0.2f), eu(0.4f, 0, 0), ev(0, 0, 0.4f);
    add_quad(scene, o, o + eu, o + eu + ev, o + ev, add_material(scene, lamp));
    const LightSet lights(scene);
    const glm::vec3 n(0, -1, 0);
    // Where direction d from p meets the plane, as (s, t) in the square's parameters.
    auto params = [&](glm::vec3 d) -> std::optional<glm::dvec2> {
      const double t = glm::dot(glm::dvec3(o - view.p), glm::dvec3(n)) / glm::dot(glm::dvec3(d), glm::dvec3(n));
      if (!(t > 0.0)) return std::nullopt;
      const glm::dvec3 q = glm::dvec3(view.p) + t * glm::dvec3(d) - glm::dvec3(o);
      return glm::dvec2(glm::dot(q, glm::dvec3(eu)) / 0.16, glm::dot(q, glm::dvec3(ev)) / 0.16);
    };
    auto bin_of = [&](glm::vec3 d) {
      const auto st = params(d);
      if (!st || st->x < 0.0 || st->x >= 1.0 || st->y < 0.0 || st->y >= 1.0) return -1;
      return int(st->y * kSide) * kSide + int(st->x * kSide);
    };
    std::vector<double> expected(kSide * kSide, 0.0);
    for (int bin = 0; bin < kSide * kSide; ++bin)
      for (int a = 0; a < kSub; ++a)
        for (int b = 0; b < kSub; ++b) {
          const double s = (bin % kSide + (a + 0.5) / kSub) / kSide, t = (bin / kSide + (b + 0.5) / kSub) / kSide;
          const glm::vec3 q = o + float(s) * eu + float(t) * ev;
          const glm::vec3 d = q - view.p;
          const float r2 = glm::dot(d, d);
          const float cos_light = -glm::dot(n, d) / std::sqrt(r2);
          const double dA = 0.16 / (double(kSide) * kSide * kSub * kSub);
          expected[size_t(bin)] += lights.pdf_area(0, view.p, q) * cos_light / r2 * dA * kSamples;
        }
    uint32_t i = 0;
    std::string why;
    const double p = chi_square_p_value(
        [&](glm::vec2 u) -> std::optional<glm::vec3> {
          const LightSample s = lights.sample(view.p, float((i++ % 997) + 0.5f) / 997.0f, u);
          if (!(s.pdf > 0.0f)) return std::nullopt;
          return s.direction;
        },
        bin_of, expected, why);
    EXPECT_GT(p, kSignificance) << view.name << ": " << why;
  }
}

// Light paths leave point lights uniformly, spots uniformly inside the outer
// cone and area lights cosine-distributed about their normal: the densities
// their flux is divided by (vpl/light_path.cpp).
TEST(SamplingPdf, LightPathsLeaveLightsWithTheirDensity) {
  struct Case { const char* name; LightType type; float outer; };
  for (const Case& c : {Case{"point", LightType::Point, 0.0f}, Case{"spot", LightType::Spot, 0.5f}}) {
    Scene scene;
    PunctualLight light;
    light.type = c.type;
    light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
    light.outer_cone = c.outer;
    light.inner_cone = 0.5f * c.outer;
    scene.lights.push_back(light);
    const LightSet lights(scene);
    uint32_t i = 0;
    const bool spot = c.type == LightType::Spot;
    const double cos_max = spot ? std::cos(double(c.outer)) : -1.0;
    const Cap cap{Onb(spot ? light.direction : glm::vec3(0, 0, 1)), spot ? cos_max - 0.05 : -1.0};
    expect_fits(
        [&](glm::vec2) -> std::optional<glm::vec3> {
          SampleStream u(i++, 99u);
          return start_light_path(lights, scene, u).ray.direction;
        },
        [&](glm::vec3 d) {
          if (!spot) return 1.0 / (4.0 * M_PI);
          return glm::dot(d, light.direction) >= cos_max ? 1.0 / (2.0 * M_PI * (1.0 - cos_max)) : 0.0;
        },
        cap, c.name);
  }
  Scene scene;
  Material lamp;
  lamp.emission = glm::vec3(1.0f);
  add_quad(scene, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, add_material(scene, lamp));  // normal +z
  const LightSet lights(scene);
  uint32_t i = 0;
  expect_fits(
      [&](glm::vec2) -> std::optional<glm::vec3> {
        SampleStream u(i++, 99u);
        return start_light_path(lights, scene, u).ray.direction;
      },
      [](glm::vec3 d) { return d.z > 0.0f ? d.z / M_PI : 0.0; }, kHemisphere, "area light");
}

// The test itself: a density that is wrong by a little is caught.
TEST(SamplingPdf, ChiSquareCatchesAWrongDensity) {
  auto p_value = [](const Pdf& pdf) {
    std::string why;
    return chi_square_p_value([](glm::vec2 u) { return cosine_hemisphere(u); },
                              [](glm::vec3 d) { return kHemisphere.bin(d); }, cap_expected(pdf, kHemisphere, 6), why);
  };
  EXPECT_LT(p_value([](glm::vec3 d) { return d.z > 0.0f ? 1.0 / (2.0 * M_PI) : 0.0; }), kSignificance) << "uniform";
  EXPECT_LT(p_value([](glm::vec3 d) { return d.z > 0.0f ? (0.95 * d.z / M_PI + 0.05 / (2.0 * M_PI)) : 0.0; }),
            kSignificance) << "5 % of the mass moved";
}

}  // namespace
}  // namespace igi
