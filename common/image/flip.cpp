#include "image/flip.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace igi {
namespace {

// One float channel of an image.
struct Plane {
  int width = 0, height = 0;
  std::vector<float> v;
  Plane(int w, int h) : width(w), height(h), v(size_t(w) * h, 0.0f) {}
  float& at(int x, int y) { return v[size_t(y) * width + x]; }
  float at(int x, int y) const { return v[size_t(y) * width + x]; }
};

// Separable convolution with clamp-to-edge: kx along rows, then ky along
// columns; both kernels have odd length and are centred.
Plane convolve(const Plane& in, const std::vector<float>& kx, const std::vector<float>& ky) {
  const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
  Plane rows(in.width, in.height), out(in.width, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      float sum = 0.0f;
      for (int k = -rx; k <= rx; ++k) sum += kx[size_t(k + rx)] * in.at(std::clamp(x - k, 0, in.width - 1), y);
      rows.at(x, y) = sum;
    }
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x) {
      float sum = 0.0f;
      for (int k = -ry; k <= ry; ++k) sum += ky[size_t(k + ry)] * rows.at(x, std::clamp(y - k, 0, in.height - 1));
      out.at(x, y) = sum;
    }
  return out;
}

// Linear sRGB <-> XYZ, with flip.py's exact fractions.
const glm::mat3 kRgbToXyz = glm::transpose(glm::mat3(
    10135552.0f / 24577794.0f, 8788810.0f / 24577794.0f, 4435075.0f / 24577794.0f,
    2613072.0f / 12288897.0f, 8788810.0f / 12288897.0f, 887015.0f / 12288897.0f,
    1425312.0f / 73733382.0f, 8788810.0f / 73733382.0f, 70074185.0f / 73733382.0f));
const glm::mat3 kXyzToRgb = glm::inverse(kRgbToXyz);
const glm::vec3 kWhite = kRgbToXyz * glm::vec3(1.0f);  // D65, the reference illuminant

glm::vec3 xyz_to_ycxcz(glm::vec3 xyz) {
  xyz /= kWhite;
  return {116.0f * xyz.y - 16.0f, 500.0f * (xyz.x - xyz.y), 200.0f * (xyz.y - xyz.z)};
}

glm::vec3 ycxcz_to_xyz(glm::vec3 c) {
  const float y = (c.x + 16.0f) / 116.0f;
  return glm::vec3(c.y / 500.0f + y, y, y - c.z / 200.0f) * kWhite;
}

// CIELAB with the Hunt adjustment (chroma scaled by L/100).
glm::vec3 linear_rgb_to_hunt_lab(glm::vec3 rgb) {
  glm::vec3 xyz = (kRgbToXyz * rgb) / kWhite;
  const float delta = 6.0f / 29.0f;
  for (int c = 0; c < 3; ++c)
    xyz[c] = xyz[c] > delta * delta * delta ? std::cbrt(xyz[c]) : xyz[c] / (3.0f * delta * delta) + 4.0f / 29.0f;
  const float l = 116.0f * xyz.y - 16.0f;
  return {l, 0.01f * l * 500.0f * (xyz.x - xyz.y), 0.01f * l * 200.0f * (xyz.y - xyz.z)};
}

