#include "importance/view_guide.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "core/clamp.h"
#include "core/parallel.h"
#include "core/vpl_contribution.h"
#include "importance/camera_points.h"
#include "material/bsdf.h"
#include "sampling/hash.h"
#include "sampling/sobol.h"
#include "vpl/light_path.h"

namespace igi::importance {
namespace {

// How a light's start space is cut into cells. The pilots come in two
// rounds: one in every cell of the coarse grid; then, where those found the
// view (and next to them), one in every cell of a grid `refine` times finer
// along each dimension the light draws.
struct PilotPlan {
  StartGuide::Resolution coarse;
  int refine;
};

std::optional<PilotPlan> plan_for(LightKind kind) {
  switch (kind) {
    case LightKind::Directional: return PilotPlan{{1, 1, 64, 64}, 4};  // where on the disc
    case LightKind::Environment: return PilotPlan{{8, 8, 8, 8}, 2};    // where on the disc, and from where
    default: return std::nullopt;  // area, point and spot lights start where the plain rule says
  }
}

using Coords = std::array<int, StartGuide::kDims>;

size_t cell_count(const StartGuide::Resolution& r) {
  size_t n = 1;
  for (int k : r) n *= size_t(k);
  return n;
}

// Cells are numbered row-major, the last dimension fastest (as StartGuide's values).
Coords coords_of(const StartGuide::Resolution& r, size_t cell) {
  Coords c{};
  for (int k = StartGuide::kDims - 1; k >= 0; --k) {
    c[k] = int(cell % size_t(r[k]));
    cell /= size_t(r[k]);
  }
  return c;
}

size_t index_of(const StartGuide::Resolution& r, const Coords& c) {
  size_t cell = 0;
  for (int k = 0; k < StartGuide::kDims; ++k) cell = cell * size_t(r[k]) + size_t(c[k]);
  return cell;
}

// The cell of grid `r` that holds `u`.
Coords coords_in(const StartGuide::Resolution& r, StartNumbers u) {
  const std::array<float, StartGuide::kDims> v = StartGuide::dims(u);
  Coords c{};
  for (int k = 0; k < StartGuide::kDims; ++k) c[k] = std::clamp(int(v[k] * float(r[k])), 0, r[k] - 1);
  return c;
}

// Pilot `pilot`'s numbers, somewhere in cell `cell` (a Sobol point of its own
// scaled into the cell, so the pilots are stratified by the grid).
StartNumbers pilot_numbers(const StartGuide::Resolution& r, size_t cell, uint32_t pilot, uint32_t seed) {
  const Coords c = coords_of(r, cell);
  const glm::vec2 a = sample_2d(pilot, 2, seed), b = sample_2d(pilot, 4, seed);
  const std::array<float, StartGuide::kDims> offset = StartGuide::dims(StartNumbers{a, b});
  std::array<float, StartGuide::kDims> v;
  for (int k = 0; k < StartGuide::kDims; ++k)
    v[k] = std::min((float(c[k]) + offset[k]) / float(r[k]), 0x1.fffffep-1f);
  return StartGuide::numbers(v);
}

// The view's points, as the light they receive is weighed: the surface, and
// what the camera sees of it (its specular chain's weight times its albedo).
struct ViewPoint {
  GSample g;
  glm::vec3 weight{1.0f};
};

std::vector<ViewPoint> view_points(const SceneContext& context, const RenderSettings& settings,
                                   const FrameSetup& frame, uint32_t seed, RayCounts& rays) {
  const CameraFrontEnd camera(frame);
  std::vector<ViewPoint> points;
  for (uint32_t i = 0; i < kGuideCameraPoints; ++i) {
    ViewPoint p{trace_camera_point(context.accel, camera, i, seed, depth_limit(settings.specular_depth), rays)};
    if (!p.g.valid()) continue;
    p.weight = p.g.throughput * p.g.surface.albedo;
    points.push_back(p);
  }
  return points;
}

// What one pilot's VPLs give the view, on average over the points it asks.
class PilotJudge {
 public:
  PilotJudge(const SceneContext& context, const RenderSettings& settings, const std::vector<ViewPoint>& points)
      : context_(context),
        settings_(settings),
        points_(points),
        shading_{context.scene, clamp_bound(settings.clamp, context.accel.mean_chord(), 0), settings.glossy_threshold} {}

