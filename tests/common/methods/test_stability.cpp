// Where many-light methods fail, measured: each test prints its figure and
// fails when it crosses the stated bound (the short CI form of the accuracy
// suite; scripts/bench-accuracy.sh is the long form).
//
//   a. corners    energy a clamped ir render loses in a corner region, per clamp
//   b. glossy     largest pixel error and relMSE on a GGX floor, per clamp
//   c. occlusion  relMSE at a fixed VPL budget: many rooms against the Cornell box
//   d. temporal   flicker along a camera path, same seed against fresh seeds
//   e. few VPLs   the interleaving pattern's spectral peak at 1/N cycles per
//                 pixel, discontinuity filter on and off
//
// Images are tiny (48 x 36) so the whole file runs in well under a minute on
// two cores. Unclamped VPL estimates have infinite variance (E[1/r^4]
// diverges), so every VPL figure uses fixed seeds: the figures are
// deterministic for a given build. Each bound sits about 1.5x beyond the
// figure measured when it was set (2026-12-03, named beside it), so a change
// that makes a method half again worse fails here.
#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <map>

#include <gtest/gtest.h>

#include "core/gbuffer.h"
#include "image/metrics.h"
#include "render/offline_render.h"
#include "scene/builtin_scenes.h"
#include "scene/suite_scenes.h"
#include "support/image_compare.h"
#include "support/render_fixture.h"

