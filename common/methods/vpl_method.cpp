#include "methods/vpl_method.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include "core/clamp.h"
#include "core/direct_lights.h"
#include "core/subpixel.h"
#include "core/tiling.h"
#include "core/vpl_contribution.h"
#include "filter/discontinuity_buffer.h"
#include "importance/view_vpls.h"
#include "methods/bias_compensation.h"
#include "methods/light_upsample.h"
#include "sampling/content_hash.h"
#include "sampling/hash.h"
#include "vpl/vpl_generator.h"
#include "wavelet/wavelet_filter.h"
#include "sampling/pixel_samples.h"

namespace igi {

const char* frame_part_name(FramePart part) {
  switch (part) {
    case FramePart::Vpls: return "VPLs (light paths, importance, bidir)";
    case FramePart::Caustics: return "caustic photons";
    case FramePart::Camera: return "camera, mirrors, glass";
    case FramePart::GlossyGather: return "glossy gather";
    case FramePart::VplLight: return "VPL shadow rays";
    case FramePart::ExactLights: return "exact lights";
    case FramePart::Compensation: return "bias compensation";
    case FramePart::Filter: return "filter and resolve";
    case FramePart::Count: break;
  }
  return "?";
}

namespace {

// Adds the time and rays from its making to its end to `parts` (if any).
class PartTimer {
 public:
  PartTimer(FrameParts* parts, FramePart part, const RayCounts& rays)
      : parts_(parts), part_(part), rays_(rays), before_(rays) {
    if (parts_) start_ = std::chrono::steady_clock::now();
  }
  ~PartTimer() {
    if (!parts_) return;
    const size_t i = size_t(part_);
    parts_->seconds[i] += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    parts_->rays[i].primary += rays_.primary - before_.primary;
    parts_->rays[i].shadow += rays_.shadow - before_.shadow;
    parts_->rays[i].secondary += rays_.secondary - before_.secondary;
  }
  PartTimer(const PartTimer&) = delete;
  PartTimer& operator=(const PartTimer&) = delete;

