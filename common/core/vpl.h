#pragma once
// Virtual point lights and the interleaved sets they come in.
//
// A VPL's contribution to a surface point x, seen from direction wo, is
//   f_x(wo, wi) |cos_x| * emitted(y -> x) * V(x, y)
// where emitted depends on its kind:
//   Surface:     f_y(incident, -wi) cos_y / r^2 * flux   (a light-path hit)
//   Area:        cos_y / r^2 * flux                     (a point on an emitter; flux = Le A / pdf)
//   Point/Spot:  1 / r^2 * flux * cone(-wi)             (flux = intensity)
//   Directional: flux, from direction -normal, at infinity
// The geometry term cos_x cos_y / r^2 is what clamping bounds.
//
// VPL sets hold Surface and Area VPLs, and Directional ones for the
// environment (one per light path leaving it: the sky's direct light, from
// the path's direction, flux = irradiance L 4 pi / its choice's probability).
// Point, spot and directional lights start light paths like any light, but
// their own light is exact: the methods evaluate each once per shading point
// (core/direct_lights.h) rather than through M identical copies per set.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "lighting/lights.h"

namespace igi {

enum class VplKind : uint8_t { Surface, Area, Point, Spot, Directional };

struct Vpl {
  // Every field initialised: VPL sets are hashed and compared bit for bit.
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f};    // Surface/Area: front normal; Spot: axis; Directional: travel direction
  glm::vec3 flux{0.0f};      // already divided by the number of paths of its set
  glm::vec3 incident{0.0f};  // Surface: unit direction back towards the light path's previous vertex
  glm::vec3 albedo{0.0f};    // Surface: base colour at the hit
  uint32_t material = 0;     // Surface: Scene::materials index
  uint32_t light = 0;        // Spot: Scene::lights index (cone shape)
  // Surface, metallic-roughness: the model's metallic and alpha at the hit
  // (textured), and whether only its diffuse base radiates (with caustics,
  // photons carry what a GGX lobe sharper than the glossy threshold reflects).
  float metallic = 0.0f;
  float alpha = 1.0f;
  VplKind kind = VplKind::Surface;
  bool diffuse_only = false;
};

// S = N x N sets; set k holds the VPLs of light paths [k M, (k+1) M). Each
// set is cut into G groups of consecutive paths for anti-aliasing
// (core/subpixel.h): path i of a set is in group floor(i G / M).
struct VplSets {
  int interleave = 3;                 // N
  int groups = 1;                     // G
  std::vector<Vpl> vpls;              // all sets, one after the other, each in group order
  std::vector<uint32_t> set_begin;    // S + 1 offsets into vpls
  std::vector<uint32_t> group_begin;  // S G + 1 offsets: group g of set k starts at [k G + g]
  uint64_t hash = 0;                  // content hash, equal on every worker for equal inputs

  int set_count() const { return int(set_begin.size()) - 1; }
  uint32_t group_first(int set, int group) const { return group_begin[size_t(set) * groups + group]; }
  uint32_t group_end(int set, int group) const { return group_begin[size_t(set) * groups + group + 1]; }
  // The set a pixel uses, from its GLOBAL image coordinates.
  int set_of_pixel(int x, int y) const { return (x % interleave) + interleave * (y % interleave); }
};

}  // namespace igi