namespace igi {
namespace {

using test::luminance;
using test::vpl_settings;

constexpr int kWidth = 48, kHeight = 36;

RenderSettings pt_settings() {
  RenderSettings s;
  s.method = MethodKind::PathTracer;
  return s;
}

// One prepared scene per name for the whole file (BVHs are not free).
const test::Prepared& prepared(const std::string& name) {
  static std::map<std::string, std::unique_ptr<test::Prepared>> cache;
  auto& p = cache[name];
  if (!p) p = std::make_unique<test::Prepared>(make_builtin_scene(name));
  return *p;
}

// Path-traced references, computed once per run.
const Image& reference(const std::string& name, int spp) {
  static std::map<std::string, Image> cache;
  auto it = cache.find(name);
  if (it == cache.end()) it = cache.emplace(name, prepared(name).render(pt_settings(), kWidth, kHeight, spp, 7)).first;
  return it->second;
}

// Visible points (pixel centres) of the camera's frame.
std::vector<GSample> visible_points(const test::Prepared& p) {
  return p.visible_points(kWidth, kHeight);
}


// a. The corner scene's light lands in one corner; the clamp cuts the
// 1/r^2 of the VPLs crowded there, so the corner itself goes dark.
TEST(Stability, CornerEnergyLossPerClamp) {
  const test::Prepared& p = prepared("corner");
  const Image& ref = reference("corner", 512);
  const std::vector<GSample> g = visible_points(p);
  const glm::vec3 corner(4.0f, 0.0f, 4.0f);
  // 1 - sum(image) / sum(base) over pixels seeing a point within `radius` of the corner.
  auto loss_in = [&](const Image& image, const Image& base, float radius) {
    double a = 0, b = 0;
    for (size_t i = 0; i < g.size(); ++i)
      if (g[i].valid() && glm::distance(g[i].surface.position, corner) < radius) {
        a += luminance(image.pixels[i]);
        b += luminance(base.pixels[i]);
      }
    return 1.0 - a / b;
  };
  // The same seeds for every clamp: the VPLs are identical, so the loss
  // against the unclamped render is the clamp's alone, free of noise.
  // 8 frames of one clamp each (no relaxation across them).
  auto render = [&](float clamp) {
    return p.render_frames(vpl_settings(MethodKind::InstantRadiosity, 8, clamp), kWidth, kHeight, 8);
  };
  const Image unclamped = render(0.0f);
  const double noise = loss_in(unclamped, ref, 0.5f);
  std::printf("[corner] unclamped ir M=8 x 8 frames against pt: corner (0.5 m) %+.1f %%, image %+.1f %%\n",
              -100 * noise, -100 * loss_in(unclamped, ref, 100.0f));
  EXPECT_LT(std::abs(noise), 0.06) << "bound: unclamped ir within 6 % of pt in the corner (measured 3.9 %)";
  double previous = 0.0;
  for (float fraction : {0.01f, 0.03f, 0.1f}) {  // of the room's diagonal
    const float clamp = p.clamp_at(fraction * p.scene.bounds().diagonal());
    const Image image = render(clamp);
    const double loss = loss_in(image, unclamped, 0.5f), whole = loss_in(image, unclamped, 100.0f);
    std::printf("[corner] clamp %.2f: corner (0.5 m) loses %5.1f %% (%5.1f %% against pt), whole image %5.1f %%\n",
                clamp, 100 * loss, 100 * loss_in(image, ref, 0.5f), 100 * whole);
    EXPECT_GE(loss, previous) << "more clamping, more loss";
    // A 6 cm clamp (1 % of the room's diagonal) hardly reaches the corner's VPLs; from 0.03 on the corner loses most.
    if (fraction >= 0.03f) {
      EXPECT_GT(loss, 1.5 * whole) << "the loss concentrates in the corner";
    }
    previous = loss;
  }
  EXPECT_LT(previous, 0.18) << "bound: clamp 0.1 loses under 18 % in the corner (measured 11.8 %)";
}

// b. VPLs seen through a glossy lobe are spikes; the clamp trades them for bias.
TEST(Stability, GlossyLargestErrorPerClamp) {
  const test::Prepared& p = prepared("glossy");
  const Image& ref = reference("glossy", 512);
  const std::vector<GSample> g = visible_points(p);
  std::map<float, double> peak, error;
  for (float clamp : {0.0f, 0.02f, 0.1f}) {
    const Image image = p.render(vpl_settings(MethodKind::Igi, 16, clamp), kWidth, kHeight, 2, 1);
    peak[clamp] = 0.0;  // over the metal floor, where the spikes are
    for (size_t i = 0; i < g.size(); ++i)
      if (g[i].valid() && g[i].surface.material->type == MaterialType::Conductor)
        for (int c = 0; c < 3; ++c)
          peak[clamp] = std::max(peak[clamp], double(std::abs(image.pixels[i][c] - ref.pixels[i][c])));
    error[clamp] = rel_mse(image, ref);
    std::printf("[glossy] igi M=16 x 2, clamp %.2f: largest error on the floor %7.3f, relMSE %.4f\n", clamp,
                peak[clamp], error[clamp]);
  }
  // Measured: the floor's largest error does not move with the clamp: the
  // spikes come from the GGX lobe, not from 1/r^2, so G-clamping leaves them.
  EXPECT_LE(peak[0.1f], peak[0.0f]) << "clamping never raises the spikes";
  EXPECT_LT(peak[0.02f], 0.55) << "bound: largest floor error at clamp 0.02 (measured 0.364)";
  EXPECT_LT(error[0.02f], 0.025) << "bound: relMSE at clamp 0.02 (measured 0.0164)";
}

// c. The same VPL budget spread over 16 rooms, most of them hidden.
TEST(Stability, OcclusionErrorAtFixedVplBudget) {
  std::map<std::string, double> error;
  for (const char* name : {"cornell", "rooms"}) {
    const Image& ref = reference(name, 512);
    const Image image = prepared(name).render(vpl_settings(MethodKind::Igi, 16, 0.02f), kWidth, kHeight, 4, 1);
    error[name] = rel_mse(image, ref);
    std::printf("[occlusion] %-8s igi M=16 x 4 passes, clamp 0.02: relMSE %.4f\n", name, error[name]);
  }
  std::printf("[occlusion] rooms / cornell: %.1fx\n", error["rooms"] / error["cornell"]);
  EXPECT_LT(error["cornell"], 0.008) << "bound: the open box (measured 0.0053)";
  EXPECT_LT(error["rooms"], 0.28) << "bound: many rooms (measured 0.186)";
}

// d. Mean absolute luminance difference of consecutive frames over the back
// wall while the camera slides parallel to it (the wall's shading barely
// moves, so what changes is the estimator).
TEST(Stability, TemporalFlickerSameSeedAgainstFreshSeed) {
  const test::Prepared& p = prepared("cornell");
  const int frames = 6;
  auto flicker = [&](bool fresh_seed) {
    const RenderSettings settings = vpl_settings(MethodKind::Igi, 8, 0.02f);
    Image previous;
    double sum = 0;
    int count = 0;
    for (int f = 0; f < frames; ++f) {
      FrameSetup frame = p.frame(kWidth, kHeight, fresh_seed ? 1 + 977u * f : 1);
      frame.camera.position.x += 0.004f * float(f);  // 4 mm a frame
      FrameOptions options;
      const Image image = render_offline(p.context(), settings, frame, 1, options).image;
      if (f > 0)
        for (int y = 8; y < 14; ++y)  // the upper back wall
          for (int x = 15; x < 33; ++x) {
            sum += std::abs(luminance(image.at(x, y)) - luminance(previous.at(x, y)));
            ++count;
          }
      previous = image;
    }
    return sum / count;
  };
  const double same = flicker(false), fresh = flicker(true);
  std::printf("[temporal] %d frames: flicker same seed %.5f, fresh seed %.5f (%.1fx)\n", frames, same, fresh,
              fresh / same);
  EXPECT_LT(same, 0.22 * fresh) << "bound: a fixed seed cuts the flicker to under 0.22 of it (measured 0.15)";
}

// d2. The same measure where light importance and bidirectional IR act
// (rooms-4, the camera sliding 2 cm a frame sideways, whole image, averaged
// over three seeds: one seed's figure moves by 10 % with the random numbers).
// Their VPLs follow the view, so they change as the camera moves while plain
// igi's stay put; what matters is whether the image flickers more.
double rooms_flicker(const RenderSettings& settings) {
  const test::Prepared& p = prepared("rooms");
  const int frames = 6;
  double sum = 0, mean = 0;
  for (uint32_t seed : {1u, 1001u, 2001u}) {
    Image previous;
    for (int f = 0; f < frames; ++f) {
      FrameSetup frame = p.frame(kWidth, kHeight, seed);
      frame.camera.position.x += 0.02f * float(f);
      const Image image = render_offline(p.context(), settings, frame, 1, FrameOptions{}).image;
      if (f > 0)
        for (size_t i = 0; i < image.pixels.size(); ++i) {
          sum += std::abs(luminance(image.pixels[i]) - luminance(previous.pixels[i]));
          mean += luminance(image.pixels[i]);
        }
      previous = image;
    }
  }
  return sum / mean;
}

TEST(Stability, TemporalFlickerWithLightImportanceAndBidirectionalIr) {
  RenderSettings plain = vpl_settings(MethodKind::Igi, 16, 0.05f, true, 0, 4);
  RenderSettings importance = plain;
  importance.importance_paths = 4096;
  RenderSettings bidir = plain;
  bidir.bidir_vpls = 32;
  const double f_plain = rooms_flicker(plain), f_importance = rooms_flicker(importance), f_bidir = rooms_flicker(bidir);
  std::printf("[temporal] rooms-4, 2 cm a frame: flicker (mean |dL| / mean L) plain %.4f, importance %.4f (%.2fx), "
              "bidirectional %.4f (%.2fx)\n", f_plain, f_importance, f_importance / f_plain, f_bidir, f_bidir / f_plain);
  EXPECT_LE(f_importance, 1.05 * f_plain) << "light importance flickers no more than plain igi";
  // Missed for bidirectional IR (README, "Bidirectional IR"): its reverse VPLs
  // move with the camera and its draws change; bound: a quarter more.
  EXPECT_LE(f_bidir, 1.25 * f_plain);
}

// e. Power of the region's luminance at the N-periodic frequencies (k/N
// cycles per pixel, DC excluded), relative to its mean.
double interleave_peak(const Image& image, int x0, int y0, int w, int h, int n) {
  double mean = 0;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) mean += luminance(image.at(x, y));
  mean /= double(w) * h;
  double peak = 0;
  for (int u = 0; u < n; ++u)
    for (int v = 0; v < n; ++v) {
      if (u == 0 && v == 0) continue;
      std::complex<double> f = 0;
      for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x)
          f += luminance(image.at(x, y)) * std::polar(1.0, -2.0 * M_PI * (double(u * x) + double(v * y)) / n);
      peak = std::max(peak, std::abs(f) / (double(w) * h));
    }
  return peak / mean;
}

TEST(Stability, FewVplsInterleavingPatternWithFilterOnAndOff) {
  const test::Prepared& p = prepared("cornell");
  const std::vector<GSample> g = visible_points(p);
  // 18 x 6 pixels of the back wall (a multiple of N = 3 each way).
  const int x0 = 15, y0 = 8, w = 18, h = 6;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x)
      ASSERT_GT(g[size_t(y) * kWidth + x].surface.geometric_normal.z * -1.0f, 0.99f) << "back wall at " << x << "," << y;
  double peak[2];
  for (int filter : {0, 1}) {
    const Image image = p.render(vpl_settings(MethodKind::Igi, 2, 0.02f, filter), kWidth, kHeight, 1, 1);
    peak[filter] = interleave_peak(image, x0, y0, w, h, 3);
    std::printf("[few vpls] igi M=2, filter %s: peak at 1/3 cycle/pixel %.4f of the mean\n", filter ? "on " : "off",
                peak[filter]);
  }
  EXPECT_GT(peak[0], 0.15) << "without the filter the 3x3 pattern shows (measured 0.229)";
  EXPECT_LT(peak[1], 0.27 * peak[0]) << "bound: the filter removes at least 73 % of it (measured 82 %)";
}

}  // namespace
}  // namespace igi
