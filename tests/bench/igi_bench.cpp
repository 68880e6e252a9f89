// igi-bench: throughput of the IGI renderer against raw Embree on the same
// rays, frames per second, border overhead. Prints figures; asserts nothing.
//
//   igi-bench [--size WxH] [--frames F] [--vpls-per-set V] [--scenes a,b] [--tile T]
//   igi-bench --defaults [--scenes a,b] [--size WxH] [--frames F] [--aa S]
//
// --defaults: where the default frame's time and rays go, part by part
// (bench_defaults). Without it:
// Also: the same frame with 4x anti-aliasing by VPL groups (same VPLs), and
// the cost of progress reporting on a multi-pass render (render_offline).
// Tiles are T x T pixels, igi-render's and igi-master's default (64) unless
// given. The AA cost is also the median of per-pair ratios over F pairs of
// frames rendered alternately (plain, AA, plain, ...), which a load that
// comes and goes sways less than two medians taken one after the other.
//
// Every figure is the median over F frames. "cpu" columns divide by the CPU
// time the process actually received (the machine is shared), "wall" by
// elapsed time.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bench/bench_clock.h"
#include "methods/vpl_method.h"
#include "photons/caustic_settings.h"
#include "render/offline_render.h"
#include "render/frame_renderer.h"
#include "scene/load_scene.h"
#include "vpl/vpl_generator.h"

