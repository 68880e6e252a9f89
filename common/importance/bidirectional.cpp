#include "importance/bidirectional.h"

#include <algorithm>
#include <cmath>

#include "core/clamp.h"
#include "core/direct_lights.h"
#include "core/parallel.h"
#include "core/vpl_contribution.h"
#include "importance/camera_points.h"
#include "importance/resample.h"
#include "material/bsdf.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/surface.h"

namespace igi::importance {

float continuation_density(const Scene& scene, const Vpl& z, const LightVertex& from, glm::vec3 y, glm::vec3 n_y,
                           int max_depth) {
  const glm::vec3 d = y - z.position;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return 0.0f;
  const glm::vec3 w = d / std::sqrt(dist2);
  const float cos_y = std::abs(glm::dot(n_y, w));
  // From an emitter the path leaves cosine-distributed, always.
  if (z.kind == VplKind::Area) return std::max(0.0f, glm::dot(z.normal, w)) * kInvPi * cos_y / dist2;
  if (z.kind != VplKind::Surface || from.depth + 1 >= max_depth) return 0.0f;
  SurfacePoint sp;
  sp.position = z.position;
  sp.geometric_normal = sp.shading_normal = z.normal;
  sp.material = &scene.materials[z.material];
  sp.albedo = z.albedo;
  const float pdf = bsdf_pdf(sp, z.incident, w);
  if (!(pdf > 0.0f)) return 0.0f;
  // The light path's Russian roulette keeps it with q = min(1, max f cos / pdf).
  const glm::vec3 weight = bsdf_eval(sp, z.incident, w) * (std::abs(glm::dot(w, z.normal)) / pdf);
  return pdf * std::min(1.0f, max_component(weight)) * cos_y / dist2;
}

float punctual_density(const Scene& scene, const Vpl& light, float scene_radius, glm::vec3 y, glm::vec3 n_y) {
  if (light.kind == VplKind::Directional)
    return std::abs(glm::dot(n_y, light.normal)) / (kPi * scene_radius * scene_radius);
  const glm::vec3 d = y - light.position;
  const float dist2 = glm::dot(d, d);
  if (!(dist2 > 0.0f)) return 0.0f;
  const glm::vec3 w = d / std::sqrt(dist2);
  const float cos_y = std::abs(glm::dot(n_y, w));
  if (light.kind == VplKind::Point) return cos_y / (4.0f * kPi * dist2);
  const PunctualLight& pl = scene.lights[light.light];
  const float cos_max = std::cos(pl.outer_cone);
  if (glm::dot(glm::normalize(pl.direction), w) < cos_max) return 0.0f;
  return cos_y / (2.0f * kPi * (1.0f - cos_max) * dist2);
}

namespace {

constexpr uint32_t kCameraTag = 0x62636d70u;    // "bcmp": camera paths
constexpr uint32_t kResampleTag = 0x7273706cu;  // "rspl": resampling offsets

struct Candidate {
  Vpl vpl;                   // flux: as traced (standard) or gathered (reverse), before the MIS weight
  LightVertex from;          // standard: how its light path reached it
  bool reverse = false;
  int own = -1;              // reverse: the camera path that found it
  GSample receiver;          // reverse: the VPL's point as a shading point facing its camera path
  float density = 0.0f;      // p_R: how densely the set's camera paths reach it (diffuse VPLs only)
  glm::vec3 response{0.0f};  // image response to unit flux at the VPL, over the set's camera points
};

struct CameraPoint {
  GSample x;
  glm::vec3 facing{0.0f};  // x's shading normal on the viewer's side
  bool receives = false;   // shaded by VPLs (not a gathered glossy surface)
};

// Builds one frame's sets; every method is a step of generate_bidirectional().
class Builder {
 public:
  Builder(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
          const LightPathOptions& light_paths, RayCounts& rays)
      : context_(context), settings_(settings), frame_(frame), selection_(light_paths.selection), guide_(light_paths.guide), rays_(rays),
        shading_{context.scene, clamp_bound(settings.clamp, context.accel.mean_chord(), frame.sample_begin),
                 settings.glossy_threshold},
        gathering_{context.scene, INFINITY, settings.glossy_threshold},
        exact_(exact_lights(context.scene)), camera_(frame),
        camera_seed_(hash(frame.seed, kCameraTag)),
        camera_paths_(settings.bidir_camera_paths > 0 ? settings.bidir_camera_paths : settings.paths_per_set),
        max_depth_(depth_limit(settings.light_depth)) {
    // Exact light i is LightSet entry exact_entry_[i].
    const auto& lights = context.lights.lights();
    for (uint32_t i = 0; i < exact_.size(); ++i)
      for (uint32_t l = 0; l < lights.size(); ++l)
        if (lights[l].kind != LightKind::Area && lights[l].index == exact_[i].light) exact_entry_.push_back(l);
  }

