#include "lightcuts/lightcuts_method.h"

#include <stdexcept>

#include "lightcuts/lightcuts_settings.h"
#include "lightcuts/reconstruction.h"
#include "methods/clamp.h"
#include "sampling/content_hash.h"
#include "sampling/hash.h"
#include "vpl/vpl_generator.h"

namespace igi::lightcuts {

LightcutsMethod::LightcutsMethod(const SceneContext& context, const RenderSettings& settings)
    : context_(context), settings_(settings) {
  if (auto error = settings_error(settings)) throw std::invalid_argument(*error);
}

void LightcutsMethod::begin_frame(const FrameSetup& frame) {
  frame_ = frame;
  clamp_bound_ = clamp_bound(settings_.clamp, context_.accel.mean_chord(), frame.sample_begin);
  vpls_ = generate_vpls(context_, settings_, frame.seed);
  tree_ = build_light_tree(make_light_leaves(context_.scene, vpls_), context_.scene.bounds().diagonal(), frame.seed);
  state_hash_ = combine_content_hashes(vpls_.hash, tree_.hash);
  for (auto* counter : {&cuts_, &cut_nodes_, &reused_, &interpolated_, &reconstructed_}) counter->store(0);
}

CutStats LightcutsMethod::stats() const {
  CutStats s;
  s.cuts = cuts_.load();
  s.cut_nodes = cut_nodes_.load();
  s.reused = reused_.load();
  s.interpolated = interpolated_.load();
  s.reconstructed = reconstructed_.load();
  return s;
}

CutEngine LightcutsMethod::engine() const {
  const LightingContext lighting{context_.scene, vpls_.vpls, clamp_bound_};
  return CutEngine(tree_, lighting, context_.accel, CutSettings{settings_.lightcuts_error, settings_.lightcuts_max_cut});
}

// Every pixel its own cut, through its K gather points.
void LightcutsMethod::render_plain(const TileJob& job, std::span<glm::vec3> out, CutStats& stats,
                                   RayCounts& rays) const {
  const int samples = settings_.lightcuts_samples;
  const GatherPointTracer tracer(context_.accel, frame_, samples, specular_depth(settings_));
  CutEngine cuts = engine();
  thread_local std::vector<GatherPoint> points;
  thread_local GatherTree gather;
  const uint32_t gather_seed = hash(frame_.seed, 0x67747265u /* "gtre" */);
  for (int y = 0; y < job.h; ++y)
    for (int x = 0; x < job.w; ++x) {
      const int px = job.x + x, py = job.y + y;
      points.clear();
      glm::vec3 emitted(0.0f);
      for (int k = 0; k < samples; ++k) {
        points.push_back(tracer.trace(px, py, k, rays));
        emitted += points.back().emitted;
      }
      gather.build(points, samples, hash(gather_seed, uint32_t(px), uint32_t(py)));
      out[size_t(y) * job.w + x] = emitted * (1.0f / float(samples)) + cuts.shade(gather, nullptr, stats, rays);
    }
}

namespace {

struct SampleCut {
  GatherPoint point;
  std::vector<CutNode> cut;
  SampleVisibility visibility;
  glm::vec3 value{0.0f};
};

}  // namespace

// Full cuts at the grid samples of the tile's cells (some outside the tile),
// then every other pixel from the samples at its cell's corners.
void LightcutsMethod::render_reconstructed(const TileJob& job, std::span<glm::vec3> out, CutStats& stats,
                                           RayCounts& rays) const {
  const SampleAxis ax{settings_.lightcuts_spacing, frame_.width}, ay{settings_.lightcuts_spacing, frame_.height};
  const int kx0 = ax.cell(job.x), kx1 = ax.cell(job.x + job.w - 1) + 1;
  const int ky0 = ay.cell(job.y), ky1 = ay.cell(job.y + job.h - 1) + 1;
  const int nx = kx1 - kx0 + 1;
  const GatherPointTracer tracer(context_.accel, frame_, 1, specular_depth(settings_));
  CutEngine cuts = engine();
  thread_local GatherTree gather;
  thread_local std::vector<GatherPoint> one(1);
  thread_local std::vector<SampleCut> grid;
  grid.resize(size_t(nx) * size_t(ky1 - ky0 + 1));
  for (int ky = ky0; ky <= ky1; ++ky)
    for (int kx = kx0; kx <= kx1; ++kx) {
      SampleCut& s = grid[size_t(ky - ky0) * nx + (kx - kx0)];
      s.point = one[0] = tracer.trace(ax.coordinate(kx), ay.coordinate(ky), 0, rays);
      gather.build(one, 1, 0);
      s.value = s.point.emitted + cuts.shade(gather, &s.cut, stats, rays);
      s.visibility.build(tree_, s.cut);
    }
  auto sample = [&](int kx, int ky) -> const SampleCut& { return grid[size_t(ky - ky0) * nx + (kx - kx0)]; };
  for (int y = 0; y < job.h; ++y)
    for (int x = 0; x < job.w; ++x) {
      const int px = job.x + x, py = job.y + y;
      glm::vec3& pixel = out[size_t(y) * job.w + x];
      const int sx = ax.sample_at(px), sy = ay.sample_at(py);
      if (sx >= 0 && sy >= 0) {
        pixel = sample(sx, sy).value;
        continue;
      }
      one[0] = tracer.trace(px, py, 0, rays);
      gather.build(one, 1, 0);
      const SampleVisibility* similar[4];
      size_t count = 0;
      const int kx = ax.cell(px), ky = ay.cell(py);
      for (int corner = 0; corner < 4; ++corner) {
        const SampleCut& s = sample(kx + (corner & 1), ky + (corner >> 1));
        if (same_surface(one[0], s.point)) similar[count++] = &s.visibility;
      }
      const size_t used = count >= 2 ? count : 0;  // one sample alone is not trusted
      pixel = one[0].emitted + cuts.shade(gather, nullptr, stats, rays, {similar, used});
    }
}

void LightcutsMethod::render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const {
  CutStats stats;
  if (settings_.lightcuts_spacing > 1)
    render_reconstructed(job, out, stats, rays);
  else
    render_plain(job, out, stats, rays);
  cuts_ += stats.cuts;
  cut_nodes_ += stats.cut_nodes;
  reused_ += stats.reused;
  interpolated_ += stats.interpolated;
  reconstructed_ += stats.reconstructed;
}

}  // namespace igi::lightcuts