  float value(uint32_t light, uint32_t pilot, uint32_t seed, StartNumbers u, RayCounts& rays) const {
    const LightPathStart start = start_light_path_at(context_.lights, context_.scene, light, 1.0f, u);
    double sum = 0.0;
    uint32_t lookup = pilot * uint32_t(kPilotLookups + kFirstLookups);
    if (start.from_environment) {
      Vpl sky;
      sky.kind = VplKind::Directional;
      sky.normal = start.ray.direction;
      sky.flux = start.irradiance;
      sum += seen(sky, lookup, rays);
    }
    const int depth = std::min(depth_limit(settings_.light_depth), kPilotVertices);
    rays.secondary += uint64_t(walk_light_path(
        context_.accel, context_.scene, start, depth, pilot, seed, BounceDraws::TwoSingles,
        [&](const LightPathVertex& v) {
          const Material& m = *v.sp.material;
          if (settings_.caustics ? focuses_light(m, settings_.glossy_threshold) : m.is_specular()) return true;
          const Vpl vpl{v.sp.position, v.sp.shading_normal_facing(v.wo), v.flux, v.wo, v.sp.albedo,
                        context_.scene.triangle_material[v.hit.triangle], 0, VplKind::Surface};
          sum += seen(vpl, lookup, rays, v.depth == 0 ? kFirstLookups : kPilotLookups);
          return true;
        }));
    return float(sum);
  }

 private:
  // The luminance `vpl` gives the view's points kPilotLookups at a time from
  // `lookup` on, averaged: one shadow ray a point it would light.
  double seen(const Vpl& vpl, uint32_t& lookup, RayCounts& rays, int lookups = kPilotLookups) const {
    double sum = 0.0;
    for (int k = 0; k < lookups; ++k, ++lookup) {
      const ViewPoint& p = points_[lookup % points_.size()];
      ShadowQuery q;
      const glm::vec3 c = shading_.contribution(p.g, vpl, q);
      if (c == glm::vec3(0.0f)) continue;
      ++rays.shadow;
      if (!context_.accel.occluded(Ray{q.origin, q.direction, 0.0f, q.tfar})) sum += luminance(c * p.weight);
    }
    return sum / lookups;
  }