  VplSets build() {
    RenderSettings paths = settings_;
    paths.aa_samples = 1;  // one group per set: the candidates
    LightPathOptions options;
    options.selection = selection_;
    options.guide = guide_;
    options.vertices = &vertices_;
    standard_ = generate_vpls(context_, paths, frame_.seed, options);
    const int sets = standard_.set_count();
    points_.resize(size_t(sets));
    std::vector<RayCounts> point_rays(static_cast<size_t>(sets));
    parallel_tasks(sets, [&](int k) { points_[size_t(k)] = camera_points(k, point_rays[size_t(k)]); });
    for (const RayCounts& r : point_rays) rays_ += r;
    // Sets are independent: built on threads, joined in set order.
    std::vector<SetResult> results(static_cast<size_t>(sets));
    parallel_tasks(standard_.set_count(), [&](int k) { results[size_t(k)] = build_set(k); });
    VplSets out;
    out.interleave = settings_.interleave;
    out.groups = settings_.aa_samples;
    out.set_begin.push_back(0);
    for (const SetResult& r : results) {
      uint32_t group = uint32_t(out.vpls.size());
      for (uint32_t size : r.group_sizes) {
        out.group_begin.push_back(group);
        group += size;
      }
      out.vpls.insert(out.vpls.end(), r.vpls.begin(), r.vpls.end());
      out.set_begin.push_back(uint32_t(out.vpls.size()));
      rays_ += r.rays;
    }
    out.group_begin.push_back(uint32_t(out.vpls.size()));
    out.hash = hash_vpls(out.vpls);
    return out;
  }

 private:
  float selection_probability(uint32_t light) const {
    return selection_ ? selection_->probability(light) : context_.lights.selection_probability(light);
  }

  bool occluded(const ShadowQuery& q, RayCounts& rays) const {
    ++rays.shadow;
    return context_.accel.occluded(Ray{q.origin, q.direction, 0.0f, q.tfar});
  }

  struct SetResult {
    std::vector<Vpl> vpls;              // the set's groups, one after the other
    std::vector<uint32_t> group_sizes;  // G entries
    RayCounts rays;
  };

  SetResult build_set(int k) const {
    SetResult r;
    const std::vector<CameraPoint>& points = points_[size_t(k)];
    std::vector<Candidate> candidates = standard_candidates(k);
    const size_t standard_count = candidates.size();
    add_reverse_candidates(k, points, candidates, r.rays);
    for (Candidate& c : candidates) measure(c, points, r.rays);
    for (size_t c = standard_count; c < candidates.size(); ++c)
      gather(candidates[c], std::span<const Candidate>(candidates.data(), standard_count), r.rays);
    for (size_t c = 0; c < standard_count; ++c) weigh_standard(candidates[c], candidates, standard_.set_begin[size_t(k)]);
    resample(k, candidates, r);
    return r;
  }

  // Camera path i of set k: its first non-specular point.
  std::vector<CameraPoint> camera_points(int k, RayCounts& rays) const {
    std::vector<CameraPoint> points(static_cast<size_t>(camera_paths_));
    for (int i = 0; i < camera_paths_; ++i) {
      CameraPoint& p = points[size_t(i)];
      p.x = trace_camera_point(context_.accel, camera_, uint32_t(k * camera_paths_ + i), camera_seed_,
                               depth_limit(settings_.specular_depth), rays);
      if (!p.x.valid()) continue;
      const SurfacePoint& s = p.x.surface;
      p.facing = glm::dot(p.x.wo, s.geometric_normal) >= 0.0f ? s.shading_normal : -s.shading_normal;
      p.receives = receives_vpls(*s.material, settings_.glossy_threshold);
    }
    return points;
  }

  std::vector<Candidate> standard_candidates(int k) const {
    std::vector<Candidate> out;
    for (uint32_t v = standard_.set_begin[size_t(k)]; v < standard_.set_begin[size_t(k) + 1]; ++v) {
      Candidate c;
      c.vpl = standard_.vpls[v];
      c.from = vertices_[v];
      out.push_back(c);
    }
    return out;
  }

