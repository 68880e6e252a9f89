#include "methods/shadow_batch.h"

#include <algorithm>
#include <cfloat>

namespace igi {

void PixelBatch::clear() {
  for (auto* v : {&ox, &oy, &oz, &px, &py, &pz, &nx, &ny, &nz, &gx, &gy, &gz}) v->clear();
  index.clear();
  sample.clear();
  fast.clear();
  chunk_fast.clear();
  count = 0;
}

void PixelBatch::add(uint32_t id, const GSample& g) {
  const SurfacePoint& sp = g.surface;
  const glm::vec3 n = sp.shading_normal_facing(g.wo), ng = sp.geometric_normal_facing(g.wo);
  const glm::vec3 o = offset_origin(sp, ng);
  index.push_back(id);
  sample.push_back(&g);
  ox.push_back(o.x); oy.push_back(o.y); oz.push_back(o.z);
  px.push_back(sp.position.x); py.push_back(sp.position.y); pz.push_back(sp.position.z);
  nx.push_back(n.x); ny.push_back(n.y); nz.push_back(n.z);
  gx.push_back(ng.x); gy.push_back(ng.y); gz.push_back(ng.z);
  // The fast lanes test light against both normals; a viewer below the
  // shading normal (a leaning normal at a silhouette) sees nothing reflected
  // there (bsdf_eval): the general lanes say so.
  fast.push_back(sp.material->type == MaterialType::Diffuse && glm::dot(g.wo, n) > 0.0f);
  ++count;
}

void PixelBatch::pad() {
  while (index.size() % 16 != 0) {
    index.push_back(0);
    sample.push_back(nullptr);
    for (auto* v : {&ox, &oy, &oz, &px, &py, &pz, &nx, &ny, &nz, &gx, &gy, &gz}) v->push_back(0.0f);
    fast.push_back(1);  // inert: zero normals give no contribution
  }
  chunk_fast.clear();
  for (size_t c = 0; c < index.size(); c += 16)
    chunk_fast.push_back(std::all_of(fast.begin() + c, fast.begin() + c + 16, [](uint8_t f) { return f != 0; }));
  sum_r.assign(index.size(), 0.0f);
  sum_g.assign(index.size(), 0.0f);
  sum_b.assign(index.size(), 0.0f);
}

namespace {

// Diffuse-to-diffuse lanes: G = min(cos_x cos_y / r^2, bound), visible side only.
// Written as independent lanes over restrict pointers so it vectorises. Each
// operation is VplShading::contribution's, in its order (a division where it
// divides), so a lane gives the scalar rule's value bit for bit
// (ctest -R VplShading.FastLanes).
void fill_fast_lanes(const PixelBatch& b, size_t first, const Vpl& vpl, float bound, float* __restrict g_out,
                     RTCRay16& rays) {
  const float vx = vpl.position.x, vy = vpl.position.y, vz = vpl.position.z;
  const glm::vec3 target = shadow_target(vpl);
  const float tx = target.x, ty = target.y, tz = target.z;
  const float mx = vpl.normal.x, my = vpl.normal.y, mz = vpl.normal.z;
  const float* __restrict px = b.px.data() + first;
  const float* __restrict py = b.py.data() + first;
  const float* __restrict pz = b.pz.data() + first;
  const float* __restrict nx = b.nx.data() + first;
  const float* __restrict ny = b.ny.data() + first;
  const float* __restrict nz = b.nz.data() + first;
  const float* __restrict gx = b.gx.data() + first;
  const float* __restrict gy = b.gy.data() + first;
  const float* __restrict gz = b.gz.data() + first;
  const float* __restrict ox = b.ox.data() + first;
  const float* __restrict oy = b.oy.data() + first;
  const float* __restrict oz = b.oz.data() + first;
  // Results go to local arrays first: GCC 12 does not take the restrict
  // pointers into the packet as proof that nothing aliases, and without it
  // (more than 10 run-time alias checks) the loop stayed scalar; profiled at
  // 10 % of a Cornell box frame.
  alignas(64) float dir_x[16], dir_y[16], dir_z[16], tfar[16], g_lane[16];
  for (int k = 0; k < 16; ++k) {
    const float dx = vx - px[k], dy = vy - py[k], dz = vz - pz[k];
    const float dist2 = dx * dx + dy * dy + dz * dz;
    const float dist = std::sqrt(dist2);
    const float wx = dx / dist, wy = dy / dist, wz = dz / dist;
    const float cos_x = wx * nx[k] + wy * ny[k] + wz * nz[k];
    const float side = wx * gx[k] + wy * gy[k] + wz * gz[k];
    const float cos_y = -(wx * mx + wy * my + wz * mz);
    const float g = std::min(cos_x * cos_y / dist2, bound);
    // Bitwise &, not &&: no branches, so the loop vectorises. A VPL on the
    // point itself (dist2 0, unclamped) gives an infinite or NaN g: no light.
    const bool visible = (cos_x > 0.0f) & (side > 0.0f) & (cos_y > 0.0f) & (g <= FLT_MAX);
    g_lane[k] = visible ? g : 0.0f;
    // The ray aims from the nudged origin at the nudged VPL (shadow_target, scene/surface.h shadow_ray).
    const float rx = tx - ox[k], ry = ty - oy[k], rz = tz - oz[k];
    const float length = std::sqrt(rx * rx + ry * ry + rz * rz);
    dir_x[k] = rx / length; dir_y[k] = ry / length; dir_z[k] = rz / length;
    tfar[k] = length * (1.0f - kShadowEpsilon);
  }
  std::copy_n(g_lane, 16, g_out);
  std::copy_n(dir_x, 16, rays.dir_x);
  std::copy_n(dir_y, 16, rays.dir_y);
  std::copy_n(dir_z, 16, rays.dir_z);
  std::copy_n(tfar, 16, rays.tfar);
  std::copy_n(b.ox.data() + first, 16, rays.org_x);
  std::copy_n(b.oy.data() + first, 16, rays.org_y);
  std::copy_n(b.oz.data() + first, 16, rays.org_z);
  std::fill_n(rays.tnear, 16, 0.0f);
  std::fill_n(rays.mask, 16, kOpaqueRayMask);
  std::fill_n(rays.flags, 16, 0u);
  std::fill_n(rays.time, 16, 0.0f);
}

bool vpl_is_diffuse_emitter(const Vpl& vpl, const Scene& scene) {
  return vpl.kind == VplKind::Area ||
         (vpl.kind == VplKind::Surface && scene.materials[vpl.material].type == MaterialType::Diffuse);
}

}  // namespace

void fill_shadow_packet(const PixelBatch& batch, size_t first, const Vpl& vpl, const VplShading& shading,
                        ShadowPacket& packet) {
  const bool fast_vpl = vpl_is_diffuse_emitter(vpl, shading.scene);
  alignas(64) float g[16];
  if (fast_vpl) {
    fill_fast_lanes(batch, first, vpl, shading.clamp_bound, g, packet.rays);
    // The receiver's BSDF (1/pi: albedo 1) times what leaves the VPL per unit G,
    // as the scalar rule multiplies them: a Lambertian VPL's own BSDF (any
    // direction: it has none) times its flux.
    const glm::vec3 emitted = vpl.kind == VplKind::Area ? vpl.flux : shading.vpl_bsdf(vpl, vpl.normal) * vpl.flux;
    const glm::vec3 i = glm::vec3(kInvPi) * emitted;
    for (int k = 0; k < 16; ++k) {
      packet.r[k] = i.x * g[k];
      packet.g[k] = i.y * g[k];
      packet.b[k] = i.z * g[k];
      packet.valid[k] = g[k] > 0.0f ? -1 : 0;  // padding lanes have g = 0
    }
    if (batch.chunk_fast[first / 16]) return;
  }
  // General lanes: glossy receivers, or a VPL that is not a diffuse emitter.
  for (int k = 0; k < 16; ++k) {
    const size_t i = first + k;
    if (i >= batch.count || (fast_vpl && batch.fast[i])) continue;
    ShadowQuery q{};
    glm::vec3 c = shading.contribution(*batch.sample[i], vpl, q);
    packet.r[k] = c.x; packet.g[k] = c.y; packet.b[k] = c.z;
    packet.valid[k] = c.x > 0.0f || c.y > 0.0f || c.z > 0.0f ? -1 : 0;
    set_rtc_lane(packet.rays, k, Ray{q.origin, q.direction, 0.0f, q.tfar, kOpaqueRayMask});
  }
  if (!fast_vpl)
    for (size_t k = batch.count > first ? batch.count - first : 0; k < 16; ++k) packet.valid[k] = 0;
}

int accumulate_shadow_packet(const ShadowPacket& packet, size_t first, PixelBatch& batch) {
  float* __restrict r = batch.sum_r.data() + first;
  float* __restrict g = batch.sum_g.data() + first;
  float* __restrict b = batch.sum_b.data() + first;
  int traced = 0;
  for (int k = 0; k < 16; ++k) {
    // Embree sets tfar to -inf for occluded lanes. A select, not a product
    // with 0: an inactive lane's stale value must not reach the sum.
    const bool lit = (packet.valid[k] != 0) & (packet.rays.tfar[k] >= 0.0f);
    r[k] += lit ? packet.r[k] : 0.0f;
    g[k] += lit ? packet.g[k] : 0.0f;
    b[k] += lit ? packet.b[k] : 0.0f;
    traced += packet.valid[k] != 0;
  }
  return traced;
}

// The packet as one rtcOccluded16 (in small scenes: below). Embree's packet
// traversal tests a lane against every triangle of every leaf that any lane
// of the packet reaches, where a single ray tests only the leaves whose boxes
// it passes, so a lane whose answer hangs on a rounding could be answered
// differently beside other rays; and which points share a packet depends on
// how the frame is cut into tiles. From 2026-12-04 to 2026-12-07 every lane was therefore traced
// alone (rtcOccluded1): at 64x48, 4 passes, 8 paths a set, 4 sub-samples,
// 16-pixel tiles had differed from the whole frame in 6 of 12 renders (a few
// pixels each, by about 1e-5). Every lane that answered differently (56 in
// that test, traced both ways) was one ray: from a point of the Cornell box's
// ceiling to a VPL on the ceiling, running along it and ending 1e-4 of its
// length short of the VPL, within a rounding of the ceiling's plane. Such a
// ray now ends off the VPL's surface as it starts off its own
// (shadow_target, core/vpl_contribution.h), and no lane of the test suite
// answers differently as a packet and alone (counted over the whole suite,
// every render traced both ways; tests/bench/RESULTS.md, "Shadow packets").
//
// Packets pay in small scenes only, where a packet's rays stay together
// through a shallow tree: one thread, 640x480, the defaults, medians of 5
// alternating runs (2026-12-07), frame time one at a time over packets:
// Cornell box (32 triangles) 1.39x, glossy (32) 1.27x, rooms (188) 1.45x,
// corridor (282) 1.20x, rooms-10 (1,292) 1.46x, courtyard (2,230) 1.04x,
// cornell-blob (316,980) 0.84x, large (1,058,844) 0.92x. Above
// kPacketTriangles each lane goes alone; it answers as it would in the packet
// (the same test), so the choice never shows in an image, and every peer
// makes the same one.
constexpr size_t kPacketTriangles = 65536;

void trace_shadow_lanes(const Accel& accel, RTCIntersectContext& context, ShadowPacket& packet) {
  if (accel.scene().triangles.size() < kPacketTriangles) {
    rtcOccluded16(packet.valid, accel.handle(), &context, &packet.rays);
    return;
  }
  RTCRay ray;
  for (int k = 0; k < 16; ++k) {
    if (!packet.valid[k]) continue;
    ray.org_x = packet.rays.org_x[k]; ray.org_y = packet.rays.org_y[k]; ray.org_z = packet.rays.org_z[k];
    ray.dir_x = packet.rays.dir_x[k]; ray.dir_y = packet.rays.dir_y[k]; ray.dir_z = packet.rays.dir_z[k];
    ray.tnear = packet.rays.tnear[k];
    ray.tfar = packet.rays.tfar[k];
    ray.mask = packet.rays.mask[k];
    ray.time = 0.0f;
    ray.id = 0;
    ray.flags = 0;
    rtcOccluded1(accel.handle(), &context, &ray);
    packet.rays.tfar[k] = ray.tfar;
  }
}

void shade_batch(PixelBatch& batch, std::span<const Vpl> vpls, const VplShading& shading, const Accel& accel,
                 RayCounts& rays, RayLog* log) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  thread_local ShadowPacket packet;
  for (const Vpl& vpl : vpls)
    for (size_t first = 0; first < batch.count; first += 16) {
      fill_shadow_packet(batch, first, vpl, shading, packet);
      if (log) {
        log->shadow.emplace_back();
        std::copy_n(packet.valid, 16, log->shadow.back().valid);
        log->shadow.back().rays = packet.rays;
      }
      trace_shadow_lanes(accel, context, packet);
      rays.shadow += accumulate_shadow_packet(packet, first, batch);
    }
}

}  // namespace igi
