#include "photons/photon_paths.h"

#include <algorithm>

#include "core/parallel.h"
#include "material/bsdf.h"
#include "photons/caustic_settings.h"
#include "sampling/hash.h"
#include "sampling/warp.h"
#include "scene/surface.h"
#include "vpl/light_path.h"

namespace igi {
namespace {

constexpr uint32_t kChunk = 1024;  // paths per unit of work: fixed, so the order is too

void trace_path(const SceneContext& ctx, const RenderSettings& settings, uint32_t path, uint32_t seed,
                float inv_paths, std::vector<Photon>& out, RayCounts& rays) {
  SampleStream start_stream(path, seed, 0);
  const LightPathStart start = start_light_path(ctx.lights, ctx.scene, start_stream);
  bool bounced = false;
  int stored = 0;
  rays.secondary += uint64_t(walk_light_path(
      ctx.accel, ctx.scene, start, settings.light_depth, path, seed, BounceDraws::OnePair,
      [&](const LightPathVertex& v) {
        // Light focused on its way here: through a mirror, glass or a GGX lobe sharper than the threshold.
        const bool focused_here = v.depth > 0 && focused(v.arrived_by, settings.glossy_threshold);
        if (focused_here && receives_vpls(v.sp, settings.glossy_threshold)) {
          out.push_back(Photon{v.sp.position, v.wo, v.sp.geometric_normal_facing(v.wo), v.flux * inv_paths,
                               bounced ? 1u : 0u});
          if (++stored == photons::kMaxPhotonsPerPath) return false;
        }
        if (v.depth > 0 && !focused_here) bounced = true;  // a diffuse or rough bounce before this one
        return true;
      }));
}

}  // namespace

std::vector<Photon> trace_photon_paths(const SceneContext& context, const RenderSettings& settings, uint32_t seed,
                                       uint32_t paths, int threads, RayCounts& rays) {
  static_assert(sizeof(Photon) == 52, "caustic_settings.h counts 52 bytes a photon");
  const uint32_t path_seed = hash(seed, 0x70686f74u);  // "phot": independent of the VPL paths
  const float inv_paths = 1.0f / float(paths);
  const uint32_t chunks = (paths + kChunk - 1) / kChunk;
  std::vector<std::vector<Photon>> per_chunk(chunks);
  std::vector<RayCounts> per_chunk_rays(chunks);
  // Each chunk a task of the shared pool (core/parallel.h), with
  // flush-to-zero set whatever the caller's mode: the photons cannot depend
  // on who calls.
  parallel_tasks(
      int(chunks),
      [&](int c) {
        for (uint32_t i = uint32_t(c) * kChunk; i < std::min(paths, (uint32_t(c) + 1) * kChunk); ++i)
          trace_path(context, settings, i, path_seed, inv_paths, per_chunk[size_t(c)], per_chunk_rays[size_t(c)]);
      },
      threads);
  for (const RayCounts& c : per_chunk_rays) rays += c;
  size_t total = 0;
  for (const auto& c : per_chunk) total += c.size();
  std::vector<Photon> photons;
  photons.reserve(total);
  for (const auto& c : per_chunk) photons.insert(photons.end(), c.begin(), c.end());
  return photons;
}

}  // namespace igi
