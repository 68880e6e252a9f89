#include "lightcuts/lightcuts_method.h"

#include <stdexcept>

#include "core/clamp.h"
#include "core/direct_lights.h"
#include "lightcuts/lightcuts_settings.h"
#include "lightcuts/reconstruction.h"
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
  scene_lights_ = exact_lights(context_.scene);
  tree_ = build_light_tree(make_light_leaves(context_.scene, vpls_), context_.scene.bounds().diagonal(), frame.seed);
  state_hash_ = combine_content_hashes(vpls_.hash, tree_.hash);
  for (auto* counter : {&cuts_, &cut_nodes_, &reused_, &interpolated_, &reconstructed_, &blocked_}) counter->store(0);
}

CutStats LightcutsMethod::stats() const {
  CutStats s;
  s.cuts = cuts_.load();
  s.cut_nodes = cut_nodes_.load();
  s.reused = reused_.load();
  s.interpolated = interpolated_.load();
  s.reconstructed = reconstructed_.load();
  s.blocked = blocked_.load();
  return s;
}

CutEngine LightcutsMethod::engine() const {
  const LightingContext lighting{context_.scene, vpls_, scene_lights_, clamp_bound_, settings_.glossy_threshold};
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

// Pixels in blocks of B x B aligned to the image (a block's pixels outside
// the tile are traced too, so a pixel never depends on the tiling). A block
// splits into groups by surface, in pixel order: each pixel not yet grouped
// gathers the later ones on its surface (lightcuts/reconstruction.h,
// same_surface). A group of two or more Lambertian points takes one block cut
// (lightcuts/cut.h); any other pixel a plain cut of its own.
void LightcutsMethod::render_blocks(const TileJob& job, std::span<glm::vec3> out, CutStats& stats,
                                    RayCounts& rays) const {
  const int b = settings_.lightcuts_block;
  const GatherPointTracer tracer(context_.accel, frame_, 1, specular_depth(settings_));
  CutEngine cuts = engine();
  thread_local std::vector<GatherPoint> points, group;
  thread_local std::vector<glm::vec3> values, group_values;
  thread_local std::vector<size_t> members;
  thread_local std::vector<char> done;
  thread_local GatherTree gather;
  auto diffuse = [](const GatherPoint& g) { return g.valid() && g.surface.material->type == MaterialType::Diffuse; };
  for (int by = job.y / b * b; by < job.y + job.h; by += b)
    for (int bx = job.x / b * b; bx < job.x + job.w; bx += b) {
      const int w = std::min(b, frame_.width - bx), h = std::min(b, frame_.height - by);
      auto inside = [&](size_t i) {
        const int x = bx + int(i) % w, y = by + int(i) / w;
        return x >= job.x && x < job.x + job.w && y >= job.y && y < job.y + job.h;
      };
      points.clear();
      for (int y = by; y < by + h; ++y)
        for (int x = bx; x < bx + w; ++x) points.push_back(tracer.trace(x, y, 0, rays));
      values.assign(points.size(), glm::vec3(0.0f));
      done.assign(points.size(), 0);
      for (size_t i = 0; i < points.size(); ++i) {
        if (done[i]) continue;
        group.clear();
        members.clear();
        if (diffuse(points[i]))
          for (size_t j = i; j < points.size(); ++j)
            if (!done[j] && diffuse(points[j]) && same_surface(points[j], points[i])) {
              group.push_back(points[j]);
              members.push_back(j);
            }
        group_values.assign(group.size(), glm::vec3(0.0f));
        if (group.size() >= 2 && cuts.shade_block(group, group_values, stats, rays)) {
          for (size_t m = 0; m < members.size(); ++m) {
            values[members[m]] = group_values[m];
            done[members[m]] = 1;
          }
          continue;
        }
        done[i] = 1;
        if (!inside(i)) continue;  // only the tile's pixels need a cut of their own
        gather.build(std::span<const GatherPoint>(&points[i], 1), 1, 0);
        values[i] = cuts.shade(gather, nullptr, stats, rays);
      }
      for (int y = std::max(by, job.y); y < std::min(by + h, job.y + job.h); ++y)
        for (int x = std::max(bx, job.x); x < std::min(bx + w, job.x + job.w); ++x) {
          const size_t i = size_t(y - by) * w + size_t(x - bx);
          out[size_t(y - job.y) * job.w + size_t(x - job.x)] = points[i].emitted + values[i];
        }
    }
}

void LightcutsMethod::render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const {
  CutStats stats;
  if (settings_.lightcuts_block > 1 && settings_.lightcuts_spacing <= 1 && settings_.lightcuts_samples == 1)
    render_blocks(job, out, stats, rays);
  else if (settings_.lightcuts_spacing > 1)
    render_reconstructed(job, out, stats, rays);
  else
    render_plain(job, out, stats, rays);
  cuts_ += stats.cuts;
  cut_nodes_ += stats.cut_nodes;
  reused_ += stats.reused;
  interpolated_ += stats.interpolated;
  reconstructed_ += stats.reconstructed;
  blocked_ += stats.blocked;
}

}  // namespace igi::lightcuts
