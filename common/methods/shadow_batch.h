#pragma once
// The inner loop of VPL shading: one VPL against 16 pixels of one set, set up
// as one 16-lane shadow packet. Pixels are kept structure-of-arrays so the common
// case (diffuse receiver, diffuse or area-light VPL) runs as plain 16-lane
// arithmetic the compiler vectorises; other lanes take the general path in
// vpl_contribution.h. Each lane's arithmetic is independent of its
// neighbours, and the packet is traced as one 16-wide Embree packet (in
// scenes small enough for packets to pay) whose rays stop off every surface
// at both ends, where a lane answers as it would alone (shadow_batch.cpp says why; ctest -R ShadowPackets), so a pixel's
// result does not depend on the packet it is in.
#include <cstdint>
#include <span>
#include <vector>

#include <embree3/rtcore.h>

#include "core/gbuffer.h"
#include "core/ray_log.h"
#include "core/vpl_contribution.h"

namespace igi {

// Shading points (one set's pixels, say), padded to a multiple of 16 lanes.
struct PixelBatch {
  std::vector<uint32_t> index;    // the caller's id of each point
  std::vector<const GSample*> sample;  // the point itself (general lanes read it)
  std::vector<float> ox, oy, oz;  // shadow-ray origin, nudged to the viewer's side
  std::vector<float> px, py, pz;  // surface position
  std::vector<float> nx, ny, nz;  // shading normal, facing the viewer
  std::vector<float> gx, gy, gz;  // geometric normal, facing the viewer
  std::vector<uint8_t> fast;      // diffuse receiver: vectorised lane
  std::vector<uint8_t> chunk_fast;  // per 16 lanes: all of them fast
  std::vector<float> sum_r, sum_g, sum_b;  // accumulated demodulated irradiance
  size_t count = 0;

  void clear();
  // `g` must be valid and outlive the batch.
  void add(uint32_t id, const GSample& g);
  void pad();  // to a multiple of 16, with inert lanes
};

struct alignas(64) ShadowPacket {
  int valid[16];
  RTCRay16 rays;
  float r[16], g[16], b[16];  // unoccluded contribution per lane
};

// Fills `packet` for lanes [first, first + 16) of `batch` against `vpl`.
void fill_shadow_packet(const PixelBatch& batch, size_t first, const Vpl& vpl, const VplShading& shading,
                        ShadowPacket& packet);
// After tracing: adds the unoccluded lanes' contributions to the batch sums.
// Returns the number of rays the packet traced.
int accumulate_shadow_packet(const ShadowPacket& packet, size_t first, PixelBatch& batch);

// Traces the packet's valid lanes (one rtcOccluded16); an occluded lane's tfar becomes -inf.
void trace_shadow_lanes(const Accel& accel, RTCIntersectContext& context, ShadowPacket& packet);

// Every VPL of `vpls` against every point of the padded batch, one packet
// per VPL and 16 points, added to the batch's sums. `log`, if given,
// records each packet (benchmarks; one thread only).
void shade_batch(PixelBatch& batch, std::span<const Vpl> vpls, const VplShading& shading, const Accel& accel,
                 RayCounts& rays, RayLog* log = nullptr);

}  // namespace igi