float hyab(glm::vec3 a, glm::vec3 b) {
  return std::abs(a.x - b.x) + std::sqrt((a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
}

// A CSF filter is a sum of two Gaussians a sqrt(pi/b) exp(-pi^2 r^2 / b), r in
// degrees, normalised to unit sum over the (2R+1)^2 window. Each Gaussian is
// separable, so filtering is a weighted sum of two separable passes.
struct CsfTerm {
  float weight;               // share of the 2D kernel's sum
  std::vector<float> kernel;  // 1D, unit sum
};

std::vector<CsfTerm> csf_filter(float a1, float b1, float a2, float b2, float ppd) {
  const float b_max = 0.04f;  // the largest b of all three channels sets one radius
  const int radius = int(std::ceil(3.0f * std::sqrt(b_max / (2.0f * float(M_PI * M_PI))) * ppd));
  std::vector<CsfTerm> terms;
  double total = 0.0;
  for (auto [a, b] : {std::pair{a1, b1}, std::pair{a2, b2}}) {
    if (a == 0.0f) continue;
    CsfTerm t{0.0f, std::vector<float>(size_t(2 * radius + 1))};
    double sum = 0.0;
    for (int i = -radius; i <= radius; ++i) {
      const double x = double(i) / ppd;
      sum += t.kernel[size_t(i + radius)] = float(std::exp(-M_PI * M_PI * x * x / b));
    }
    for (float& k : t.kernel) k = float(k / sum);
    const double mass = a * std::sqrt(M_PI / b) * sum * sum;  // this term's 2D sum
    t.weight = float(mass);
    total += mass;
    terms.push_back(std::move(t));
  }
  for (CsfTerm& t : terms) t.weight = float(t.weight / total);
  return terms;
}

Plane csf_blur(const Plane& in, const std::vector<CsfTerm>& terms) {
  Plane out(in.width, in.height);
  for (const CsfTerm& t : terms) {
    const Plane part = convolve(in, t.kernel, t.kernel);
    for (size_t i = 0; i < out.v.size(); ++i) out.v[i] += t.weight * part.v[i];
  }
  return out;
}

// Colour pipeline up to the Hunt-adjusted L*a*b* of the blurred image.
std::vector<glm::vec3> filtered_lab(const Image& srgb, float ppd) {
  const int w = srgb.width, h = srgb.height;
  std::vector<Plane> opponent(3, Plane(w, h));
  for (size_t i = 0; i < srgb.pixels.size(); ++i) {
    glm::vec3 linear;
    for (int c = 0; c < 3; ++c) linear[c] = srgb_to_linear(std::clamp(srgb.pixels[i][c], 0.0f, 1.0f));
    const glm::vec3 o = xyz_to_ycxcz(kRgbToXyz * linear);
    for (int c = 0; c < 3; ++c) opponent[size_t(c)].v[i] = o[c];
  }
  // Achromatic, red-green, blue-yellow contrast sensitivity (flip.py).
  const std::vector<CsfTerm> csf[3] = {csf_filter(1.0f, 0.0047f, 0.0f, 1e-5f, ppd),
                                       csf_filter(1.0f, 0.0053f, 0.0f, 1e-5f, ppd),
                                       csf_filter(34.1f, 0.04f, 13.5f, 0.025f, ppd)};
  for (int c = 0; c < 3; ++c) opponent[size_t(c)] = csf_blur(opponent[size_t(c)], csf[c]);
  std::vector<glm::vec3> lab(srgb.pixels.size());
  for (size_t i = 0; i < lab.size(); ++i) {
    const glm::vec3 o(opponent[0].v[i], opponent[1].v[i], opponent[2].v[i]);
    const glm::vec3 rgb = glm::clamp(kXyzToRgb * ycxcz_to_xyz(o), 0.0f, 1.0f);  // back into gamut
    lab[i] = linear_rgb_to_hunt_lab(rgb);
  }
  return lab;
}

// HyAB^qc remapped so that differences up to pc * cmax fill [0, pt].
float colour_error(float distance) {
  const float qc = 0.7f, pc = 0.4f, pt = 0.95f;
  static const float cmax = std::pow(hyab(linear_rgb_to_hunt_lab({0, 1, 0}), linear_rgb_to_hunt_lab({0, 0, 1})), qc);
  const float d = std::pow(distance, qc);
  if (d < pc * cmax) return pt / (pc * cmax) * d;
  return std::min(1.0f, pt + (d - pc * cmax) / (cmax - pc * cmax) * (1.0f - pt));
}

// Edge (order 1) or point (order 2) detector along x: derivatives of a
// Gaussian of sd = 0.5 * 0.082 degrees, positive and negative lobes each
// normalised to unit sum. The y kernel is the plain Gaussian of unit sum
// (the 2D kernel's lobes then sum to one as in flip.py).
void feature_kernels(float ppd, int order, std::vector<float>& along, std::vector<float>& across) {
  const float sd = 0.5f * 0.082f * ppd;
  const int radius = int(std::ceil(3.0f * sd));
  along.assign(size_t(2 * radius + 1), 0.0f);
  across.assign(size_t(2 * radius + 1), 0.0f);
  double positive = 0, negative = 0, gauss = 0;
  for (int i = -radius; i <= radius; ++i) {
    const float g = std::exp(-float(i * i) / (2.0f * sd * sd));
    const float k = order == 1 ? -float(i) * g : (float(i * i) / (sd * sd) - 1.0f) * g;
    along[size_t(i + radius)] = k;
    across[size_t(i + radius)] = g;
    (k > 0 ? positive : negative) += std::abs(k);
    gauss += g;
  }
  for (float& k : along) k = float(k > 0 ? k / positive : k / negative);
  for (float& g : across) g = float(g / gauss);
}

// |(response along x, response along y)| of the detector, per pixel.
Plane feature_magnitude(const Plane& luminance, float ppd, int order) {
  std::vector<float> along, across;
  feature_kernels(ppd, order, along, across);
  // convolve() takes the row kernel first: x-derivative, then y-derivative.
  const Plane fx = convolve(luminance, along, across);
  const Plane fy = convolve(luminance, across, along);
  Plane m(luminance.width, luminance.height);
  for (size_t i = 0; i < m.v.size(); ++i) m.v[i] = std::hypot(fx.v[i], fy.v[i]);
  return m;
}

// Achromatic channel of the unfiltered image, normalised to [0, 1].
Plane normalised_luminance(const Image& srgb) {
  Plane y(srgb.width, srgb.height);
  for (size_t i = 0; i < srgb.pixels.size(); ++i) {
    glm::vec3 linear;
    for (int c = 0; c < 3; ++c) linear[c] = srgb_to_linear(std::clamp(srgb.pixels[i][c], 0.0f, 1.0f));
    y.v[i] = (xyz_to_ycxcz(kRgbToXyz * linear).x + 16.0f) / 116.0f;
  }
  return y;
}

}  // namespace

double FlipMap::mean() const {
  double sum = 0.0;
  for (float e : error) sum += e;
  return error.empty() ? 0.0 : sum / double(error.size());
}

FlipMap flip_ldr(const Image& test, const Image& reference, float ppd) {
  if (test.width != reference.width || test.height != reference.height)
    throw std::invalid_argument("flip: image sizes differ: " + std::to_string(test.width) + "x" +
                                std::to_string(test.height) + " vs " + std::to_string(reference.width) + "x" +
                                std::to_string(reference.height));
  const std::vector<glm::vec3> lab_test = filtered_lab(test, ppd), lab_ref = filtered_lab(reference, ppd);
  const Plane y_test = normalised_luminance(test), y_ref = normalised_luminance(reference);
  const Plane edges_test = feature_magnitude(y_test, ppd, 1), edges_ref = feature_magnitude(y_ref, ppd, 1);
  const Plane points_test = feature_magnitude(y_test, ppd, 2), points_ref = feature_magnitude(y_ref, ppd, 2);
  const float qf = 0.5f;
  FlipMap map{test.width, test.height, std::vector<float>(test.pixels.size())};
  for (size_t i = 0; i < map.error.size(); ++i) {
    const float colour = colour_error(hyab(lab_test[i], lab_ref[i]));
    const float feature_difference = std::max(std::abs(edges_ref.v[i] - edges_test.v[i]),
                                              std::abs(points_ref.v[i] - points_test.v[i]));
    const float feature = std::pow(feature_difference / std::sqrt(2.0f), qf);
    map.error[i] = std::pow(colour, 1.0f - feature);
  }
  return map;
}

Image tonemap_for_flip(const Image& linear, float exposure) {
  Image out(linear.width, linear.height);
  for (size_t i = 0; i < linear.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      out.pixels[i][c] = linear_to_srgb(std::clamp(exposure * linear.pixels[i][c], 0.0f, 1.0f));
  return out;
}

double mean_flip(const Image& test, const Image& reference, float exposure, float ppd) {
  return flip_ldr(tonemap_for_flip(test, exposure), tonemap_for_flip(reference, exposure), ppd).mean();
}

}  // namespace igi
