#pragma once
// An HDR environment map: an equirectangular (latitude-longitude) image of
// the radiance arriving from every direction, read with OpenImageIO (.exr,
// .hdr, any float format it knows). Row 0 is straight up (+y, glTF's up),
// the last row straight down; the middle column looks along -z (glTF's
// default view direction), u growing towards +x. `rotation` turns the map
// about +y by that many degrees (counter-clockwise seen from above).
//
// Each texel is constant over its patch of the sphere (nearest lookup), and
// sampling picks a texel by luminance x solid angle, then a direction
// uniform over its patch (uniform in longitude and in cos of the polar
// angle): the density is exact, constant over each patch, and the estimate
// L / pdf of a patch is its luminance-weighted share (pbrt-v4's
// piecewise-constant environment light, with patches in solid angle).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "image/image.h"
#include "sampling/distribution.h"

namespace igi {

class EnvironmentMap {
 public:
  // Throws std::runtime_error naming the problem: too small (under 2 x 1),
  // too large, or a texel that is not finite or is negative.
  EnvironmentMap(Image image, float rotation_degrees);
  // Reads `path` (an equirectangular float image); errors name the file.
  static EnvironmentMap load(const std::string& path, float rotation_degrees);
  // The file it was read from (empty when made from an image): what the master sends workers.
  const std::string& source() const { return source_; }

  // Radiance arriving from `direction` (towards the sky; any length > 0).
  glm::vec3 radiance(glm::vec3 direction) const;

  struct Sample {
    glm::vec3 direction;  // unit, towards the sky
    glm::vec3 radiance;
    float pdf = 0.0f;     // solid angle
  };
  // A direction by luminance x solid angle; pdf 0 for a black map.
  Sample sample(glm::vec2 u) const;
  // The density with which sample() returns `direction`.
  float pdf(glm::vec3 direction) const;
  // Integral of the radiance over the sphere (W/m^2 for radiance W/(m^2 sr)),
  // and of its luminance.
  glm::vec3 integral() const { return integral_; }
  float luminance_integral() const { return rows_.total(); }

  int width() const { return image_.width; }
  int height() const { return image_.height; }
  float rotation() const { return rotation_; }
  const Image& image() const { return image_; }

 private:
  glm::ivec2 texel_of(glm::vec3 direction) const;  // (column, row)
  float solid_angle(int row) const;                // of one texel in `row`

  Image image_;
  std::string source_;
  float rotation_;           // degrees
  float cos_rotation_, sin_rotation_;
  std::vector<float> row_cos_;          // cos of the polar angle at each row's top edge, and the last row's bottom
  glm::vec3 integral_{0.0f};
  Distribution1D rows_;                 // each row's luminance x solid angle
  std::vector<Distribution1D> columns_;  // within each row
};

}  // namespace igi