namespace igi {
namespace {

using bench::Clock;
using bench::median;

struct Timing {
  double wall, cpu;
  RayCounts rays;
};

Timing time_frames(const Method& method, const FrameSetup& frame, int border, int threads, int tile, int frames) {
  std::vector<double> wall, cpu;
  RayCounts rays;
  for (int f = 0; f < frames; ++f) {
    FrameOptions options;
    options.threads = threads;
    options.tile_size = tile;
    rays = RayCounts{};
    Clock start = Clock::now();
    render_frame(method, frame, border, options, rays);
    Clock d = Clock::now() - start;
    wall.push_back(d.wall);
    cpu.push_back(d.cpu);
  }
  return {median(wall), median(cpu), rays};
}

// A logged packet's valid lanes, each as a ray of its own (rtcOccluded1), as
// the renderer traced shadow rays from 2026-12-04 to 2026-12-07
// (methods/shadow_batch.cpp). Returns the rays traced.
size_t trace_one_at_a_time(const Accel& accel, RTCIntersectContext& context, const LoggedShadow& s) {
  size_t traced = 0;
  for (int k = 0; k < 16; ++k) {
    if (!s.valid[k]) continue;
    RTCRay r{s.rays.org_x[k], s.rays.org_y[k], s.rays.org_z[k], s.rays.tnear[k],
             s.rays.dir_x[k], s.rays.dir_y[k], s.rays.dir_z[k], 0.0f, s.rays.tfar[k], ~0u, 0u, 0u};
    rtcOccluded1(accel.handle(), &context, &r);
    ++traced;
  }
  return traced;
}

// Replays the logged packets through Embree alone, on one thread: incoherent
// as the renderer traces them (scene/accel.h), or with the coherent flag;
// shadow rays as 16-wide packets of one VPL and 16 pixels as the renderer
// traces them (methods/shadow_batch.cpp), or one at a time.
Timing time_replay(const Accel& accel, RayLog& log, int frames,
                   RTCIntersectContextFlags flags = RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, bool single_shadow = false) {
  std::vector<double> wall, cpu;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = flags;
  RayCounts rays;
  for (int f = 0; f < frames; ++f) {
    rays = RayCounts{};
    std::vector<LoggedPrimary> primary = log.primary;  // rays are overwritten by tracing
    std::vector<LoggedShadow> shadow = log.shadow;
    Clock start = Clock::now();
    for (LoggedPrimary& p : primary) rtcIntersect16(p.valid, accel.handle(), &context, &p.rays);
    if (single_shadow)
      for (const LoggedShadow& s : shadow) trace_one_at_a_time(accel, context, s);
    else
      for (LoggedShadow& s : shadow) rtcOccluded16(s.valid, accel.handle(), &context, &s.rays);
    Clock d = Clock::now() - start;
    wall.push_back(d.wall);
    cpu.push_back(d.cpu);
    for (const LoggedPrimary& p : log.primary) rays.primary += std::count(p.valid, p.valid + 16, -1);
    for (const LoggedShadow& s : log.shadow) rays.shadow += std::count(s.valid, s.valid + 16, -1);
  }
  return {median(wall), median(cpu), rays};
}

// Replays the shadow rays one at a time, as
// the packets they were logged in (16 pixels, one VPL), and as packets of
// one point each: what packets would gain in this scene.
void replay_breakdown(const Accel& accel, const RayLog& log) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);  // incoherent, as the renderer traces (scene/accel.h)
  std::vector<LoggedPrimary> primary = log.primary;
  std::vector<LoggedShadow> shadow = log.shadow;
  size_t np = 0, ns = 0;
  Clock t0 = Clock::now();
  for (LoggedPrimary& p : primary) rtcIntersect16(p.valid, accel.handle(), &context, &p.rays);
  Clock t1 = Clock::now();
  for (LoggedShadow& s : shadow) rtcOccluded16(s.valid, accel.handle(), &context, &s.rays);
  Clock t2 = Clock::now();
  for (const LoggedShadow& s : log.shadow) ns += trace_one_at_a_time(accel, context, s);
  Clock t3 = Clock::now();
  // The same rays in the one packet layout that no tiling can change: each
  // point's own rays (one origin, its set's VPLs), 16 to a packet, points in
  // the order the renderer first meets them.
  std::vector<LoggedShadow> by_point;
  {
    std::map<std::array<uint32_t, 3>, size_t> point_of;  // origin bits -> index in rays_of
    std::vector<std::vector<RTCRay>> rays_of;
    for (const LoggedShadow& s : log.shadow)
      for (int k = 0; k < 16; ++k) {
        if (!s.valid[k]) continue;
        const std::array<uint32_t, 3> key{std::bit_cast<uint32_t>(s.rays.org_x[k]), std::bit_cast<uint32_t>(s.rays.org_y[k]),
                                          std::bit_cast<uint32_t>(s.rays.org_z[k])};
        auto [it, fresh] = point_of.try_emplace(key, rays_of.size());
        if (fresh) rays_of.emplace_back();
        rays_of[it->second].push_back(RTCRay{s.rays.org_x[k], s.rays.org_y[k], s.rays.org_z[k], s.rays.tnear[k],
                                             s.rays.dir_x[k], s.rays.dir_y[k], s.rays.dir_z[k], 0.0f, s.rays.tfar[k],
                                             ~0u, 0u, 0u});
      }
    for (const std::vector<RTCRay>& rays : rays_of) {
      for (size_t first = 0; first < rays.size(); first += 16) {
        LoggedShadow& p = by_point.emplace_back();
        for (size_t k = 0; k < 16; ++k) {
          const RTCRay& r = rays[std::min(first + k, rays.size() - 1)];
          p.valid[k] = first + k < rays.size() ? -1 : 0;
          p.rays.org_x[k] = r.org_x; p.rays.org_y[k] = r.org_y; p.rays.org_z[k] = r.org_z;
          p.rays.dir_x[k] = r.dir_x; p.rays.dir_y[k] = r.dir_y; p.rays.dir_z[k] = r.dir_z;
          p.rays.tnear[k] = r.tnear; p.rays.tfar[k] = r.tfar; p.rays.mask[k] = r.mask;
          p.rays.time[k] = 0.0f; p.rays.flags[k] = 0u;
        }
      }
    }
  }
  Clock t4 = Clock::now();
  for (LoggedShadow& s : by_point) rtcOccluded16(s.valid, accel.handle(), &context, &s.rays);
  Clock t5 = Clock::now();
  for (const LoggedPrimary& p : log.primary) np += std::count(p.valid, p.valid + 16, -1);
  std::printf("raw Embree per cpu-s: primary 16-wide %.1f Mrays/s, shadow 16-wide %.1f, shadow 1-wide %.1f, "
              "shadow 16-wide of one point each %.1f (%.1f rays a packet)\n",
              np * 1e-6 / (t1 - t0).cpu, ns * 1e-6 / (t2 - t1).cpu, ns * 1e-6 / (t3 - t2).cpu,
              ns * 1e-6 / (t5 - t4).cpu, double(ns) / std::max<size_t>(1, by_point.size()));
}

