#pragma once
// A hashed uniform grid over photons, for fixed-radius density estimation.
//
// Why a grid and not k nearest neighbours: the frame's map is rebuilt every
// frame on every worker, so building must be cheap and deterministic; a
// counting sort by cell is O(N) with no balancing and no ties to break,
// where a kd-tree is O(N log N). A fixed radius also makes a lookup's cost
// bounded by the photon density (at most 8 cells), not by a heap of k
// candidates, and gives every pixel the same kernel, so the estimate is
// smooth across a surface; kNN adapts its radius (sharper in dense regions,
// blurrier in sparse ones), which a fixed radius trades for predictability.
// Progressive passes lower the variance of the fixed-radius estimate; its
// bias (blur of radius r) stays, and --caustic-radius sets it.
//
// Cells are 2r wide, so the cube of half-width r around a query point
// touches at most 2 x 2 x 2 of them; cells hash into 2^k buckets
// (k: at least twice the photon count). Buckets that several of the eight
// cells share are visited once, and a photon is accepted by its distance
// alone, so collisions cost time, never correctness. Photons are stored
// bucket by bucket in path order: the same photons give the same grid. A
// bit per bucket says whether it holds any photon: most pixels are far from
// every photon, and their lookups then touch only that bitset.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "photons/photon.h"

namespace igi {

class PhotonGrid {
 public:
  PhotonGrid() = default;
  // `origin`: the scene's lower corner. Cell coordinates count from it, so
  // they stay small (at most the diagonal over 2r) wherever the scene sits.
  PhotonGrid(const std::vector<Photon>& photons, float radius, glm::vec3 origin);

  float radius() const { return radius_; }
  size_t size() const { return photons_.size(); }

  // Calls f(photon, squared distance) for every photon within the radius of p.
  template <class F>
  void for_each_within(glm::vec3 p, F&& f) const {
    if (photons_.empty()) return;
    const glm::ivec3 c0 = cell(p - radius_);
    uint32_t seen[8];
    int seen_count = 0;
    const float r2 = radius_ * radius_;
    for (int dz = 0; dz < 2; ++dz)
      for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
          const uint32_t b = bucket(c0 + glm::ivec3(dx, dy, dz));
          if (!(occupied_[b >> 6] >> (b & 63) & 1u)) continue;  // most are empty: no load of begin_
          bool again = false;
          for (int i = 0; i < seen_count; ++i) again |= seen[i] == b;
          if (again) continue;
          seen[seen_count++] = b;
          for (uint32_t i = begin_[b]; i < begin_[b + 1]; ++i) {
            const glm::vec3 d = positions_[i] - p;
            const float d2 = glm::dot(d, d);
            if (d2 < r2) f(photons_[i], d2);
          }
        }
  }

 private:
  glm::ivec3 cell(glm::vec3 p) const {
    // Clamped so that a point far outside the scene cannot overflow an int.
    const glm::vec3 c = glm::clamp(glm::floor((p - origin_) * inv_cell_), glm::vec3(-1e9f), glm::vec3(1e9f));
    return glm::ivec3(c);
  }
  uint32_t bucket(glm::ivec3 c) const {
    // Teschner et al.'s spatial hash (2003): three multiplies. A full
    // avalanche hash (sampling/hash.h) cost 7 % of a frame for the 8
    // lookups a pixel makes. Collisions cost only time (see above).
    return ((uint32_t(c.x) * 73856093u) ^ (uint32_t(c.y) * 19349663u) ^ (uint32_t(c.z) * 83492791u)) & mask_;
  }

  float radius_ = 0.0f, inv_cell_ = 0.0f;
  glm::vec3 origin_{0.0f};
  uint32_t mask_ = 0;
  std::vector<uint32_t> begin_;  // mask + 2 offsets into photons_
  std::vector<uint64_t> occupied_;  // one bit a bucket: any photon in it (small enough for L1)
  std::vector<Photon> photons_;  // grouped by bucket, path order inside each
  std::vector<glm::vec3> positions_;  // photons_' positions, packed: most candidates fail the distance test
};

}  // namespace igi
