#include "image/view_transform.h"

#include <algorithm>
#include <cmath>

#include "image/image.h"

namespace igi {

namespace {

// Khronos PBR Neutral, as its specification writes it (PBR_Neutral/README.md):
// F90 = 0.04, Ks = 0.8 - F90 where compression starts, Kd = 0.15 the speed of
// desaturation.
glm::vec3 pbr_neutral(glm::vec3 c) {
  constexpr float kF90 = 0.04f, kStart = 0.8f - kF90, kDesaturation = 0.15f;
  const float x = std::min({c.x, c.y, c.z});
  const float offset = x <= 2.0f * kF90 ? x - x * x / (4.0f * kF90) : kF90;  // the surface's reflection, taken off
  c -= offset;
  const float peak = std::max({c.x, c.y, c.z});
  if (peak <= kStart) return c;
  const float d = 1.0f - kStart;
  const float new_peak = 1.0f - d * d / (peak + d - kStart);  // the peak, compressed towards 1
  const float g = 1.0f / (kDesaturation * (peak - new_peak) + 1.0f);  // how much colour is kept
  return c * (new_peak / peak) * g + glm::vec3(new_peak) * (1.0f - g);
}

// AgX's constants. Log2 encoding: middle grey 0.18, 10 stops under it at 0 and
// 6.5 over it at 1. The sigmoid (Troy Sobotka's, after Jed Smith's tunable
// sigmoid; EaryChow/AgX_LUT_Gen sigmoid.py with no linear section): through
// the pivot (x_p, y_p) = (10 / 16.5, 0.18^(1/2.4)) with slope 2.4 there, and
// toe and shoulder h(t) = t / (1 + t^p)^(1/p) of power p = 1.5, each scaled
// so the curve meets (0, 0) and (1, 1).
constexpr double kMiddleGrey = 0.18, kStopsUnder = 10.0, kStopsOver = 6.5;
constexpr double kSlope = 2.4, kPower = 1.5;
constexpr double kPivotX = kStopsUnder / (kStopsUnder + kStopsOver);
const double kPivotY = std::pow(kMiddleGrey, 1.0 / 2.4);

// The scale of the toe or shoulder that spans `dx` of input and `dy` of output from the pivot.
double sigmoid_scale(double dx, double dy) {
  return std::pow(std::pow(kSlope * dx, -kPower) * (std::pow(kSlope * dx / dy, kPower) - 1.0), -1.0 / kPower);
}
const float kToeScale = float(-sigmoid_scale(kPivotX, kPivotY));
const float kShoulderScale = float(sigmoid_scale(1.0 - kPivotX, 1.0 - kPivotY));

// Matrices as written with row vectors (v' = v M), which glm's column-major
// constructor turns into M' v. Rec.709 to Rec.2020 (ITU-R BT.2087); AgX's
// inset and outset in Rec.2020 (Blender's config.ocio, EaryChow's AgX), all as
// allenwp/AgX-GLSL-Shaders' combined-AgX-matrices.txt lists them.
const glm::mat3 kRec709ToRec2020(0.627403895934699f, 0.069097289358232f, 0.016391438875150f,
                                 0.329283038377884f, 0.919540395075458f, 0.088013307877226f,
                                 0.043313065687417f, 0.011362315566309f, 0.895595253247624f);
const glm::mat3 kAgxInset(0.856627153315983f, 0.137318972929847f, 0.11189821299995f,
                          0.0951212405381588f, 0.761241990602591f, 0.0767994186031903f,
                          0.0482516061458583f, 0.101439036467562f, 0.811302368396859f);
const glm::mat3 kAgxOutset(0.899796955911611f, 0.11142098895748f, 0.11142098895748f,
                           0.0871996192028351f, 0.875575586156966f, 0.0871996192028349f,
                           0.013003424885555f, 0.0130034248855548f, 0.801379391839686f);
const glm::mat3 kInset = kAgxInset * kRec709ToRec2020;
const glm::mat3 kOutset = glm::inverse(kRec709ToRec2020) * glm::inverse(kAgxOutset);

glm::vec3 agx(glm::vec3 c) {
  const float log2_min = float(std::log2(kMiddleGrey) - kStopsUnder), range = float(kStopsUnder + kStopsOver);
  c = kInset * c;
  glm::vec3 formed;
  for (int i = 0; i < 3; ++i) {
    const float x = std::max((std::log2(std::max(c[i], 1e-10f)) - log2_min) / range, 0.0f);
    formed[i] = std::pow(agx_sigmoid(x), 2.4f);  // the sigmoid's values are for a 2.4 display: linear again
  }
  return glm::clamp(kOutset * formed, 0.0f, 1.0f);
}

}  // namespace

float agx_sigmoid(float x) {
  const float scale = x < float(kPivotX) ? kToeScale : kShoulderScale;
  const float t = float(kSlope) * (x - float(kPivotX)) / scale;  // >= 0 on both sides
  const float p = float(kPower);
  return float(kPivotY) + scale * t / std::pow(1.0f + std::pow(t, p), 1.0f / p);
}

const char* view_name(ViewTransform view) {
  switch (view) {
    case ViewTransform::Standard: return "standard";
    case ViewTransform::Neutral: return "neutral";
    case ViewTransform::Agx: return "agx";
  }
  return "?";
}

std::optional<ViewTransform> parse_view(const std::string& name) {
  for (ViewTransform v : kViewTransforms)
    if (name == view_name(v)) return v;
  return std::nullopt;
}

glm::vec3 view_transform(glm::vec3 exposed, ViewTransform view) {
  switch (view) {
    case ViewTransform::Standard: return glm::clamp(exposed, 0.0f, 1.0f);
    case ViewTransform::Neutral: return pbr_neutral(glm::max(exposed, 0.0f));
    case ViewTransform::Agx: return agx(glm::max(exposed, 0.0f));
  }
  return exposed;
}

std::array<uint8_t, 3> tone_map_srgb8(glm::vec3 linear, const ToneMapping& tone) {
  const glm::vec3 shown = view_transform(tone.exposure * linear, tone.view);
  std::array<uint8_t, 3> bytes;
  for (int c = 0; c < 3; ++c) bytes[size_t(c)] = uint8_t(std::lround(255.0f * linear_to_srgb(shown[c])));
  return bytes;
}

namespace {

constexpr float kTableStep = (kViewTableLog2Max - kViewTableLog2Min) / float(kViewTableSize - 1);
static_assert(kViewTableLog2Min < 0.0f && kViewTableLog2Max > 0.0f);

// The exposed value of node n of a channel: the lowest node stands for black.
float table_node(int n) { return n == 0 ? 0.0f : std::exp2(kViewTableLog2Min + kTableStep * float(n)); }

// Red fastest, as a 3-D texture's texels.
size_t table_index(glm::ivec3 node) {
  constexpr size_t n = kViewTableSize;
  return size_t(node.x) + n * (size_t(node.y) + n * size_t(node.z));
}

// Where a channel falls between the nodes, in node units.
float table_coordinate(float exposed) {
  const float log2 = std::log2(std::max(exposed, std::exp2(kViewTableLog2Min)));
  return std::clamp((log2 - kViewTableLog2Min) / kTableStep, 0.0f, float(kViewTableSize - 1));
}

}  // namespace

std::vector<glm::vec3> view_table(ViewTransform view) {
  constexpr int n = kViewTableSize;
  std::vector<glm::vec3> table(size_t(n) * n * n);
  for (int b = 0; b < n; ++b)
    for (int g = 0; g < n; ++g)
      for (int r = 0; r < n; ++r) {
        const glm::vec3 shown = view_transform(glm::vec3(table_node(r), table_node(g), table_node(b)), view);
        table[table_index({r, g, b})] = glm::vec3(linear_to_srgb(shown.x), linear_to_srgb(shown.y), linear_to_srgb(shown.z));
      }
  return table;
}

glm::vec3 view_table_lookup(const std::vector<glm::vec3>& table, glm::vec3 exposed) {
  constexpr int n = kViewTableSize;
  glm::ivec3 base;
  glm::vec3 f;
  for (int c = 0; c < 3; ++c) {
    const float u = table_coordinate(exposed[c]);
    base[c] = std::min(int(u), n - 2);
    f[c] = u - float(base[c]);
  }
  // The tetrahedron of the cell that holds the point: from the base corner, a
  // step along the axis of the largest fraction, then the next, then the last.
  int order[3] = {0, 1, 2};
  std::sort(order, order + 3, [&](int a, int b) { return f[a] > f[b]; });
  glm::ivec3 corner = base;
  glm::vec3 sum = (1.0f - f[order[0]]) * table[table_index(corner)];
  for (int step = 0; step < 3; ++step) {
    corner[order[step]] += 1;
    const float next = step < 2 ? f[order[step + 1]] : 0.0f;
    sum += (f[order[step]] - next) * table[table_index(corner)];
  }
  return sum;
}

}  // namespace igi