// Paths per set that give about `target` VPLs per set in this scene.
int paths_for_vpls(const SceneContext& ctx, RenderSettings s, int target) {
  s.paths_per_set = 64;
  VplSets sets = generate_vpls(ctx, s, 1);
  double per_path = double(sets.vpls.size()) / (64.0 * sets.set_count());
  return std::max(1, int(std::lround(target / per_path)));
}

// Median over `frames` pairs of the 2-thread frame time of b over a, the two
// rendered alternately.
double paired_ratio(const Method& a, const Method& b, const FrameSetup& frame, int border, int tile, int frames) {
  std::vector<double> ratios;
  for (int f = 0; f < frames; ++f) {
    const Timing ta = time_frames(a, frame, border, 2, tile, 1);
    const Timing tb = time_frames(b, frame, border, 2, tile, 1);
    ratios.push_back(tb.wall / ta.wall);
  }
  return median(ratios);
}

void bench_scene(const std::string& name, int width, int height, int frames, int vpls_per_set, int tile) {
  Scene scene = load_scene(name);
  Clock build_start = Clock::now();
  Accel accel(scene);
  double build = (Clock::now() - build_start).wall;
  LightSet lights(scene);
  SceneContext ctx{scene, accel, lights};
  RenderSettings settings;
  settings.method = MethodKind::Igi;
  settings.clamp = 0.05f;
  settings.compensation_samples = 0;
  settings.aa_samples = 1;
  settings.paths_per_set = paths_for_vpls(ctx, settings, vpls_per_set);
  VplMethod method(ctx, settings);
  FrameSetup frame;
  frame.camera = scene.camera_or_auto();
  frame.width = width;
  frame.height = height;
  frame.seed = 1;
  method.begin_frame(frame);
  const int border = tile_border(settings);
  std::printf("\n== %s: %zu triangles (BVH build %.2f s), %dx%d, M=%d paths/set -> %.1f VPLs/set, tiles %dx%d border %d\n",
              name.c_str(), scene.triangles.size(), build, width, height, settings.paths_per_set,
              double(method.vpls().vpls.size()) / method.vpls().set_count(), tile, tile, border);

  RayLog log;
  method.record_rays(&log);
  RayCounts counted;
  FrameOptions one;
  one.threads = 1;
  one.tile_size = tile;
  render_frame(method, frame, border, one, counted);
  method.record_rays(nullptr);
  Timing raw = time_replay(accel, log, frames);
  replay_breakdown(accel, log);

  std::printf("%-26s %9s %9s %10s %10s %8s\n", "", "frame ms", "fps", "Mrays/s", "Mrays/cpu-s", "rays/px");
  auto row = [&](const char* label, const Timing& t) {
    double mr = t.rays.total() * 1e-6;
    std::printf("%-26s %9.1f %9.2f %10.2f %10.2f %8.1f\n", label, 1e3 * t.wall, 1.0 / t.wall, mr / t.wall,
                mr / t.cpu, double(t.rays.total()) / (width * height));
  };
  Timing t1 = time_frames(method, frame, border, 1, tile, frames);
  Timing t2 = time_frames(method, frame, border, 2, tile, frames);
  row("igi, 1 thread", t1);
  row("igi, 2 threads", t2);
  row("raw Embree, same rays, 1t", raw);
  double igi_rate = (t1.rays.primary + t1.rays.shadow) / t1.cpu;
  double raw_rate = (raw.rays.primary + raw.rays.shadow) / raw.cpu;
  std::printf("igi / raw Embree throughput (primary + shadow, per cpu-s, 1 thread): %.0f %%\n", 100.0 * igi_rate / raw_rate);
  const Timing raw1 = time_replay(accel, log, frames, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, true);
  std::printf("igi / raw Embree with the shadow rays one at a time (igi traces packets): %.0f %%\n",
              100.0 * igi_rate / ((raw1.rays.primary + raw1.rays.shadow) / raw1.cpu));
  std::printf("2-thread speed-up: %.2fx\n", t1.wall / t2.wall);
  const Timing coherent = time_replay(accel, log, frames, RTC_INTERSECT_CONTEXT_FLAG_COHERENT);
  std::printf("the same packets with Embree's coherent flag: %.2f against %.2f Mrays/cpu-s incoherent (%.2fx)\n",
              coherent.rays.total() * 1e-6 / coherent.cpu, raw.rays.total() * 1e-6 / raw.cpu, raw.cpu / coherent.cpu);

  // Border overhead: the same frame without the filter border.
  Timing nb = time_frames(method, frame, 0, 1, tile, frames);
  std::printf("border overhead (%dx%d tiles): %+.1f %% primary rays, %+.1f %% frame time (1 thread)\n", tile, tile,
              100.0 * (double(t1.rays.primary) / nb.rays.primary - 1.0), 100.0 * (t1.cpu / nb.cpu - 1.0));

  // Anti-aliasing by VPL groups: the same light paths split into 4 groups.
  RenderSettings aa = settings;
  aa.aa_samples = 4;
  aa.paths_per_set = std::max(settings.paths_per_set, aa.aa_samples);
  VplMethod aa_method(ctx, aa);
  aa_method.begin_frame(frame);
  Timing a1 = time_frames(aa_method, frame, border, 1, tile, frames);
  Timing a2 = time_frames(aa_method, frame, border, 2, tile, frames);
  row("igi 4x AA, 1 thread", a1);
  row("igi 4x AA, 2 threads", a2);
  std::printf("4x AA costs %.2fx the frame time of 1x (2 threads), %.2fx the rays\n", a2.wall / t2.wall,
              double(a2.rays.total()) / double(t2.rays.total()));
  std::printf("4x AA costs %.2fx the frame time of 1x (2 threads, median of %d frame pairs rendered alternately)\n",
              paired_ratio(method, aa_method, frame, border, tile, frames), frames);
}

