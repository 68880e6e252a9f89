#include "importance/light_importance.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "importance/camera_points.h"
#include "material/bsdf.h"
#include "sampling/content_hash.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "sampling/warp.h"
#include "scene/surface.h"

namespace igi::importance {
namespace {

// Above this many lights an estimate vertex picks its light by power alone:
// weighing every light at every vertex would cost more than the paths.
constexpr size_t kMaxLocalLights = 1024;
// Share of a vertex's light choice made by power, so a light the local
// weights underrate is still asked now and then.
constexpr float kPowerShare = 0.2f;
// Dimensions: film position (2), then per vertex light choice, light point
// (2), lobe, direction (2), roulette, each 1D draw a pair of its own.
constexpr uint32_t kFilmDims = 2, kDimsPerVertex = 10;

// Every light as a point of typical irradiance, for choosing one per vertex.
struct LightProxy {
  LightKind kind;
  glm::vec3 position{0.0f};  // centroid; directional: unused
  glm::vec3 normal{0.0f};    // area: front normal; spot: axis; directional: travel direction
  float scale = 0.0f;        // area: Le A / pi (luminance); point, spot: intensity; directional, environment: irradiance
  float extent2 = 0.0f;      // area: the light's area, a floor on r^2 near it
  const PunctualLight* punctual = nullptr;
};

std::vector<LightProxy> light_proxies(const LightSet& lights) {
  const Scene& scene = lights.scene();
  const float radius = lights.scene_radius();
  std::vector<LightProxy> out;
  for (uint32_t i = 0; i < lights.lights().size(); ++i) {
    const Light& l = lights.lights()[i];
    LightProxy p;
    p.kind = l.kind;
    if (l.kind == LightKind::Environment) {
      // The irradiance of an open plane under a sky of the same flux: its
      // power is pi R^2 x the radiance over the sphere, and a constant sky L
      // gives pi L, i.e. power / (4 pi R^2). No position: the same everywhere.
      p.scale = lights.light_power(i) / (4.0f * kPi * radius * radius);
    } else if (l.kind == LightKind::Area) {
      const glm::uvec3& t = scene.triangles[l.index];
      const glm::vec3 a = scene.positions[t[0]], b = scene.positions[t[1]], c = scene.positions[t[2]];
      p.position = (a + b + c) / 3.0f;
      p.normal = glm::normalize(glm::cross(b - a, c - a));
      p.extent2 = lights.triangle_area(l.index);
      p.scale = luminance(scene.materials[scene.triangle_material[l.index]].emission) * p.extent2 * kInvPi;
    } else {
      p.punctual = &scene.lights[l.index];
      p.position = p.punctual->position;
      p.normal = glm::normalize(p.punctual->direction);
      p.scale = luminance(p.punctual->intensity);
    }
    out.push_back(p);
  }
  return out;
}

// Unoccluded irradiance a light gives at x (normal n facing the viewer), roughly.
float local_weight(const LightProxy& l, glm::vec3 x, glm::vec3 n) {
  if (l.kind == LightKind::Environment) return l.scale;
  if (l.kind == LightKind::Directional) return l.scale * std::max(0.0f, -glm::dot(n, l.normal));
  const glm::vec3 d = l.position - x;
  const float dist2 = std::max(glm::dot(d, d), 1e-12f);
  const glm::vec3 w = d / std::sqrt(dist2);
  // Centroid cosines misjudge lights near the horizon: a little weight stays.
  const float cos_x = 0.05f + std::max(0.0f, glm::dot(n, w));
  switch (l.kind) {
    case LightKind::Area: return l.scale * (0.05f + std::max(0.0f, -glm::dot(l.normal, w))) * cos_x / std::max(dist2, l.extent2);
    case LightKind::Spot: return l.scale * (0.05f + spot_attenuation(*l.punctual, -w)) * cos_x / dist2;
    default: return l.scale * cos_x / dist2;
  }
}

// One estimate path's walk, crediting lights in `credit`.
class Estimator {
 public:
  Estimator(const SceneContext& context, const RenderSettings& settings, uint32_t seed)
      : context_(context), settings_(settings), seed_(seed), proxies_(light_proxies(context.lights)) {
    for (uint32_t l = 0; l < context.lights.lights().size(); ++l) power_.push_back(context.lights.light_power(l));
    power_total_ = 0.0f;
    for (float p : power_) power_total_ += p;
    local_.resize(proxies_.size());
  }