  const SceneContext& context_;
  const RenderSettings& settings_;
  const std::vector<ViewPoint>& points_;
  const VplShading shading_;
};

// Each cell's value raised to the largest of its neighbours' (one cell along
// every dimension): ...
std::vector<float> dilated(const std::vector<float>& values, const StartGuide::Resolution& r) {
  std::vector<float> out = values;
  for (int k = 0; k < StartGuide::kDims; ++k) {
    if (r[k] == 1) continue;
    size_t stride = 1;
    for (int j = k + 1; j < StartGuide::kDims; ++j) stride *= size_t(r[j]);
    const std::vector<float> in = out;
    for (size_t c = 0; c < in.size(); ++c) {
      const int i = int((c / stride) % size_t(r[k]));
      if (i > 0) out[c] = std::max(out[c], in[c - stride]);
      if (i + 1 < r[k]) out[c] = std::max(out[c], in[c + stride]);
    }
  }
  return out;
}

// The variance of a path's contribution started by the plain rule over the
// same started by `density` (Monte Carlo over the pilots: the plain rule's
// own samples), or 1 where the pilots saw nothing.
float predicted_gain(const std::vector<float>& values, const std::vector<float>& density) {
  double mean = 0.0, square = 0.0, guided = 0.0;
  for (size_t i = 0; i < values.size(); ++i) {
    mean += values[i];
    square += double(values[i]) * values[i];
    guided += double(values[i]) * values[i] / density[i];
  }
  const double n = double(values.size());
  mean /= n, square /= n, guided /= n;
  const double plain_variance = square - mean * mean, guided_variance = guided - mean * mean;
  if (!(plain_variance > 0.0)) return 1.0f;
  return guided_variance > 0.0 ? float(plain_variance / guided_variance) : INFINITY;
}

// Coarse values on the fine grid: each fine cell takes its coarse cell's.
std::vector<float> upsampled(const std::vector<float>& coarse, const StartGuide::Resolution& coarse_r,
                             const StartGuide::Resolution& fine_r) {
  std::vector<float> out(cell_count(fine_r));
  for (size_t f = 0; f < out.size(); ++f) {
    Coords c = coords_of(fine_r, f);
    for (int k = 0; k < StartGuide::kDims; ++k) c[k] /= fine_r[k] / coarse_r[k];
    out[f] = coarse[index_of(coarse_r, c)];
  }
  return out;
}

// The guide's values in tiers (StartGuide adds the floor): kNearShare of the
// paths uniformly over the cells `near` marks; the rest over the cells
// `found` marks, kByValue of them in proportion to its values, the others
// uniformly: a pilot's value is a few lookups' worth, so the guide trusts
// that a cell reaches the view more than by how much.
std::vector<float> tiered(const std::vector<float>& found, const std::vector<float>& near) {
  double found_sum = 0.0, found_cells = 0.0, near_cells = 0.0;
  for (float v : found) found_sum += v, found_cells += v > 0.0f ? 1.0 : 0.0;
  for (float v : near) near_cells += v > 0.0f ? 1.0 : 0.0;
  const double found_share = 1.0 - double(kGuideFloor) - double(kNearShare);
  std::vector<float> out(found.size());
  for (size_t c = 0; c < out.size(); ++c) {
    double v = near[c] > 0.0f ? double(kNearShare) / near_cells : 0.0;
    if (found[c] > 0.0f) v += found_share * (kByValue * found[c] / found_sum + (1.0 - kByValue) / found_cells);
    out[c] = float(v);
  }
  return out;
}

// Each pilot's value, judged on the render threads in chunks that each
// write their own values. Pilot i walks path i of `seed`.
std::vector<float> judge_pilots(const PilotJudge& judge, uint32_t light, const std::vector<StartNumbers>& pilots,
                                uint32_t seed, RayCounts& rays) {
  constexpr size_t kChunk = 64;
  const int chunks = int((pilots.size() + kChunk - 1) / kChunk);
  std::vector<float> values(pilots.size());
  std::vector<RayCounts> chunk_rays(static_cast<size_t>(chunks));
  parallel_tasks(chunks, [&](int c) {
    for (size_t i = size_t(c) * kChunk; i < std::min(pilots.size(), size_t(c + 1) * kChunk); ++i)
      values[i] = judge.value(light, uint32_t(i), seed, pilots[i], chunk_rays[size_t(c)]);
  });
  for (const RayCounts& c : chunk_rays) rays += c;
  return values;
}

// One pilot in each of `cells` of grid `r`.
std::vector<StartNumbers> pilots_in(const StartGuide::Resolution& r, const std::vector<size_t>& cells, uint32_t seed) {
  std::vector<StartNumbers> pilots(cells.size());
  for (size_t i = 0; i < cells.size(); ++i) pilots[i] = pilot_numbers(r, cells[i], uint32_t(i), seed);
  return pilots;
}

std::vector<size_t> every_cell(const StartGuide::Resolution& r) {
  std::vector<size_t> cells(cell_count(r));
  for (size_t c = 0; c < cells.size(); ++c) cells[c] = c;
  return cells;
}

// Per cell of `r`, the mean value of the pilots in it (0 where none is).
std::vector<float> cell_means(const StartGuide::Resolution& r, const std::vector<StartNumbers>& pilots,
                              const std::vector<float>& values, std::vector<float> sum = {},
                              std::vector<float> count = {}) {
  sum.resize(cell_count(r), 0.0f);
  count.resize(sum.size(), 0.0f);
  for (size_t i = 0; i < pilots.size(); ++i) {
    const size_t cell = index_of(r, coords_in(r, pilots[i]));
    sum[cell] += values[i];
    count[cell] += 1.0f;
  }
  for (size_t c = 0; c < sum.size(); ++c) sum[c] = count[c] > 0.0f ? sum[c] / count[c] : 0.0f;
  return sum;
}

// The fine cells of the coarse cells `region` marks (values > 0).
std::vector<size_t> fine_cells_of(const StartGuide::Resolution& coarse, const StartGuide::Resolution& fine,
                                  const std::vector<float>& region) {
  Coords factor{};
  size_t split = 1;
  for (int k = 0; k < StartGuide::kDims; ++k) split *= size_t(factor[k] = fine[k] / coarse[k]);
  std::vector<size_t> cells;
  for (size_t c = 0; c < region.size(); ++c) {
    if (!(region[c] > 0.0f)) continue;
    const Coords at = coords_of(coarse, c);
    for (size_t s = 0; s < split; ++s) {
      const Coords sub = coords_of(factor, s);
      Coords f{};
      for (int k = 0; k < StartGuide::kDims; ++k) f[k] = at[k] * factor[k] + sub[k];
      cells.push_back(index_of(fine, f));
    }
  }
  return cells;
}

// A light's guide grid and its values, from its pilots: `coarse_pilots`
// (one a coarse cell, judged `coarse`), then a pilot in every fine cell
// around those that found the view, where that is affordable.
struct Guess {
  StartGuide::Resolution resolution;
  std::vector<float> values;
};

Guess guess(const PilotJudge& judge, uint32_t light, const PilotPlan& plan,
            const std::vector<StartNumbers>& coarse_pilots, const std::vector<float>& coarse, uint32_t fine_seed,
            RayCounts& rays) {
  // Where to look closer (the found cells and their neighbours), and where
  // to keep a share of the paths (kNearCells around them).
  const std::vector<float> region = dilated(coarse, plan.coarse);
  std::vector<float> near = region;
  for (int d = 1; d < kNearCells; ++d) near = dilated(near, plan.coarse);
  StartGuide::Resolution fine = plan.coarse;
  for (int& n : fine) n = n > 1 ? n * plan.refine : 1;
  const std::vector<size_t> fine_cells = fine_cells_of(plan.coarse, fine, region);
  if (fine_cells.size() > kMaxRefinePilots) return {plan.coarse, tiered(region, near)};
  // A fine cell's value: the mean of its pilots, both rounds'; then its
  // neighbours' too, so that the edges of what was found are not left to the floor.
  std::vector<StartNumbers> pilots = pilots_in(fine, fine_cells, fine_seed);
  std::vector<float> values = judge_pilots(judge, light, pilots, fine_seed, rays);
  pilots.insert(pilots.end(), coarse_pilots.begin(), coarse_pilots.end());
  values.insert(values.end(), coarse.begin(), coarse.end());
  std::vector<float> found = dilated(cell_means(fine, pilots, values), fine);
  return {fine, tiered(found, upsampled(near, plan.coarse, fine))};
}

// The variance of a path's contribution started plainly over started by
// `guide`, on kCheckPilots plain pilots of its own (the guide never saw them).
float checked_gain(const PilotJudge& judge, uint32_t light, const StartGuide& guide, uint32_t seed,
                   RayCounts& rays) {
  std::vector<StartNumbers> pilots(kCheckPilots);
  for (uint32_t i = 0; i < kCheckPilots; ++i) {
    SampleStream u(i, seed, 2);
    pilots[i].point = u.next_2d();
    pilots[i].direction = u.next_2d();
  }
  const std::vector<float> values = judge_pilots(judge, light, pilots, seed, rays);
  std::vector<float> density(kCheckPilots);
  for (uint32_t i = 0; i < kCheckPilots; ++i) density[i] = guide.density(light, pilots[i]);
  return predicted_gain(values, density);
}

}  // namespace

StartGuide build_view_guide(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                            RayCounts& rays, std::vector<GuideReport>* report) {
  StartGuide guide;
  const LightSet& lights = context.lights;
  const uint32_t seed = hash(frame.seed, 0x67756964u /* "guid" */);
  std::vector<ViewPoint> points;
  for (uint32_t light = 0; light < lights.lights().size(); ++light) {
    const std::optional<PilotPlan> plan = plan_for(lights.lights()[light].kind);
    if (!plan || !(lights.light_power(light) > 0.0f)) continue;
    if (points.empty()) points = view_points(context, settings, frame, seed, rays);
    if (points.empty()) return guide;  // the view sees no surface
    const PilotJudge judge(context, settings, points);
    const uint32_t light_seed = hash(seed, light);
    const uint32_t coarse_seed = hash(light_seed, 1), fine_seed = hash(light_seed, 2), check_seed = hash(light_seed, 3);
    // The first round: a pilot in every coarse cell.
    const std::vector<StartNumbers> coarse_pilots = pilots_in(plan->coarse, every_cell(plan->coarse), coarse_seed);
    const std::vector<float> coarse = judge_pilots(judge, light, coarse_pilots, coarse_seed, rays);
    GuideReport r{light};
    for (float v : coarse) r.reach += v > 0.0f ? 1.0f / float(coarse.size()) : 0.0f;
    if (r.reach > 0.0f && r.reach <= kMaxGuideReach) {
      const Guess g = guess(judge, light, *plan, coarse_pilots, coarse, fine_seed, rays);
      StartGuide candidate;
      candidate.guide(light, g.resolution, g.values, kGuideFloor);
      // Where few pilots found the view, the check's own few finds make its
      // answer noisy, and the plain rule is plainly worse: no check.
      r.gain = r.reach < kSureGuideReach ? INFINITY : checked_gain(judge, light, candidate, check_seed, rays);
      r.guided = r.gain >= kMinGuideGain;
      if (r.guided) guide.guide(light, g.resolution, g.values, kGuideFloor);
    }
    if (report) report->push_back(r);
  }
  return guide;
}

}  // namespace igi::importance