  // Each camera point turns by a cosine-distributed direction; a diffuse
  // surface there becomes a reverse candidate (flux gathered later).
  void add_reverse_candidates(int k, const std::vector<CameraPoint>& points, std::vector<Candidate>& out,
                              RayCounts& rays) const {
    for (int i = 0; i < camera_paths_; ++i) {
      const CameraPoint& p = points[size_t(i)];
      if (!p.x.valid()) continue;
      const glm::vec2 u = sample_2d(uint32_t(k * camera_paths_ + i), 2, camera_seed_);
      const glm::vec3 w = Onb(p.facing).to_world(cosine_hemisphere(u));
      Ray ray{offset_origin(p.x.surface, w), w};
      ++rays.secondary;
      Hit hit;
      if (!context_.accel.intersect(ray, hit)) continue;
      const SurfacePoint y = surface_at(context_.scene, hit, w);
      if (y.material->type != MaterialType::Diffuse) continue;  // reverse VPLs are Lambertian only
      Candidate c;
      c.reverse = true;
      c.own = i;
      c.receiver.surface = y;
      c.receiver.wo = -w;
      c.receiver.depth = hit.t;
      c.vpl.position = y.position;
      c.vpl.normal = glm::dot(-w, y.geometric_normal) >= 0.0f ? y.shading_normal : -y.shading_normal;
      c.vpl.incident = c.vpl.normal;
      c.vpl.albedo = y.albedo;
      c.vpl.material = context_.scene.triangle_material[hit.triangle];
      c.vpl.kind = VplKind::Surface;
      out.push_back(c);
    }
  }

  // p_R and the image response at the set's camera points: one shadow ray per
  // point that the VPL could light or that could have found it.
  void measure(Candidate& c, const std::vector<CameraPoint>& points, RayCounts& rays) const {
    Vpl unit = c.vpl;
    unit.flux = glm::vec3(1.0f);
    const bool diffuse_vpl =
        c.vpl.kind == VplKind::Surface && context_.scene.materials[c.vpl.material].type == MaterialType::Diffuse;
    for (int i = 0; i < camera_paths_; ++i) {
      const CameraPoint& p = points[size_t(i)];
      if (!p.x.valid()) continue;
      const glm::vec3 d = c.vpl.position - p.x.surface.position;
      const float dist2 = glm::dot(d, d);
      if (!(dist2 > 0.0f)) continue;
      const float dist = std::sqrt(dist2);
      const glm::vec3 w = d / dist;
      // Cosine-distributed from x, reaching the VPL's side: p(y | x) in area measure.
      const float density = diffuse_vpl ? std::max(0.0f, glm::dot(p.facing, w)) * kInvPi *
                                              std::max(0.0f, -glm::dot(c.vpl.normal, w)) / dist2
                                        : 0.0f;
      ShadowQuery q;
      const glm::vec3 light = p.receives ? shading_.contribution(p.x, unit, q) : glm::vec3(0.0f);
      const bool lights = light.x + light.y + light.z > 0.0f;
      if (!(density > 0.0f) && !lights) continue;
      if (!lights) {
        const Ray ray = shadow_ray(p.x.surface, w, shadow_target(c.vpl), dist);  // as contribution() aims it
        q = ShadowQuery{ray.origin, ray.direction, ray.tfar};
      }
      // The camera path that found the VPL saw it: no ray needed (nor a miss by rounding).
      if (i != c.own && occluded(q, rays)) continue;
      c.density += density;
      c.response += p.x.throughput * p.x.surface.albedo * light;
    }
  }

  // Balance heuristic for the path receiver <- y <- z: the weight of the
  // reverse way; the standard way's is one minus it.
  static float reverse_weight(float p_reverse, float p_standard) {
    return p_reverse + p_standard > 0.0f ? p_reverse / (p_reverse + p_standard) : 0.0f;
  }

  float punctual_standard_density(uint32_t exact, glm::vec3 y, glm::vec3 n_y) const {
    return float(settings_.paths_per_set) * selection_probability(exact_entry_[exact]) *
           punctual_density(context_.scene, exact_[exact], context_.lights.scene_radius(), y, n_y);
  }

  // A reverse VPL's flux: the light reaching it from the set's standard VPLs
  // and the exact lights, each weighted for this way, over p_R. Unclamped,
  // like a light path's own step from z to y: the weight p_R / (p_R + p_L)
  // falls as p_L grows with 1 / r^2, so the product stays bounded near z,
  // and the reverse way adds no clamping bias of its own.
  void gather(Candidate& y, std::span<const Candidate> standard, RayCounts& rays) const {
    glm::vec3 irradiance(0.0f);
    const glm::vec3 p = y.vpl.position, n = y.vpl.normal;
    for (const Candidate& z : standard) {
      ShadowQuery q;
      const glm::vec3 light = gathering_.contribution(y.receiver, z.vpl, q);
      if (!(light.x + light.y + light.z > 0.0f) || occluded(q, rays)) continue;
      irradiance += light * reverse_weight(y.density, continuation_density(context_.scene, z.vpl, z.from, p, n, max_depth_));
    }
    for (uint32_t i = 0; i < exact_.size(); ++i) {
      ShadowQuery q;
      const glm::vec3 light = gathering_.contribution(y.receiver, exact_[i], q);
      if (!(light.x + light.y + light.z > 0.0f) || occluded(q, rays)) continue;
      irradiance += light * reverse_weight(y.density, punctual_standard_density(i, p, n));
    }
    // contribution() is demodulated: a Lambertian receiver's 1 / pi.
    y.vpl.flux = y.density > 0.0f ? irradiance * (kPi / y.density) : glm::vec3(0.0f);
  }

