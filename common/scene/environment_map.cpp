#include "scene/environment_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sampling/warp.h"

namespace igi {
namespace {

constexpr int kMaxSide = 1 << 14;  // 16384 x 8192 texels: 1.6 GB of floats at most

}  // namespace

EnvironmentMap::EnvironmentMap(Image image, float rotation_degrees)
    : image_(std::move(image)), rotation_(rotation_degrees) {
  if (image_.width < 2 || image_.height < 1)
    throw std::runtime_error("an environment map needs at least 2 x 1 texels");
  if (image_.width > kMaxSide || image_.height > kMaxSide)
    throw std::runtime_error("an environment map of at most " + std::to_string(kMaxSide) + " texels a side");
  if (!std::isfinite(rotation_degrees)) throw std::runtime_error("the environment's rotation must be finite");
  for (const glm::vec3& c : image_.pixels)
    if (!std::isfinite(c.x + c.y + c.z) || c.x < 0.0f || c.y < 0.0f || c.z < 0.0f)
      throw std::runtime_error("an environment map's texels must be finite and >= 0");
  const double radians = double(rotation_degrees) * (kPi / 180.0);
  cos_rotation_ = float(std::cos(radians));
  sin_rotation_ = float(std::sin(radians));
  row_cos_.resize(size_t(image_.height) + 1);
  for (int j = 0; j <= image_.height; ++j) row_cos_[j] = float(std::cos(kPi * double(j) / image_.height));
  row_cos_.back() = -1.0f;
  std::vector<float> row_weights(image_.height), texels(image_.width);
  columns_.reserve(image_.height);
  for (int j = 0; j < image_.height; ++j) {
    double sum = 0.0;
    glm::dvec3 row_sum(0.0);
    for (int i = 0; i < image_.width; ++i) {
      sum += texels[i] = luminance(image_.at(i, j));
      row_sum += glm::dvec3(image_.at(i, j));
    }
    columns_.emplace_back(texels);
    row_weights[j] = float(sum * solid_angle(j));
    integral_ += glm::vec3(row_sum * double(solid_angle(j)));
  }
  rows_ = Distribution1D(row_weights);
}

EnvironmentMap EnvironmentMap::load(const std::string& path, float rotation_degrees) {
  Image image;
  try {
    image = read_image(path);
  } catch (const std::exception& e) {
    throw std::runtime_error(std::string("environment map: ") + e.what());  // read_image names the file
  }
  try {
    EnvironmentMap map(std::move(image), rotation_degrees);
    map.source_ = path;
    return map;
  } catch (const std::exception& e) {
    throw std::runtime_error("environment map " + path + ": " + e.what());
  }
}

float EnvironmentMap::solid_angle(int row) const {
  return float(2.0 * kPi / image_.width) * (row_cos_[row] - row_cos_[row + 1]);
}

glm::ivec2 EnvironmentMap::texel_of(glm::vec3 d) const {
  d = glm::normalize(d);
  // Into the map's frame: turned back by the rotation about +y.
  const float x = cos_rotation_ * d.x - sin_rotation_ * d.z, z = sin_rotation_ * d.x + cos_rotation_ * d.z;
  const float u = 0.5f + std::atan2(x, -z) * (0.5f * kInvPi);
  const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) * kInvPi;
  return {std::clamp(int(u * image_.width), 0, image_.width - 1), std::clamp(int(v * image_.height), 0, image_.height - 1)};
}

glm::vec3 EnvironmentMap::radiance(glm::vec3 direction) const {
  const glm::ivec2 t = texel_of(direction);
  return image_.at(t.x, t.y);
}

EnvironmentMap::Sample EnvironmentMap::sample(glm::vec2 u) const {
  if (rows_.total() <= 0.0f) return {};
  float along_row, along_column;
  const uint32_t row = rows_.sample(u.x, along_column);
  const uint32_t column = columns_[row].sample(u.y, along_row);
  // Uniform over the texel's patch: longitude, and cos of the polar angle.
  const float cos_theta = row_cos_[row] + along_column * (row_cos_[row + 1] - row_cos_[row]);
  const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
  const float phi = 2.0f * kPi * ((float(column) + along_row) / image_.width - 0.5f);
  // Map frame: u = 0.5 + atan2(x, -z) / 2 pi; then turned by the rotation.
  const float x = sin_theta * std::sin(phi), z = -sin_theta * std::cos(phi);
  Sample s;
  s.direction = glm::normalize(glm::vec3(cos_rotation_ * x + sin_rotation_ * z, cos_theta,
                                         -sin_rotation_ * x + cos_rotation_ * z));
  s.radiance = image_.at(int(column), int(row));
  s.pdf = rows_.probability(row) * columns_[row].probability(column) / solid_angle(int(row));
  return s;
}

float EnvironmentMap::pdf(glm::vec3 direction) const {
  if (rows_.total() <= 0.0f) return 0.0f;
  const glm::ivec2 t = texel_of(direction);
  return rows_.probability(uint32_t(t.y)) * columns_[t.y].probability(uint32_t(t.x)) / solid_angle(t.y);
}

}  // namespace igi