  void trace(const CameraFrontEnd& camera, uint32_t index, std::vector<double>& credit, RayCounts& rays) {
    GSample g = trace_camera_point(context_.accel, camera, index, seed_, depth_limit(settings_.specular_depth), rays);
    if (!g.valid()) return;
    SurfacePoint sp = g.surface;
    glm::vec3 wo = g.wo, throughput = g.throughput;
    for (int vertex = 0; vertex < kEstimateBounces; ++vertex) {
      SampleStream u(index, seed_, kFilmDims + kDimsPerVertex * uint32_t(vertex));
      const float u_light = u.next_1d();
      const glm::vec2 u_point = u.next_2d();
      const float u_lobe = u.next_1d();
      const glm::vec2 u_dir = u.next_2d();
      const float u_roulette = u.next_1d();
      if (!sp.material->is_specular()) next_event(sp, wo, throughput, vertex, u_light, u_point, credit, rays);
      auto bs = bsdf_sample(sp, wo, u_dir, u_lobe);
      if (!bs) return;
      throughput *= bs->weight;
      if (vertex >= 1) {  // Russian roulette on the path's throughput
        const float q = std::min(0.95f, max_component(throughput));
        if (!(u_roulette < q)) return;
        throughput /= q;
      }
      Ray ray{offset_origin(sp, bs->wi), bs->wi};
      ++rays.secondary;
      Hit hit;
      if (!context_.accel.intersect(ray, hit)) return;
      sp = surface_at(context_.scene, hit, ray.direction);
      wo = -ray.direction;
    }
  }

 private:
  // The light to ask at x: by local irradiance (mixed with power), or by power alone.
  uint32_t choose_light(const SurfacePoint& sp, glm::vec3 wo, float u, float& probability) {
    const size_t n = proxies_.size();
    const glm::vec3 normal = glm::dot(wo, sp.shading_normal) >= 0.0f ? sp.shading_normal : -sp.shading_normal;
    float local_total = 0.0f;
    if (n <= kMaxLocalLights)
      for (size_t l = 0; l < n; ++l) local_total += (local_[l] = local_weight(proxies_[l], sp.position, normal));
    const float local_share = local_total > 0.0f ? 1.0f - kPowerShare : 0.0f;
    auto choice = [&](size_t l) {
      return (local_share > 0.0f ? local_share * local_[l] / local_total : 0.0f) +
             (1.0f - local_share) * power_[l] / power_total_;
    };
    float cumulative = 0.0f;
    size_t last = 0;  // the last light that can be chosen, for u rounded past every boundary
    for (size_t l = 0; l < n; ++l) {
      probability = choice(l);
      if (!(probability > 0.0f)) continue;
      cumulative += probability;
      last = l;
      if (u < cumulative) return uint32_t(l);
    }
    probability = choice(last);
    return uint32_t(last);
  }

  void next_event(const SurfacePoint& sp, glm::vec3 wo, glm::vec3 throughput, int vertex, float u_light,
                  glm::vec2 u_point, std::vector<double>& credit, RayCounts& rays) {
    float select = 0.0f;
    const uint32_t l = choose_light(sp, wo, u_light, select);
    // Punctual lights' direct light is exact: only what bounces counts for
    // their VPLs. Area lights and the sky reach the image through VPLs of their own.
    const bool has_vpls = proxies_[l].kind == LightKind::Area || proxies_[l].kind == LightKind::Environment;
    if (select <= 0.0f || (vertex == 0 && !has_vpls)) return;
    const LightSample ls = context_.lights.sample_light(l, select, sp.position, u_point);
    if (!(ls.pdf > 0.0f)) return;
    const glm::vec3 f = bsdf_eval(sp, wo, ls.direction);
    const glm::vec3 c = throughput * f * ls.radiance * (std::abs(glm::dot(ls.direction, sp.shading_normal)) / ls.pdf);
    const float y = luminance(c);
    if (!(y > 0.0f) || !std::isfinite(y)) return;
    const Ray shadow = shadow_ray(sp, ls.direction, ls.position, ls.distance);
    ++rays.shadow;
    if (!context_.accel.occluded(shadow)) {
      credit[l] += double(y);
      ++credited_;
    }
  }