// A multi-pass render with and without a progress callback (igi-render's
// --quiet): the callback's thread must not hold the passes back.
void bench_progress(const std::string& name, int width, int height, int frames) {
  Scene scene = load_scene(name);
  Accel accel(scene);
  LightSet lights(scene);
  RenderSettings settings;  // the defaults, as igi-render --spp 20 --vpl-paths 6 renders
  settings.paths_per_set = 6;
  FrameSetup frame;
  frame.camera = scene.camera_or_auto();
  frame.width = width;
  frame.height = height;
  frame.seed = 1;
  std::vector<double> quiet, reporting;
  for (int f = 0; f < frames; ++f) {
    FrameOptions options;
    quiet.push_back(render_offline({scene, accel, lights}, settings, frame, 20, options).seconds);
    options.progress = [](float) {};
    reporting.push_back(render_offline({scene, accel, lights}, settings, frame, 20, options).seconds);
  }
  std::printf("\n== progress: %s %dx%d, igi, 20 passes: %.3f s quiet, %.3f s with progress (%.2fx)\n", name.c_str(),
              width, height, median(quiet), median(reporting), median(reporting) / median(quiet));
}

// The default frame, part by part (--defaults): igi-render's defaults on
// each scene (caustics where it has mirrors, glass or sharp GGX, as
// igi-render chooses), one thread, F frames of one pass each (a new seed
// each); each part's share of the frame's time, its rays a pixel and rate,
// and raw Embree's rate on the frame's camera and VPL shadow rays beside them.
void bench_defaults(const std::vector<std::string>& scenes, int width, int height, int frames, int tile, int aa) {
  for (const std::string& name : scenes) {
    Scene scene = load_scene(name);
    Accel accel(scene);
    LightSet lights(scene);
    SceneContext ctx{scene, accel, lights};
    RenderSettings settings;  // igi-render's defaults
    settings.method = MethodKind::Igi;
    settings.caustics = photons::has_specular_surfaces(scene, settings.glossy_threshold);
    if (aa > 0) settings.aa_samples = aa;
    VplMethod method(ctx, settings);
    FrameSetup frame;
    frame.camera = scene.camera_or_auto();
    frame.width = width;
    frame.height = height;
    const int border = tile_border(settings);
    FrameOptions one;
    one.threads = 1;
    one.tile_size = tile;
    // Unrecorded frames first: what the timers cost.
    std::vector<double> plain;
    for (int f = 0; f < frames; ++f) {
      frame.seed = uint32_t(f + 1);
      RayCounts rays;
      Clock start = Clock::now();
      method.begin_frame(frame);
      render_frame(method, frame, border, one, rays);
      plain.push_back((Clock::now() - start).cpu);
    }
    FrameParts parts;
    method.record_parts(&parts);
    RayCounts rays;
    double total = 0.0;
    for (int f = 0; f < frames; ++f) {
      frame.seed = uint32_t(f + 1);
      Clock start = Clock::now();
      method.begin_frame(frame);
      render_frame(method, frame, border, one, rays);
      total += (Clock::now() - start).wall;
    }
    method.record_parts(nullptr);
    // One more frame with its camera and VPL shadow rays logged: raw Embree's rate on them.
    RayLog log;
    method.record_rays(&log);
    RayCounts logged;
    render_frame(method, frame, border, one, logged);
    method.record_rays(nullptr);
    const Timing raw = time_replay(accel, log, 1);
    const double pixels = double(width) * height * frames;
    const RayCounts setup_rays = parts.rays[size_t(FramePart::Vpls)];
    std::printf("\n== %s: igi defaults (aa %d, %d paths a set, compensation %d, caustics %s), %dx%d, 1 thread, %d frames\n",
                name.c_str(), settings.aa_samples, settings.paths_per_set, settings.compensation_samples,
                settings.caustics ? "on" : "off", width, height, frames);
    std::printf("frame %.1f ms (%.1f ms with the part timers), %.1f rays a pixel (%.1f in the frame's tiles)\n",
                median(plain) * 1e3, total / frames * 1e3, (rays.total() + setup_rays.total()) / pixels,
                rays.total() / pixels);
    std::printf("raw Embree on the frame's camera rays and its packets of shadow rays (VPLs, exact lights, compensation): %.2f Mrays/cpu-s\n",
                raw.rays.total() * 1e-6 / raw.cpu);
    std::printf("%-40s %9s %7s %12s %12s\n", "part", "ms/frame", "share", "rays/pixel", "Mrays/s");
    double counted = 0.0;
    for (size_t i = 0; i < size_t(FramePart::Count); ++i) {
      const double sec = parts.seconds[i];
      counted += sec;
      const double r = double(parts.rays[i].total());
      std::printf("%-40s %9.1f %6.1f%% %12.2f %12.2f\n", frame_part_name(FramePart(i)), sec / frames * 1e3,
                  100.0 * sec / total, r / pixels, sec > 0.0 ? r * 1e-6 / sec : 0.0);
    }
    std::printf("%-40s %9.1f %6.1f%%\n", "the rest (scheduling, combine)", (total - counted) / frames * 1e3,
                100.0 * (total - counted) / total);
  }
}

}  // namespace
}  // namespace igi

