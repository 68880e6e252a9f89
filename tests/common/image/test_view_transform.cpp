// What 8-bit outputs show (issue 65): each view transform against its
// published reference values, the standard view byte for byte as before
// views, the window's table within an 8-bit step of the function, and the
// exposure meter.
#include <cmath>
#include <cstdio>
#include <random>

#include <gtest/gtest.h>

#include "image/exposure_check.h"
#include "image/image.h"
#include "image/view_transform.h"
#include "support/image_compare.h"

namespace igi {
namespace {

// Before views, every 8-bit output was this: the sRGB curve of exposure x value, clamped.
uint8_t srgb8_before_views(float value, float exposure) {
  return uint8_t(std::lround(255.0f * linear_to_srgb(exposure * value)));
}

TEST(ViewTransform, StandardIsEvery8BitOutputAsBeforeByteForByte) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(-0.5f, 3.0f), exposure(0.0f, 8.0f);
  for (int i = 0; i < 100000; ++i) {
    const glm::vec3 c(value(random), value(random), value(random));
    const float e = i < 1000 ? 1.0f : exposure(random);
    const std::array<uint8_t, 3> shown = tone_map_srgb8(c, {e, ViewTransform::Standard});
    for (int k = 0; k < 3; ++k) ASSERT_EQ(shown[size_t(k)], srgb8_before_views(c[k], e)) << c[k] << " at " << e;
  }
}

TEST(ViewTransform, NamesRoundTripAndOthersAreRefused) {
  for (ViewTransform v : kViewTransforms) EXPECT_EQ(parse_view(view_name(v)), v);
  EXPECT_FALSE(parse_view("filmic"));
}

// Khronos PBR Neutral's specification (KhronosGroup/ToneMapping,
// PBR_Neutral/README.md): "c_out = c_in - F90 for all input colors where
// 0.08 <= R, G, B <= 0.8", F90 = 0.04.
TEST(ViewTransform, NeutralShowsBaseColoursAsThemselvesLessTheSurfacesReflection) {
  std::mt19937 random(3);
  std::uniform_real_distribution<float> base(0.08f, 0.8f);
  for (int i = 0; i < 10000; ++i) {
    const glm::vec3 c(base(random), base(random), base(random));
    const glm::vec3 shown = view_transform(c, ViewTransform::Neutral);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(shown[k], c[k] - 0.04f, 1e-6f);
  }
  EXPECT_EQ(view_transform(glm::vec3(0.0f), ViewTransform::Neutral), glm::vec3(0.0f));
  // White, from the specification's equations by hand: x = 1, f = 0.04, p = 0.96, K_s = 0.76,
  // p_n = 1 - 0.24^2 / (0.96 + 1 - 1.52) = 1 - 0.0576 / 0.44 = 0.869091; a grey has no colour to mix.
  const glm::vec3 white = view_transform(glm::vec3(1.0f), ViewTransform::Neutral);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(white[k], 1.0f - 0.0576f / 0.44f, 1e-6f);
}

// The inverse the specification's authors publish beside it (PBR_Neutral/
// lut-writer.mjs, inverseNeutral), written again here from its equations:
// the forward function must undo it wherever in [0, 1)^3 it is defined.
glm::vec3 neutral_inverse(glm::vec3 c) {
  constexpr float kStart = 0.8f - 0.04f, kDesaturation = 0.15f;
  const float peak = std::max({c.x, c.y, c.z});
  if (peak > kStart) {
    const float d = 1.0f - kStart;
    const float old_peak = d * d / (1.0f - peak) - d + kStart;
    const float f_inverse = kDesaturation * (old_peak - peak) + 1.0f;
    const float f = 1.0f / f_inverse;
    c = (c + (f - 1.0f) * peak) * f_inverse * (old_peak / peak);
  }
  const float y = std::min({c.x, c.y, c.z});
  if (y < 0.0f) return glm::vec3(-1.0f);  // a colour no input shows (highlights lose saturation)
  float offset = 0.04f;
  if (y < 0.04f) {
    const float x = std::sqrt(y / 6.25f);
    offset = x - 6.25f * x * x;
  }
  return c + offset;
}

TEST(ViewTransform, NeutralUndoesItsPublishedInverseAndKeepsHue) {
  std::mt19937 random(5);
  std::uniform_real_distribution<float> shown(0.0f, 0.98f);
  for (int i = 0; i < 10000; ++i) {
    const glm::vec3 out(shown(random), shown(random), shown(random));
    const glm::vec3 in = neutral_inverse(out);
    if (std::min({in.x, in.y, in.z}) < 0.0f) continue;  // a colour no input shows (highlights lose saturation)
    const glm::vec3 again = view_transform(in, ViewTransform::Neutral);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(again[k], out[k], 2e-4f) << "from " << in[k];
    // No hue shift: out = a in + b (1, 1, 1), so the channels keep their proportions about the smallest.
    const float in_span = std::max({in.x, in.y, in.z}) - std::min({in.x, in.y, in.z});
    const float out_span = std::max({out.x, out.y, out.z}) - std::min({out.x, out.y, out.z});
    if (in_span < 1e-2f || out_span < 1e-2f) continue;
    for (int k = 0; k < 3; ++k)
      ASSERT_NEAR((in[k] - std::min({in.x, in.y, in.z})) / in_span,
                  (out[k] - std::min({out.x, out.y, out.z})) / out_span, 2e-3f);
  }
}

// Blender's AgX sigmoid as its generator publishes it, sampled at 4096 points:
// EaryChow/AgX_LUT_Gen, AgX_Default_Contrast.spi1d, entry i at x = i / 4095.
TEST(ViewTransform, AgxSigmoidIsBlendersPublishedCurve) {
  struct Entry {
    int index;
    float value;
  };
  for (const Entry e : {Entry{0, 0.0f}, Entry{410, 0.0188606f}, Entry{1024, 0.0650178f}, Entry{2048, 0.2761296f},
                        Entry{2482, 0.4895436f}, Entry{3071, 0.7741766f}, Entry{3686, 0.9369822f},
                        Entry{4095, 1.0f}})
    EXPECT_NEAR(agx_sigmoid(float(e.index) / 4095.0f), e.value, 2e-6f) << "entry " << e.index;
}

TEST(ViewTransform, AgxKeepsMiddleGreyAndRollsHighlightsOffToWhite) {
  // Middle grey shows as itself: the sigmoid's pivot is 0.18 for a 2.4 display, the matrices keep greys.
  const glm::vec3 grey = view_transform(glm::vec3(0.18f), ViewTransform::Agx);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(grey[k], 0.18f, 2e-4f);
  // White 6.5 stops over middle grey; below it every stop is still brighter than the last.
  const float white = 0.18f * std::exp2(6.5f);
  EXPECT_GT(view_transform(glm::vec3(white), ViewTransform::Agx).y, 0.999f);
  float last = 0.0f;
  for (float stops = -9.5f; stops <= 6.0f; stops += 0.5f) {
    const float shown = view_transform(glm::vec3(0.18f * std::exp2(stops)), ViewTransform::Agx).y;
    EXPECT_GT(shown, last) << stops << " stops";
    last = shown;
  }
  // Where the standard view clips flat (4 x white), agx still shows detail.
  EXPECT_LT(view_transform(glm::vec3(4.0f), ViewTransform::Agx).y, 0.9f);
  EXPECT_GT(view_transform(glm::vec3(4.0f), ViewTransform::Agx).y,
            view_transform(glm::vec3(2.0f), ViewTransform::Agx).y);
  // Saturated colours stay displayable.
  const glm::vec3 red = view_transform(glm::vec3(20.0f, 0.0f, 0.0f), ViewTransform::Agx);
  for (int k = 0; k < 3; ++k) EXPECT_TRUE(red[k] >= 0.0f && red[k] <= 1.0f) << red[k];
  EXPECT_GT(red.x, red.y);
}

// CIE L*a*b* (D65) of an sRGB-encoded colour: for colour differences (CIE76 delta E).
glm::vec3 lab(glm::vec3 encoded) {
  const glm::vec3 l(srgb_to_linear(encoded.x), srgb_to_linear(encoded.y), srgb_to_linear(encoded.z));
  const glm::vec3 xyz(0.4124f * l.x + 0.3576f * l.y + 0.1805f * l.z, 0.2126f * l.x + 0.7152f * l.y + 0.0722f * l.z,
                      0.0193f * l.x + 0.1192f * l.y + 0.9505f * l.z);
  const glm::vec3 n = xyz / glm::vec3(0.95047f, 1.0f, 1.08883f);
  auto f = [](float t) { return t > 216.0f / 24389.0f ? std::cbrt(t) : (24389.0f / 27.0f * t + 16.0f) / 116.0f; };
  return glm::vec3(116.0f * f(n.y) - 16.0f, 500.0f * (f(n.x) - f(n.y)), 200.0f * (f(n.y) - f(n.z)));
}

// The window's shader interpolates a table of the function (view_table) in
// 81^3 nodes a quarter stop apart, tetrahedrally (Khronos's own OpenColorIO
// configuration ships Neutral as 57^3 nodes over 19 stops, a third of a stop
// apart, interpolated so). Over colours from 2^-14 to 2^10: greys, and every
// colour of the standard view, within an 8-bit step of what the PNG writer
// writes; any colour of the others within CIE76 delta E 2, under a
// just-noticeable difference (2.3); measured 1.64 for neutral, 1.15 for agx,
// where a dim channel beside bright ones is off by up to 5 steps. Trilinear
// (the GPU's own filtering) was off by 5.9 steps on greys near white, delta E 3.2.
TEST(ViewTransform, TheWindowsTableShowsWhatThePngWriterWrites) {
  std::mt19937 random(11);
  std::uniform_real_distribution<float> stops(-14.0f, 10.0f);
  for (ViewTransform view : kViewTransforms) {
    const std::vector<glm::vec3> table = view_table(view);
    float grey_steps = 0.0f, steps = 0.0f, delta_e = 0.0f;
    for (int i = 0; i < 200000; ++i) {
      const bool grey = i % 4 == 0;
      const auto channel = [&] { return std::exp2(stops(random)); };
      const glm::vec3 c = grey ? glm::vec3(channel()) : glm::vec3(channel(), channel(), channel());
      const glm::vec3 shown = view_transform(c, view), looked_up = view_table_lookup(table, c);
      const glm::vec3 exact(linear_to_srgb(shown.x), linear_to_srgb(shown.y), linear_to_srgb(shown.z));
      for (int k = 0; k < 3; ++k) {
        const float step = 255.0f * std::abs(looked_up[k] - exact[k]);
        (grey ? grey_steps : steps) = std::max(grey ? grey_steps : steps, step);
      }
      delta_e = std::max(delta_e, glm::length(lab(looked_up) - lab(exact)));
    }
    std::printf("%s: the table's largest error: greys %.2f of an 8-bit step, colours %.2f, delta E %.2f\n",
                view_name(view), grey_steps, steps, delta_e);
    EXPECT_LT(grey_steps, 1.0f) << view_name(view);
    if (view == ViewTransform::Standard) {
      EXPECT_LT(steps, 1.0f);
    }
    EXPECT_LT(delta_e, 2.0f) << view_name(view);
    EXPECT_EQ(view_table_lookup(table, glm::vec3(0.0f)), glm::vec3(0.0f)) << "black stays black";
  }
}

// Float files stay linear: no exposure, no view; a PNG of the same image shows both.
TEST(ViewTransform, FloatFilesStayLinearAndUntouched) {
  Image image(8, 4);
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = glm::vec3(0.01f * float(i), 3.0f, 40.0f);
  const ToneMapping tone{8.0f, ViewTransform::Agx};
  const std::string exr = test::output_path("view-linear.exr"), png = test::output_path("view-agx.png");
  write_image(image, exr, tone);
  write_image(image, png, tone);
  const Image back = read_image(exr);
  EXPECT_EQ(back.pixels, image.pixels);
  const Image shown = read_image(png);
  const std::array<uint8_t, 3> want = tone_map_srgb8(image.pixels[5], tone);
  EXPECT_NEAR(shown.pixels[5].y, srgb_to_linear(float(want[1]) / 255.0f), 1e-6f);
}

Image uniform(glm::vec3 value) {
  Image image(40, 30);
  for (glm::vec3& p : image.pixels) p = value;
  return image;
}

TEST(ExposureMeter, PutsTheLogAverageOfTheLitPixelsAtMiddleGrey) {
  EXPECT_NEAR(metered_exposure(uniform(glm::vec3(0.5f))), 0.18f / 0.5f, 1e-5f);
  // A geometric mean: half the pixels at 0.02, half at 2 average to 0.2.
  Image split = uniform(glm::vec3(0.02f));
  for (size_t i = 0; i < split.pixels.size() / 2; ++i) split.pixels[i] = glm::vec3(2.0f);
  EXPECT_NEAR(metered_exposure(split), 0.18f / 0.2f, 1e-4f);
  // Unlit pixels (a black sky) are not metered; an image with no light keeps 1.
  Image half_black = uniform(glm::vec3(0.5f));
  for (size_t i = 0; i < half_black.pixels.size() / 2; ++i) half_black.pixels[i] = glm::vec3(0.0f);
  EXPECT_NEAR(metered_exposure(half_black), 0.18f / 0.5f, 1e-5f);
  EXPECT_EQ(metered_exposure(uniform(glm::vec3(0.0f))), 1.0f);
  // A dim room (0.002) is brought up by 90 x.
  EXPECT_NEAR(metered_exposure(uniform(glm::vec3(0.002f))), 90.0f, 1e-2f);
  // A fixed choice is what it says; auto is the meter's.
  EXPECT_EQ(exposure_for(split, {false, 3.0f}), 3.0f);
  EXPECT_EQ(exposure_for(split, {true, 3.0f}), metered_exposure(split));
}

}  // namespace
}  // namespace igi
