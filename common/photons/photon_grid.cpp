#include "photons/photon_grid.h"

#include <bit>

namespace igi {

PhotonGrid::PhotonGrid(const std::vector<Photon>& photons, float radius, glm::vec3 origin)
    : radius_(radius), inv_cell_(0.5f / radius), origin_(origin) {
  const uint32_t buckets = std::bit_ceil(uint32_t(std::max<size_t>(2 * photons.size(), 16)));
  mask_ = buckets - 1;
  // Counting sort by bucket: stable, so path order survives inside a bucket.
  std::vector<uint32_t> key(photons.size());
  begin_.assign(size_t(buckets) + 1, 0);
  for (size_t i = 0; i < photons.size(); ++i) {
    key[i] = bucket(cell(photons[i].position));
    ++begin_[key[i] + 1];
  }
  occupied_.assign((size_t(buckets) + 63) / 64, 0);
  for (uint32_t b = 0; b < buckets; ++b)
    if (begin_[b + 1] > 0) occupied_[b >> 6] |= uint64_t(1) << (b & 63);
  for (uint32_t b = 0; b < buckets; ++b) begin_[b + 1] += begin_[b];
  std::vector<uint32_t> fill(begin_.begin(), begin_.end() - 1);
  photons_.resize(photons.size());
  for (size_t i = 0; i < photons.size(); ++i) photons_[fill[key[i]]++] = photons[i];
  positions_.resize(photons_.size());
  for (size_t i = 0; i < photons_.size(); ++i) positions_[i] = photons_[i].position;
}

}  // namespace igi