int main(int argc, char** argv) {
  int width = 640, height = 480, frames = 5, vpls = 16, tile = 64, aa = 0;
  std::vector<std::string> scenes = {"cornell", "cornell-blob"};
  bool defaults = false, scenes_given = false;
  std::vector<std::string> args;  // option, value, option, value ...
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--defaults") defaults = true;
    else args.push_back(argv[i]);
  }
  for (size_t i = 0; i + 1 < args.size(); i += 2) {
    const std::string& a = args[i];
    const std::string& v = args[i + 1];
    if (a == "--size") std::sscanf(v.c_str(), "%dx%d", &width, &height);
    else if (a == "--frames") frames = std::stoi(v);
    else if (a == "--aa") aa = std::stoi(v);
    else if (a == "--vpls-per-set") vpls = std::stoi(v);
    else if (a == "--tile") tile = std::stoi(v);
    else if (a == "--scenes") {
      scenes_given = true;
      scenes.clear();
      for (size_t p = 0, q; p <= v.size(); p = q + 1) {
        q = v.find(',', p);
        if (q == std::string::npos) q = v.size();
        scenes.push_back(v.substr(p, q - p));
      }
    }
  }
  igi::enable_flush_to_zero();
  if (defaults) {
    if (!scenes_given) scenes = {"cornell", "glossy", "rooms", "glass"};
    igi::bench_defaults(scenes, width, height, frames, tile, aa);
    return 0;
  }
  for (const std::string& s : scenes) igi::bench_scene(s, width, height, frames, vpls, tile);
  igi::bench_progress("cornell", width, height, frames);
  return 0;
}
