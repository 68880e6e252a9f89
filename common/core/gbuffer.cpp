#include "core/gbuffer.h"

#include <algorithm>
#include <stdexcept>

#include "core/camera_front_end.h"
#include "core/pixel_surface.h"
#include "material/bsdf.h"
#include "sampling/hash.h"

namespace igi {

Region tile_region(const TileJob& job, int image_width, int image_height) {
  Region r;
  r.x0 = std::max(0, job.x - job.border);
  r.y0 = std::max(0, job.y - job.border);
  r.width = std::min(image_width, job.x + job.w + job.border) - r.x0;
  r.height = std::min(image_height, job.y + job.h + job.border) - r.y0;
  return r;
}

namespace {

// One path through mirrors and glass, from a hit not yet shaded.
struct Branch {
  Ray ray;
  Hit hit;
  bool traced = true;   // hit is known (else the ray is traced first)
  glm::vec3 throughput{1.0f};
  float travelled = 0.0f;
  int depth = 0;        // specular surfaces met so far
  int index = 0;        // which output it fills
};

// Glass's random choice on branch b: branch 0 with follow_specular_chain's numbers.
float lobe_number(uint32_t seed, int branch, int depth) {
  const uint32_t branch_seed = branch == 0 ? seed : hash(seed, 0x62726e63u /* "brnc" */, uint32_t(branch));
  return float(hash(branch_seed, uint32_t(depth)) >> 8) * 0x1p-24f;
}

// The chain ends at a non-specular surface: g holds it.
void end_at_surface(GSample& g, const SurfacePoint& sp, glm::vec3 wo, float depth) {
  g.surface = sp;
  g.wo = wo;
  g.depth = depth;
  g.has_surface = true;
}

// Where branch b leaves the specular surface sp, its throughput updated; a
// glass surface may split, its reflection pushed on `pending` as a branch of
// its own (while fewer than `branches` are used). Nothing: the path ends.
std::optional<glm::vec3> specular_direction(const SurfacePoint& sp, const Branch& b, glm::vec3& throughput,
                                            uint32_t seed, int branches, Branch* pending, int& pending_count,
                                            int& used) {
  const glm::vec3 wo = -b.ray.direction;
  if (sp.material->type == MaterialType::Glass && used < branches && dielectric_branches(sp, wo).reflectance < 1.0f) {
    const DielectricBranches split = dielectric_branches(sp, wo);
    pending[pending_count++] = Branch{Ray{offset_origin(sp, split.reflected), split.reflected, 0.0f, 1e30f, b.ray.mask},
                                      Hit{}, false, throughput * split.reflectance, b.travelled, b.depth + 1, used++};
    throughput *= split.transmittance;
    return split.refracted;
  }
  auto bs = bsdf_sample(sp, wo, glm::vec2(0.5f), lobe_number(seed, b.index, b.depth));
  if (!bs) return std::nullopt;
  throughput *= bs->weight;
  return bs->wi;
}

}  // namespace

int follow_specular_tree(const Accel& accel, Ray ray, Hit hit, uint32_t seed, int specular_depth, int branches,
                         GSample* const* out, RayCounts& rays) {
  const Scene& scene = accel.scene();
  {
    // Most camera rays end on a surface that is not specular: no branches,
    // no stack (building it cost more than the rest of this path).
    const SurfacePoint sp = surface_at(scene, hit, ray.direction);
    if (!sp.material->is_specular()) {
      GSample& g = *out[0];
      g = GSample{};
      g.emitted += g.throughput * sp.emitted();
      end_at_surface(g, sp, -ray.direction, 0.0f + hit.t);
      return 1;
    }
  }
  Branch pending[kMaxGlassBranches];
  int pending_count = 0, used = 1;
  pending[pending_count++] = Branch{ray, hit};
  while (pending_count > 0) {
    Branch b = pending[--pending_count];
    GSample& g = *out[b.index];
    g = GSample{};
    g.throughput = b.throughput;
    if (!b.traced) {
      ++rays.secondary;
      if (!accel.intersect(b.ray, b.hit)) {
        g.emitted += g.throughput * scene.sky(b.ray.direction);  // out of the scene: the sky
        continue;
      }
    }
    for (;; ++b.depth) {
      const SurfacePoint sp = surface_at(scene, b.hit, b.ray.direction);
      b.travelled += b.hit.t;
      g.emitted += g.throughput * sp.emitted();
      if (!sp.material->is_specular()) {
        end_at_surface(g, sp, -b.ray.direction, b.travelled);
        break;
      }
      if (b.depth + 1 >= specular_depth) break;
      const std::optional<glm::vec3> wi = specular_direction(sp, b, g.throughput, seed, branches, pending, pending_count, used);
      if (!wi) break;
      b.ray = Ray{offset_origin(sp, *wi), *wi, 0.0f, 1e30f, b.ray.mask};
      ++rays.secondary;
      if (!accel.intersect(b.ray, b.hit)) {
        g.emitted += g.throughput * scene.sky(b.ray.direction);
        break;
      }
    }
  }
  return used;
}

void follow_specular_chain(const Accel& accel, Ray ray, Hit hit, uint32_t seed, int specular_depth, GSample& g,
                           RayCounts& rays) {
  GSample* out[1] = {&g};
  follow_specular_tree(accel, ray, hit, seed, specular_depth, 1, out, rays);
}

namespace {

// One 4x4 block of one layer as a 16-wide packet. Blocks lie on the image's
// own grid (bx, by multiples of 4) and trace every lane inside the image,
// those outside the region too (then dropped): a packet holds the same rays
// whichever tile traces it, and Embree's answer for a ray can depend on the
// other rays of its packet (methods/shadow_batch.cpp).
void trace_block(const Accel& accel, const CameraFrontEnd& camera, int image_width, int image_height, int bx, int by,
                 int k, int glass_branches, int specular_depth, GBuffer& out, RayCounts& rays, RayLog* log,
                 std::span<PixelSurface> surfaces) {
  const Region& region = out.region;
  const int step = region.step;
  const int lattice_width = lattice_extent(image_width, step), lattice_height = lattice_extent(image_height, step);
  auto image_x = [&](int x) { return lattice_to_image(x, step, image_width); };
  auto image_y = [&](int y) { return lattice_to_image(y, step, image_height); };
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  alignas(64) int valid[16];
  alignas(64) RTCRayHit16 packet;
  for (int i = 0; i < 16; ++i) {
    const int x = bx + (i & 3), y = by + (i >> 2);  // image (lattice) coordinates
    valid[i] = x < lattice_width && y < lattice_height ? -1 : 0;
    // A lane outside the image traces (masked off) where the lattice would go on.
    Ray ray = valid[i] ? camera.pixel_ray(image_x(x), image_y(y), k)
                       : camera.pixel_ray(x * step + step / 2, y * step + step / 2, k);
    ray.tfar = INFINITY;
    set_rtc_lane(packet.ray, i, ray);
    packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    rays.primary += valid[i] ? 1 : 0;
  }
  if (log) {
    log->primary.emplace_back();
    std::copy_n(valid, 16, log->primary.back().valid);
    log->primary.back().rays = packet;
  }
  rtcIntersect16(valid, accel.handle(), &context, &packet);
  GSample more[kMaxGlassBranches];  // reset by follow_specular_tree as it uses them
  for (int i = 0; i < 16; ++i) {
    // Region coordinates from here on.
    const int x = bx + (i & 3) - region.x0, y = by + (i >> 2) - region.y0;
    if (!valid[i] || x < 0 || y < 0 || x >= region.width || y >= region.height) continue;
    const bool surface = k == 0 && !surfaces.empty();
    if (packet.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
      const glm::vec3 direction{packet.ray.dir_x[i], packet.ray.dir_y[i], packet.ray.dir_z[i]};
      GSample& g = out.at(k, size_t(y) * region.width + x);
      g = GSample{};
      g.emitted = accel.scene().sky(direction);  // black without one
      if (surface) surfaces[size_t(y) * region.width + x] = PixelSurface{};
      continue;
    }
    Ray ray{{packet.ray.org_x[i], packet.ray.org_y[i], packet.ray.org_z[i]},
            {packet.ray.dir_x[i], packet.ray.dir_y[i], packet.ray.dir_z[i]}, 0.0f, 1e30f, kCameraRayMask};
    Hit hit{packet.ray.tfar[i], accel.triangle_index(packet.hit.instID[0][i], packet.hit.geomID[i], packet.hit.primID[i]),
            {packet.hit.u[i], packet.hit.v[i]}};
    if (surface) surfaces[size_t(y) * region.width + x] = pixel_surface(accel, hit, ray.direction);
    const uint32_t seed = camera.chain_seed(image_x(region.x0 + x), image_y(region.y0 + y), k);
    // Branch 0 into its layer; further branches on the stack, then into
    // layers of their own, which the region gets when a pixel first needs one.
    const size_t pixel = size_t(y) * region.width + x;
    GSample* branches[kMaxGlassBranches] = {&out.at(k, pixel)};
    for (int b = 1; b < glass_branches; ++b) branches[b] = &more[b];
    const int used = follow_specular_tree(accel, ray, hit, seed, specular_depth, glass_branches, branches, rays);
    for (int b = 1; b < used; ++b) {
      for (; out.branches <= b; ++out.branches)
        std::fill_n(out.layers.begin() + ptrdiff_t(size_t(out.branches) * out.samples * region.pixels()),
                    size_t(out.samples) * region.pixels(), GSample{});
      out.at(b * out.samples + k, pixel) = more[b];
    }
  }
}

}  // namespace

void build_gbuffer(const Accel& accel, const FrameSetup& frame, const Region& region, int samples,
                   int glass_branches, int specular_depth, GBuffer& out, RayCounts& rays, RayLog* log,
                   std::span<PixelSurface> surfaces) {
  if (!surfaces.empty() && (region.step != 1 || surfaces.size() != region.pixels()))
    throw std::invalid_argument("build_gbuffer: surfaces are one a pixel of a region without a step");
  out.region = region;  // with its step
  out.samples = samples;
  out.branches = 1;
  // Room for every branch (kept between tiles). Branch 0's layers are not
  // reset here: trace_block writes every one of their samples.
  const size_t layer_pixels = size_t(samples) * region.pixels();
  if (out.layers.size() < size_t(glass_branches) * layer_pixels) out.layers.resize(size_t(glass_branches) * layer_pixels);
  const CameraFrontEnd camera(frame, samples);
  const int x_end = region.x0 + region.width, y_end = region.y0 + region.height;
  for (int k = 0; k < samples; ++k)
    for (int by = region.y0 / 4 * 4; by < y_end; by += 4)
      for (int bx = region.x0 / 4 * 4; bx < x_end; bx += 4)
        trace_block(accel, camera, frame.width, frame.height, bx, by, k, glass_branches, specular_depth, out, rays, log,
                    surfaces);
}

}  // namespace igi
