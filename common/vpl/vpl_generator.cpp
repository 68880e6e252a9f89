#include "vpl/vpl_generator.h"

#include <cmath>

#include "material/bsdf.h"
#include "sampling/content_hash.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "vpl/light_path.h"

namespace igi {
namespace {

void trace_light_path(const SceneContext& ctx, const RenderSettings& settings, uint32_t path,
                      uint32_t seed, float inv_paths, std::vector<Vpl>& out, const LightPathOptions& options) {
  SampleStream start_stream(path, seed, 0);
  const size_t first = out.size();
  const LightPathStart start = start_light_path(ctx.lights, ctx.scene, start_stream, options.selection, options.guide);
  // The vertex the path leaves from: the Area VPL it leaves on the light, or the punctual light.
  LightVertex previous{LightVertex::From::Punctual, start.light};
  // An area light leaves a VPL on itself, the environment a directional one.
  // Point, spot and directional lights leave none: the methods evaluate their light exactly (core/vpl.h); their
  // paths still carry it on.
  if (start.on_area_light || start.from_environment) {
    // The environment's path leaves a Directional VPL: the sky's light from
    // the path's direction, at infinity (a constant sky is no punctual light
    // to evaluate exactly, so its direct light comes from these).
    Vpl v;
    v.kind = start.on_area_light ? VplKind::Area : VplKind::Directional;
    v.position = start.position;
    v.normal = start.on_area_light ? start.normal : start.ray.direction;
    v.flux = (start.on_area_light ? start.power : start.irradiance) * inv_paths;
    out.push_back(v);
    if (options.vertices) options.vertices->push_back(LightVertex{});
    previous = {LightVertex::From::Vpl, uint32_t(first)};
  }
  walk_light_path(ctx.accel, ctx.scene, start, settings.light_depth, path, seed, BounceDraws::TwoSingles,
                  [&](const LightPathVertex& v) {
                    // Mirrors and glass get no VPL; the path carries their light on. Nor, with caustics
                    // on, do sharp GGX surfaces: their light reaches diffuse surfaces as caustic photons
                    // (material/bsdf.h: focuses_light). Without caustics, VPLs on them radiate through a
                    // widened lobe (VplShading::vpl_bsdf).
                    const Material& m = *v.sp.material;
                    if (settings.caustics ? focuses_light(m, settings.glossy_threshold) : m.is_specular()) {
                      previous = {LightVertex::From::Specular, 0};
                      return true;
                    }
                    // The VPL reflects towards the side the light arrived from.
                    out.push_back(Vpl{v.sp.position, v.sp.shading_normal_facing(v.wo), v.flux * inv_paths, v.wo,
                                      v.sp.albedo, ctx.scene.triangle_material[v.hit.triangle], 0,
                                      VplKind::Surface});
                    if (options.vertices) options.vertices->push_back({previous.from, previous.index, v.depth});
                    previous = {LightVertex::From::Vpl, uint32_t(out.size() - 1)};
                    return true;
                  });
}

}  // namespace

uint64_t hash_vpls(const std::vector<Vpl>& vpls) {
  ContentHasher h;
  for (const Vpl& v : vpls) {
    h.add(v.position);
    h.add(v.normal);
    h.add(v.flux);
    h.add(v.incident);
    h.add(v.kind);
  }
  return h.value();
}

VplSets generate_vpls(const SceneContext& context, const RenderSettings& settings, uint32_t seed,
                      const LightPathOptions& options) {
  VplSets sets;
  sets.interleave = settings.interleave;
  sets.groups = settings.aa_samples;
  const int set_count = settings.interleave * settings.interleave;
  const uint32_t paths = uint32_t(settings.paths_per_set);
  const uint32_t groups = uint32_t(settings.aa_samples);
  const float inv_paths = 1.0f / float(paths);
  const uint32_t path_seed = hash(seed, 0x76706c73u);  // "vpls": independent of pixel seeds
  sets.set_begin.push_back(0);
  for (int k = 0; k < set_count; ++k) {
    for (uint32_t g = 0; g < groups; ++g) {
      sets.group_begin.push_back(uint32_t(sets.vpls.size()));
      // Paths i with floor(i G / M) = g.
      for (uint32_t i = (g * paths + groups - 1) / groups; i < ((g + 1) * paths + groups - 1) / groups; ++i)
        trace_light_path(context, settings, uint32_t(k) * paths + i, path_seed, inv_paths, sets.vpls, options);
    }
    sets.set_begin.push_back(uint32_t(sets.vpls.size()));
  }
  sets.group_begin.push_back(uint32_t(sets.vpls.size()));
  sets.hash = hash_vpls(sets.vpls);
  return sets;
}

}  // namespace igi