 public:
  // Shadow rays that found their light: the estimate's sample count.
  size_t credited() const { return credited_; }

 private:

  const SceneContext& context_;
  const RenderSettings& settings_;
  const uint32_t seed_;
  std::vector<LightProxy> proxies_;
  std::vector<float> power_;
  float power_total_ = 0.0f;
  std::vector<float> local_;
  size_t credited_ = 0;
};

}  // namespace

std::vector<float> selection_weights(const std::vector<float>& contribution, const std::vector<float>& power,
                                     float floor) {
  double c_total = 0.0, p_total = 0.0;
  for (float c : contribution) c_total += c;
  for (float p : power) p_total += p;
  // Nothing seen (a camera in the dark): power alone.
  const double view_share = c_total > 0.0 ? 1.0 - double(floor) : 0.0;
  std::vector<float> weights(power.size());
  for (size_t l = 0; l < power.size(); ++l)
    weights[l] = float(view_share * (c_total > 0.0 ? contribution[l] / c_total : 0.0) +
                       (1.0 - view_share) * (p_total > 0.0 ? power[l] / p_total : 0.0));
  return weights;
}

LightSelection estimate_light_importance(const SceneContext& context, const RenderSettings& settings,
                                         const FrameSetup& frame, RayCounts& rays) {
  const uint32_t seed = hash(frame.seed, 0x6c677469u /* "lgti" */);
  const CameraFrontEnd camera(frame);
  const size_t lights = context.lights.lights().size();
  // Chunks of a fixed number of paths, summed in chunk order: the sums do not
  // depend on how many threads ran them.
  constexpr int kChunk = 256;
  const int paths = settings.importance_paths, chunks = (paths + kChunk - 1) / kChunk;
  struct Chunk {
    std::vector<double> credit;
    size_t credited = 0;
    RayCounts rays;
  };
  std::vector<Chunk> parts(static_cast<size_t>(chunks));
  parallel_tasks(chunks, [&](int c) {
    Chunk& part = parts[size_t(c)];
    part.credit.assign(lights, 0.0);
    Estimator estimator(context, settings, seed);
    for (int i = c * kChunk; i < std::min(paths, (c + 1) * kChunk); ++i)
      estimator.trace(camera, uint32_t(i), part.credit, part.rays);
    part.credited = estimator.credited();
  });
  std::vector<double> credit(lights, 0.0);
  size_t credited = 0;
  for (const Chunk& part : parts) {
    for (size_t l = 0; l < lights; ++l) credit[l] += part.credit[l];
    credited += part.credited;
    rays += part.rays;
  }
  LightSelection out;
  std::vector<float> power(lights);
  for (uint32_t l = 0; l < lights; ++l) {
    out.contribution.push_back(float(credit[l] / std::max(1, settings.importance_paths)));
    power[l] = context.lights.light_power(l);
  }
  // With fewer samples than lights most lights' estimates are 0 or one
  // sample, by chance: trust the estimate less (the floor rises towards power).
  const float floor = std::max(settings.importance_floor, float(lights) / float(lights + credited));
  const std::vector<float> weights = selection_weights(out.contribution, power, floor);
  out.distribution = Distribution1D(weights);
  out.hash = content_hash(weights.data(), weights.size() * sizeof(float));
  return out;
}

}  // namespace igi::importance