  // A standard VPL keeps the standard way's share of its flux. Its
  // predecessor is a candidate of the same set, which begins at VPL `first`
  // of the light paths' sets (only its geometry is read: flux weighing does
  // not change it).
  void weigh_standard(Candidate& c, const std::vector<Candidate>& set, uint32_t first) const {
    float p_standard = 0.0f;
    switch (c.from.from) {
      case LightVertex::From::Light:
      case LightVertex::From::Specular: return;  // no reverse VPL stands for it
      case LightVertex::From::Vpl: {
        const Candidate& z = set[c.from.index - first];
        p_standard = continuation_density(context_.scene, z.vpl, z.from, c.vpl.position, c.vpl.normal, max_depth_);
        break;
      }
      case LightVertex::From::Punctual:
        for (uint32_t i = 0; i < exact_.size(); ++i)
          if (exact_entry_[i] == c.from.index) p_standard = punctual_standard_density(i, c.vpl.position, c.vpl.normal);
        break;
    }
    c.vpl.flux *= 1.0f - reverse_weight(c.density, p_standard);
  }

  // K draws (on average) by estimated contribution, cut into the set's G
  // groups, each candidate rounded by its own number (importance/resample.h).
  void resample(int k, const std::vector<Candidate>& candidates, SetResult& out) const {
    std::vector<double> weights(candidates.size());
    double estimated = 0.0;
    for (size_t c = 0; c < candidates.size(); ++c)
      estimated += weights[c] = std::max(0.0f, luminance(candidates[c].vpl.flux * candidates[c].response));
    const double floor = estimated > 0.0 ? kResampleFloor * estimated / double(candidates.size()) : 1.0;
    double total = 0.0;
    for (size_t c = 0; c < candidates.size(); ++c) {
      const glm::vec3 flux = candidates[c].vpl.flux;
      weights[c] = flux.x + flux.y + flux.z > 0.0f ? weights[c] + floor : 0.0;  // nothing to carry: never drawn
      total += weights[c];
    }
    if (!(total > 0.0)) {
      out.group_sizes.assign(size_t(settings_.aa_samples), 0u);
      return;
    }
    const int groups = settings_.aa_samples, keep = settings_.bidir_vpls;
    for (int g = 0; g < groups; ++g) {
      const size_t group_first = out.vpls.size();
      const double draws = double((g + 1) * keep / groups - g * keep / groups);
      for (size_t c = 0; c < candidates.size(); ++c) {
        if (!(weights[c] > 0.0)) continue;
        // A candidate's number follows it from frame to frame: its light path
        // (standard) or camera path (reverse) within the set.
        const uint32_t id = candidates[c].reverse ? 0x80000000u | uint32_t(candidates[c].own) : uint32_t(c);
        const double u = double(hash(frame_.seed, uint32_t(k), hash(id, kResampleTag)) >> 8) * 0x1p-24;
        const double expected = draws * weights[c] / total;
        const int count = rounded_draws(expected, group_offset(u, g, groups));
        if (count == 0) continue;
        Vpl v = candidates[c].vpl;
        v.flux *= float(double(count) / (expected * double(groups)));
        out.vpls.push_back(v);
      }
      out.group_sizes.push_back(uint32_t(out.vpls.size() - group_first));
    }
  }

  const SceneContext& context_;
  const RenderSettings& settings_;
  const FrameSetup& frame_;
  const Distribution1D* selection_;
  const StartGuide* guide_;
  RayCounts& rays_;
  const VplShading shading_;    // camera points as receivers: clamped, as the image will see the VPLs
  const VplShading gathering_;  // reverse VPLs as receivers: unclamped (see gather())
  const std::vector<Vpl> exact_;
  std::vector<uint32_t> exact_entry_;
  const CameraFrontEnd camera_;
  const uint32_t camera_seed_;
  const int camera_paths_;
  const int max_depth_;
  VplSets standard_;
  std::vector<LightVertex> vertices_;
  std::vector<std::vector<CameraPoint>> points_;  // per set
};

}  // namespace

VplSets generate_bidirectional(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                               const LightPathOptions& light_paths, RayCounts& rays) {
  return Builder(context, settings, frame, light_paths, rays).build();
}

}  // namespace igi::importance