 private:
  FrameParts* parts_;
  FramePart part_;
  const RayCounts& rays_;
  RayCounts before_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

// Per-thread buffers: tiles come by the thousand, allocations would dominate.
// Shading points are numbered l * P + p for G-buffer layer l (sub-sample k =
// l mod S, glass branch l div S) of region pixel p (P pixels), then L P + h
// for gather hit h (L = S B layers).
struct VplMethod::Scratch {
  GBuffer gbuffer;  // the region's (with --light-divisor, the lattice's)
  GBuffer pixels;   // with --light-divisor: the tile's own pixels
  std::vector<glm::vec3> lattice_light;  // with --light-divisor: demodulated light per lattice sample
  GlossyHits hits;
  std::vector<std::vector<uint32_t>> hits_by_group;  // per (set, group): gather hits
  PixelBatch batch;
  std::vector<glm::vec3> sums;      // VPL sums per shading point
  std::vector<glm::vec3> direct;    // exact lights per shading point (inner pixels' layers, hits)
  std::vector<glm::vec3> value;     // demodulated irradiance per layer sample: the filter's input
  std::vector<glm::vec3> filtered;  // per layer, the core's pixels (the tile and the wavelet's footprint)
  FilterInput filter_input;
  WaveletInput wavelet_input;
  std::vector<glm::vec3> wavelet_out;  // per tile pixel: the filtered mean of its sub-samples
  std::vector<glm::vec3> ratio;        // per tile pixel: wavelet_out / the unfiltered mean, per channel
  std::vector<uint8_t> rotation;       // per region pixel: subpixel_rotation (S > 1)
  std::vector<PixelSurface> surfaces;  // per region pixel, when the caller wants them (border included)
};

VplMethod::VplMethod(const SceneContext& context, const RenderSettings& settings)
    : context_(context), settings_(settings), exact_(exact_lights(context.scene)) {
  if (auto error = settings_error(settings)) throw std::invalid_argument(*error);
  if (settings.caustics) caustics_.emplace(context, settings);
}

void VplMethod::begin_frame(const FrameSetup& frame) {
  frame_ = frame;
  clamp_bound_ = clamp_bound(settings_.clamp, context_.accel.mean_chord(), frame.sample_begin);
  wavelet_levels_ = wavelet_levels_at_pass(settings_.wavelet_levels, frame.sample_begin);
  filter_weight_ = filter_weight_at_pass(frame.sample_begin);
  setup_rays_ = RayCounts{};
  {
    PartTimer timer(parts_, FramePart::Vpls, setup_rays_);
    vpls_ = importance::generate_view_vpls(context_, settings_, frame, setup_rays_);
  }
  if (caustics_) {
    PartTimer timer(parts_, FramePart::Caustics, setup_rays_);
    caustics_->build(frame.seed, 0, frame.sample_begin);
  }
  draws_.reset();
  if (settings_.vpl_draws > 0) draws_.emplace(context_.scene, vpls_, frame.seed);
  // A typical demodulated irradiance: one set's flux spread over the scene
  // (the filter's fixed-point scale and the hand-over's spike level).
  double flux = 0.0;
  for (const Vpl& v : vpls_.vpls) flux += (v.flux.x + v.flux.y + v.flux.z) / 3.0;
  double diagonal = context_.scene.bounds().diagonal();
  const double typical = flux / std::max(1, vpls_.set_count()) / (diagonal * diagonal);
  fixed_scale_ = filter_fixed_scale(typical);
  spike_level_ = filter_spike_level(float(typical), frame.sample_begin);
}

// VPL light on receivers: their sharp GGX lobes are gathered instead (methods/glossy_gather.h).
VplShading VplMethod::vpl_shading() const {
  return VplShading{context_.scene, clamp_bound_, settings_.glossy_threshold, settings_.glossy_threshold};
}

uint64_t VplMethod::frame_state_hash() const {
  uint64_t h = vpls_.hash;
  if (draws_) h = combine_content_hashes(h, draws_->hash());
  if (caustics_) h = combine_content_hashes(h, caustics_->hash());
  return h;
}

// The valid sub-samples of set s (all pixels for ir) that connect to `group`,
// every glass branch of each, in 4 x 4 blocks of the set's own pixel grid so
// a packet's rays start close together (coherent). The set's pixels lie n
// apart in the G-buffer, each sample a few cache lines that are rarely in
// cache (profiled: half this function's time waited on them), so the ids come
// first and each sample is prefetched a few ids ahead of its reading.
// `rotation` holds subpixel_rotation of each region pixel (empty for S = 1).
void VplMethod::collect_set_samples(const GBuffer& gbuffer, std::span<const uint8_t> rotation, int s, int group,
                                    PixelBatch& batch) const {
  const Region& region = gbuffer.region;
  const int n = interleaved() ? vpls_.interleave : 1;
  const int sx = interleaved() ? s % n : 0, sy = interleaved() ? s / n : 0;
  // First column and row of the region that belong to the set (global coordinates).
  const int x_first = region.x0 + ((sx - region.x0 % n) + n) % n;
  const int y_first = region.y0 + ((sy - region.y0 % n) + n) % n;
  const int nx = x_first < region.x0 + region.width ? (region.x0 + region.width - x_first + n - 1) / n : 0;
  const int ny = y_first < region.y0 + region.height ? (region.y0 + region.height - y_first + n - 1) / n : 0;
  thread_local std::vector<uint32_t> ids;
  ids.clear();
  for (int by = 0; by < ny; by += 4)
    for (int bx = 0; bx < nx; bx += 4)
      for (int j = by; j < std::min(by + 4, ny); ++j)
        for (int i = bx; i < std::min(bx + 4, nx); ++i) {
          const int x = x_first + n * i, y = y_first + n * j;
          const size_t pixel = region.index(x, y);
          // subsample_of_group, its rotation looked up.
          const int k = rotation.empty() ? 0 : (group >= rotation[pixel] ? 0 : gbuffer.samples) + group - rotation[pixel];
          for (int b = 0; b < gbuffer.branches; ++b)
            ids.push_back(uint32_t(size_t(b * gbuffer.samples + k) * region.pixels() + pixel));
        }
  constexpr size_t kAhead = 8;
  for (size_t i = 0; i < ids.size(); ++i) {
    if (i + kAhead < ids.size()) {
      const char* ahead = reinterpret_cast<const char*>(&gbuffer.layers[ids[i + kAhead]]);
      for (size_t line = 0; line < sizeof(GSample); line += 64) __builtin_prefetch(ahead + line);
      __builtin_prefetch(ahead + sizeof(GSample) - 1);
    }
    const GSample& g = gbuffer.layers[ids[i]];
    if (g.valid() && receives_vpls(g.surface, settings_.glossy_threshold)) batch.add(ids[i], g);
  }
}

// VPL sums at every shading point that takes VPL light: the sub-samples of
// each (set, group), then the gather hits traced from them. A gather hit
// takes every group of its set, not its sub-sample's group alone: the
// discontinuity buffer averages a camera point's group with its neighbours'
// on the same surface, but a hit lies somewhere else in the scene, alone, and
// with a quarter of a set's VPLs (at --aa 4) one close VPL made a speck that
// the filter spread into a square on a glossy floor. Hits are few (the
// sharp glossy sub-samples' rays), so this costs little.
void VplMethod::shade_vpls(const GBuffer& gbuffer, const GlossyHits& hits, Scratch& scratch, RayCounts& rays) const {
  if (draws_) return shade_drawn(gbuffer, hits, scratch, rays);
  const Region& region = gbuffer.region;
  const size_t camera_points = gbuffer.points();
  const int sets = interleaved() ? vpls_.set_count() : 1;
  const int groups = vpls_.groups;
  scratch.sums.assign(camera_points + hits.points.size(), glm::vec3(0.0f));
  scratch.hits_by_group.resize(size_t(sets) * groups);
  for (auto& list : scratch.hits_by_group) list.clear();
  for (uint32_t h = 0; h < hits.points.size(); ++h) {
    const GSample& y = hits.points[h];
    if (!y.valid() || !receives_vpls(y.surface, settings_.glossy_threshold)) continue;
    const size_t pixel = hits.owner[h] % region.pixels();
    const int x = region.x0 + int(pixel % region.width), yy = region.y0 + int(pixel / region.width);
    const int set = interleaved() ? vpls_.set_of_pixel(x, yy) : 0;
    for (int g = 0; g < groups; ++g) scratch.hits_by_group[size_t(set) * groups + g].push_back(h);
  }
  // Each pixel's group rotation, once per tile (not once per group).
  static_assert(kMaxAntialiasSamples <= 256, "rotations are kept in bytes");
  scratch.rotation.clear();
  if (gbuffer.samples > 1)
    for (int y = region.y0; y < region.y0 + region.height; ++y)
      for (int x = region.x0; x < region.x0 + region.width; ++x)
        scratch.rotation.push_back(uint8_t(subpixel_rotation(x, y, gbuffer.samples)));
  const VplShading shading = vpl_shading();
  PixelBatch& batch = scratch.batch;
  for (int s = 0; s < sets; ++s)
    for (int g = 0; g < groups; ++g) {
      batch.clear();
      collect_set_samples(gbuffer, scratch.rotation, s, g, batch);
      for (uint32_t h : scratch.hits_by_group[size_t(s) * groups + g])
        batch.add(uint32_t(camera_points + h), hits.points[h]);
      if (batch.count == 0) continue;
      batch.pad();
      // igi: the set's own group; ir: that group of every set.
      for (int v = interleaved() ? s : 0; v < (interleaved() ? s + 1 : vpls_.set_count()); ++v) {
        const auto first = vpls_.vpls.begin() + vpls_.group_first(v, g);
        const auto last = vpls_.vpls.begin() + vpls_.group_end(v, g);
        shade_batch(batch, std::span<const Vpl>(first, last), shading, context_.accel, rays, log_);
      }
      for (size_t i = 0; i < batch.count; ++i)
        scratch.sums[batch.index[i]] += glm::vec3(batch.sum_r[i], batch.sum_g[i], batch.sum_b[i]);
    }
}

// The same with --vpl-draws: each shading point draws its own VPLs of all
// sets (methods/vpl_draws.h), one at a time.
void VplMethod::shade_drawn(const GBuffer& gbuffer, const GlossyHits& hits, Scratch& scratch, RayCounts& rays) const {
  const Region& region = gbuffer.region;
  const size_t camera_points = gbuffer.points();
  scratch.sums.assign(camera_points + hits.points.size(), glm::vec3(0.0f));
  const VplShading shading = vpl_shading();
  const uint32_t frame_seed = hash(frame_.seed, 0x76647277u /* "vdrw" */);
  // Shading point `id` = l P + p of the region, or rank r + 1 of its gather hits.
  auto stream = [&](size_t id, uint32_t rank) {
    const size_t pixel = id % region.pixels();
    const int x = region.x0 + int(pixel % region.width), y = region.y0 + int(pixel / region.width);
    return hash(PixelSamples{frame_seed}.drawn(x, y, uint32_t(id / region.pixels())), rank);
  };
  const int k = settings_.vpl_draws;
  for (size_t id = 0; id < camera_points; ++id) {
    const GSample& g = gbuffer.layers[id];
    if (g.valid() && receives_vpls(g.surface, settings_.glossy_threshold))
      scratch.sums[id] = draws_->shade(g, k, stream(id, 0), vpls_.vpls, shading, context_.accel, rays);
  }
  uint32_t rank = 0;
  for (size_t h = 0; h < hits.points.size(); ++h) {
    rank = h > 0 && hits.owner[h] == hits.owner[h - 1] ? rank + 1 : 0;  // an owner's hits are consecutive
    const GSample& y = hits.points[h];
    if (y.valid() && receives_vpls(y.surface, settings_.glossy_threshold))
      scratch.sums[camera_points + h] =
          draws_->shade(y, k, stream(hits.owner[h], rank + 1), vpls_.vpls, shading, context_.accel, rays);
  }
}

// Exact lights at every layer sample of the tile's own pixels (never
// filtered, so the border needs none) and at every gather hit.
void VplMethod::shade_exact(const GBuffer& gbuffer, const TileJob& job, const GlossyHits& hits, Scratch& scratch,
                            RayCounts& rays) const {
  const Region& region = gbuffer.region;
  const size_t camera_points = gbuffer.points();
  scratch.direct.assign(camera_points + hits.points.size(), glm::vec3(0.0f));
  if (exact_.empty()) return;
  PixelBatch& batch = scratch.batch;
  batch.clear();
  for (int l = 0; l < gbuffer.layer_count(); ++l)
    for (int by = 0; by < job.h; by += 4)
      for (int bx = 0; bx < job.w; bx += 4)
        for (int y = job.y + by; y < job.y + std::min(by + 4, job.h); ++y)
          for (int x = job.x + bx; x < job.x + std::min(bx + 4, job.w); ++x) {
            const size_t id = size_t(l) * region.pixels() + region.index(x, y);
            if (gbuffer.layers[id].valid()) batch.add(uint32_t(id), gbuffer.layers[id]);
          }
  for (uint32_t h = 0; h < hits.points.size(); ++h)
    if (hits.points[h].valid()) batch.add(uint32_t(camera_points + h), hits.points[h]);
  if (batch.count == 0) return;
  batch.pad();
  // Exact lights reach every lobe: no gather ray can find a point light.
  const VplShading shading{context_.scene, clamp_bound_, settings_.glossy_threshold, 0.0f};
  shade_batch(batch, exact_, shading, context_.accel, rays, log_);
  for (size_t i = 0; i < batch.count; ++i)
    scratch.direct[batch.index[i]] = glm::vec3(batch.sum_r[i], batch.sum_g[i], batch.sum_b[i]);
}

// Demodulated irradiance per layer sample: its group's VPL sum scaled to a
// whole set's estimate, plus what its gather rays brought back (a gather
// ray that lands on a diffuse surface brings its caustic too).
void VplMethod::combine(const GBuffer& gbuffer, const GlossyHits& hits, Scratch& scratch) const {
  const size_t camera_points = gbuffer.points();
  // Each set alone estimates the full light (ir averages all of them); each group 1 / G of it.
  // Drawn VPLs (--vpl-draws) estimate the whole light already.
  // Gather hits take every group (shade_vpls).
  const float set_scale = draws_ || interleaved() ? 1.0f : 1.0f / float(vpls_.set_count());
  const float scale = draws_ ? 1.0f : float(vpls_.groups) * set_scale;
  scratch.value.resize(camera_points);
  for (size_t i = 0; i < camera_points; ++i) scratch.value[i] = scale * scratch.sums[i];
  for (size_t h = 0; h < hits.points.size(); ++h) {
    const GSample& y = hits.points[h];
    glm::vec3 radiance = y.emitted;
    if (y.valid())
      radiance += y.throughput * modulation(y.surface, y.wo) *
                  (set_scale * scratch.sums[camera_points + h] + scratch.direct[camera_points + h] + caustic(y));
    scratch.value[hits.owner[h]] += hits.weight[h] * radiance;
  }
  for (size_t i = 0; i < hits.light_owner.size(); ++i) scratch.value[hits.light_owner[i]] += hits.light_value[i];
}

// Layer l's demodulated irradiance of the tile's own pixels: through the
// discontinuity buffer (igi), or cropped from the region as it is (ir, or
// filter off). Each layer is filtered on its own: a sub-sample is averaged
// with the same sub-sample of its neighbours where they lie on its surface,
// so edges stay sharp per sub-sample. The rotation of groups
// (core/subpixel.h) gives the neighbours other groups, and over the S
// layers a pixel on an open surface averages every (set, group) once: all the
// frame's VPLs, as with S = 1. A glass branch's layer holds what neighbouring
// pixels see through the same branch (the refracted room, the reflection),
// which is as smooth as any surface's light and filters alike. A layer with
// no valid sample in the tile (no glass there) is skipped: resolve reads
// only valid samples.
void VplMethod::filter_layer(const GBuffer& gbuffer, int l, const Rect& core, Scratch& scratch) const {
  const Region& region = gbuffer.region;
  const size_t inner = size_t(core.w) * core.h;
  const auto layer_value = scratch.value.begin() + ptrdiff_t(size_t(l) * region.pixels());
  glm::vec3* out = scratch.filtered.data() + size_t(l) * inner;
  bool any_valid = false;
  for (int y = core.y; y < core.y + core.h && !any_valid; ++y)
    for (int x = core.x; x < core.x + core.w && !any_valid; ++x) any_valid = gbuffer.at(l, region.index(x, y)).valid();
  if (!any_valid) return;
  if (interleaved() && settings_.filter) {
    FilterInput& in = scratch.filter_input;
    in.x0 = region.x0; in.y0 = region.y0; in.width = region.width; in.height = region.height;
    in.value.assign(layer_value, layer_value + ptrdiff_t(region.pixels()));
    in.depth.resize(region.pixels());
    in.normal.resize(region.pixels());
    for (size_t p = 0; p < region.pixels(); ++p) {
      const GSample& g = gbuffer.at(l, p);
      in.depth[p] = g.depth;
      in.normal[p] = g.valid() ? g.surface.shading_normal : glm::vec3(0.0f);
    }
    FilterSettings fs;
    fs.window = settings_.interleave;
    fs.normal_cos = settings_.filter_normal_cos;
    fs.depth_ratio = settings_.filter_depth_ratio;
    fs.fixed_scale = fixed_scale_;
    filter_handed_over(in, fs, core, filter_weight_, spike_level_, std::span<glm::vec3>(out, inner));
    return;
  }
  for (int y = 0; y < core.h; ++y)
    for (int x = 0; x < core.w; ++x)
      out[size_t(y) * core.w + x] = layer_value[ptrdiff_t(region.index(core.x + x, core.y + y))];
}

// The wavelet filter (wavelet/wavelet_filter.h) runs once per pixel, not per
// layer: on the mean of the filtered demodulated irradiance of the pixel's
// sub-samples (glass branch 0), guided by its first valid sub-sample's
// depth, normal and material. Each sub-sample's irradiance is then scaled
// per channel by filtered / unfiltered mean (resolve), so a pixel whose
// sub-samples share a surface takes the filtered value and one across an
// edge keeps the contrast between its sub-samples. Glass branches past the
// first (reflections in glass) are left as the discontinuity buffer made them.
void VplMethod::wavelet_pass(const GBuffer& gbuffer, const Rect& core, const TileJob& job, Scratch& scratch) const {
  const Region& region = gbuffer.region;
  const size_t core_pixels = size_t(core.w) * core.h;
  WaveletInput& in = scratch.wavelet_input;
  in.x0 = core.x; in.y0 = core.y; in.width = core.w; in.height = core.h;
  in.depth.assign(core_pixels, INFINITY);
  in.normal.assign(core_pixels, glm::vec3(0.0f));
  in.material.assign(core_pixels, 0);
  in.value.assign(core_pixels, glm::vec3(0.0f));
  for (int y = 0; y < core.h; ++y)
    for (int x = 0; x < core.w; ++x) {
      const size_t c = size_t(y) * core.w + x, pixel = region.index(core.x + x, core.y + y);
      int count = 0;
      for (int k = 0; k < gbuffer.samples; ++k) {
        const GSample& g = gbuffer.at(k, pixel);
        if (!g.valid()) continue;
        if (count++ == 0) {
          in.depth[c] = g.depth;
          in.normal[c] = g.surface.shading_normal;
          in.material[c] = uint32_t(g.surface.material - context_.scene.materials.data());
        }
        in.value[c] += scratch.filtered[size_t(k) * core_pixels + c];
      }
      if (count > 1) in.value[c] /= float(count);
    }
  WaveletSettings ws;
  ws.levels = wavelet_levels_;
  const size_t inner = size_t(job.w) * job.h;
  scratch.wavelet_out.resize(inner);
  filter_wavelet(in, ws, Rect{job.x, job.y, job.w, job.h}, scratch.wavelet_out);
  scratch.ratio.resize(inner);
  for (int y = 0; y < job.h; ++y)
    for (int x = 0; x < job.w; ++x) {
      const size_t i = size_t(y) * job.w + x;
      const glm::vec3 before = in.value[size_t(job.y - core.y + y) * core.w + size_t(job.x - core.x + x)];
      const glm::vec3 after = scratch.wavelet_out[i];
      for (int c = 0; c < 3; ++c) scratch.ratio[i][c] = before[c] > 0.0f ? after[c] / before[c] : 1.0f;
    }
}

// A pixel is the mean over its sub-samples of the sum over their glass
// branches of the radiance each layer sample sends along its chain:
// emission seen on the way, plus the chain's throughput x albedo x (filtered
// VPL light + exact lights + caustic). The caustic is unfiltered, like the
// exact lights: its density estimate is already smooth at the photon
// radius, and through the filter the sharp edge of a focused caustic would
// spill onto the neighbours the filter accepts.
void VplMethod::resolve(const GBuffer& gbuffer, const Rect& core, const TileJob& job, const Scratch& scratch,
                        std::span<glm::vec3> out) const {
  const size_t core_pixels = size_t(core.w) * core.h;
  const float inv_samples = 1.0f / float(gbuffer.samples);
  for (int y = 0; y < job.h; ++y)
    for (int x = 0; x < job.w; ++x) {
      const size_t pixel = gbuffer.region.index(job.x + x, job.y + y);
      const size_t c_index = size_t(job.y - core.y + y) * core.w + size_t(job.x - core.x + x);
      const glm::vec3 ratio = wavelet_levels_ > 0 ? scratch.ratio[size_t(y) * job.w + x] : glm::vec3(1.0f);
      glm::vec3 c(0.0f);
      for (int l = 0; l < gbuffer.layer_count(); ++l) {
        const GSample& g = gbuffer.at(l, pixel);
        c += g.emitted;
        if (!g.valid()) continue;
        glm::vec3 filtered = scratch.filtered[size_t(l) * core_pixels + c_index];
        if (l < gbuffer.samples) filtered *= ratio;
        c += g.throughput * modulation(g.surface, g.wo) *
             (filtered + scratch.direct[size_t(l) * gbuffer.region.pixels() + pixel] + caustic(g));
      }
      out[size_t(y) * job.w + x] = c * inv_samples;
    }
}

void VplMethod::render_tile(const TileJob& job, std::span<glm::vec3> out, RayCounts& rays) const {
  render(job, out, {}, rays);
}

bool VplMethod::render_tile_with_surfaces(const TileJob& job, std::span<glm::vec3> out,
                                          std::span<PixelSurface> surfaces, RayCounts& rays) const {
  render(job, out, surfaces, rays);
  return true;
}

// The surfaces, when wanted, come from the G-buffer's sub-sample 0: the rays
// trace_pixel_surfaces() would trace (a third of a sharp preview's time on
// Sponza when traced again).
void VplMethod::render(const TileJob& job, std::span<glm::vec3> out, std::span<PixelSurface> surfaces,
                       RayCounts& rays) const {
  thread_local Scratch scratch;
  if (lattice_light(settings_)) return render_lattice_tile(job, out, surfaces, scratch, rays);
  GBuffer& gbuffer = scratch.gbuffer;
  {
    PartTimer timer(parts_, FramePart::Camera, rays);
    const Region region = tile_region(job, frame_.width, frame_.height);
    scratch.surfaces.resize(surfaces.empty() ? 0 : region.pixels());
    build_gbuffer(context_.accel, frame_, region, settings_.aa_samples, settings_.glass_branches,
                  depth_limit(settings_.specular_depth), gbuffer, rays, log_, scratch.surfaces);
    if (!surfaces.empty())
      for (int y = 0; y < job.h; ++y)
        std::copy_n(scratch.surfaces.begin() + ptrdiff_t(region.index(job.x, job.y + y)), job.w,
                    surfaces.begin() + ptrdiff_t(size_t(y) * job.w));
  }
  const Rect core = light(gbuffer, job, scratch, rays);
  PartTimer timer(parts_, FramePart::Filter, rays);
  resolve(gbuffer, core, job, scratch, out);
}

// The light of the job's pixels (region coordinates: the image's, or a
// lattice's) into scratch.filtered over the returned core, and
// scratch.direct: every part but the camera rays and the resolve.
Rect VplMethod::light(const GBuffer& gbuffer, const TileJob& job, Scratch& scratch, RayCounts& rays) const {
  {
    PartTimer timer(parts_, FramePart::GlossyGather, rays);
    trace_glossy_gather(context_.accel, context_.lights, gbuffer, settings_, frame_.seed, scratch.hits, rays);
  }
  {
    PartTimer timer(parts_, FramePart::VplLight, rays);
    shade_vpls(gbuffer, scratch.hits, scratch, rays);
  }
  {
    PartTimer timer(parts_, FramePart::ExactLights, rays);
    shade_exact(gbuffer, job, scratch.hits, scratch, rays);
  }
  // The glossy gather joins the demodulated irradiance before the filter, so
  // a glossy surface averages its neighbours' gathers like its VPL light.
  combine(gbuffer, scratch.hits, scratch);
  // So does the compensation: it is as noisy as the VPL sums (a few
  // hemisphere samples, one VPL set), the filter's cost does not depend on
  // the values, and filtering it lowers relMSE. Measured with igi-accuracy
  // (corner, 64x48, clamp 0.1, 4 samples, median of 3 seeds), relMSE
  // filtered / added after the filter: M=1 0.0709 / 0.0718, M=16 0.0091 /
  // 0.0094, M=64 0.0065 / 0.0068.
  {
    PartTimer timer(parts_, FramePart::Compensation, rays);
    const VplShading shading = vpl_shading();
    const BiasCompensation compensation(context_.accel, shading, vpls_, exact_, interleaved(),
                                        settings_.compensation_samples, log_);
    compensation.add(gbuffer, frame_.seed, scratch.value, rays);
  }
  PartTimer timer(parts_, FramePart::Filter, rays);
  // The core: the tile and, with the wavelet filter, its footprint (in the region).
  const Region& region = gbuffer.region;
  const int grow = wavelet_footprint(wavelet_levels_);
  const int cx0 = std::max(job.x - grow, region.x0), cy0 = std::max(job.y - grow, region.y0);
  const int cx1 = std::min(job.x + job.w + grow, region.x0 + region.width);
  const int cy1 = std::min(job.y + job.h + grow, region.y0 + region.height);
  const Rect core{cx0, cy0, cx1 - cx0, cy1 - cy0};
  scratch.filtered.resize(size_t(core.w) * core.h * gbuffer.layer_count());
  for (int l = 0; l < gbuffer.layer_count(); ++l) filter_layer(gbuffer, l, core, scratch);
  if (wavelet_levels_ > 0) wavelet_pass(gbuffer, core, job, scratch);
  return core;
}

// --light-divisor D (methods/light_upsample.h): the tile's own pixels at
// full resolution, light on the lattice cells around them (with the filter's
// border in lattice pixels), then each pixel's light upsampled from them.
void VplMethod::render_lattice_tile(const TileJob& job, std::span<glm::vec3> out, std::span<PixelSurface> surfaces,
                                    Scratch& scratch, RayCounts& rays) const {
  const int step = settings_.light_divisor;
  const TileJob cells = lattice_cells(job, step, frame_.width, frame_.height, light_border(settings_));
  GBuffer& pixels = scratch.pixels;
  GBuffer& lattice = scratch.gbuffer;
  {
    PartTimer timer(parts_, FramePart::Camera, rays);
    const int depth = depth_limit(settings_.specular_depth);
    build_gbuffer(context_.accel, frame_, Region{job.x, job.y, job.w, job.h}, settings_.aa_samples,
                  settings_.glass_branches, depth, pixels, rays, log_, surfaces);
    Region region = tile_region(cells, lattice_extent(frame_.width, step), lattice_extent(frame_.height, step));
    region.step = step;
    build_gbuffer(context_.accel, frame_, region, settings_.aa_samples, settings_.glass_branches, depth, lattice,
                  rays, log_);
  }
  const Rect core = light(lattice, cells, scratch, rays);
  PartTimer timer(parts_, FramePart::Filter, rays);
  // The cells' demodulated light per layer, as resolve() adds it up.
  const size_t core_pixels = size_t(core.w) * core.h;
  scratch.lattice_light.assign(size_t(lattice.layer_count()) * lattice.region.pixels(), glm::vec3(0.0f));
  for (int l = 0; l < lattice.layer_count(); ++l)
    for (int y = cells.y; y < cells.y + cells.h; ++y)
      for (int x = cells.x; x < cells.x + cells.w; ++x) {
        const size_t pixel = lattice.region.index(x, y);
        const GSample& g = lattice.at(l, pixel);
        if (!g.valid()) continue;
        const size_t c_index = size_t(y - core.y) * core.w + size_t(x - core.x);
        glm::vec3 filtered = scratch.filtered[size_t(l) * core_pixels + c_index];
        if (l < lattice.samples && wavelet_levels_ > 0) filtered *= scratch.ratio[size_t(y - cells.y) * cells.w + (x - cells.x)];
        scratch.lattice_light[size_t(l) * lattice.region.pixels() + pixel] =
            filtered + scratch.direct[size_t(l) * lattice.region.pixels() + pixel] + caustic(g);
      }
  const LatticeLight light{lattice, scratch.lattice_light, cells};
  const float inv_samples = 1.0f / float(pixels.samples);
  for (int y = 0; y < job.h; ++y)
    for (int x = 0; x < job.w; ++x) {
      const size_t pixel = pixels.region.index(job.x + x, job.y + y);
      glm::vec3 c(0.0f);
      for (int l = 0; l < pixels.layer_count(); ++l) {
        const GSample& g = pixels.at(l, pixel);
        c += g.emitted;
        if (g.valid())
          c += g.throughput * modulation(g.surface, g.wo) * upsample_light(light, l, g, job.x + x, job.y + y);
      }
      out[size_t(y) * job.w + x] = c * inv_samples;
    }
}

}  // namespace igi
