#include "frame_check.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <regex>

#include "image/metrics.h"
#include "lighting/lights.h"
#include "view/frame_plan.h"
#include "render/offline_render.h"
#include "render/scene_state.h"
#include "scene/accel.h"
#include "render/scene_state.h"
#include "scene/load_scene.h"

namespace igi::soak {

namespace fs = std::filesystem;

std::string frame_file(const std::string& dir, int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame-%04d.exr", frame);
  return (fs::path(dir) / name).string();
}

// As a worker holds the scene (worker/worker_session.cpp).
struct ReferenceRenderer::Prepared {
  std::unique_ptr<SceneState> state;
};

ReferenceRenderer::ReferenceRenderer(const RenderOptions& options, const CameraPath& path)
    : options_(options), path_(path), prepared_(new Prepared) {
  prepared_->state = std::make_unique<SceneState>(load_scene(options.scene));
}

ReferenceRenderer::~ReferenceRenderer() = default;

Image ReferenceRenderer::render(int i) const {
  SceneState& state = *prepared_->state;
  const FrameSetup f = plan_frame(options_, path_, state.scene(), i, false);  // as igi-master renders it
  state.set_pose(f.pose);
  FrameOptions frame_options;
  frame_options.tile_size = options_.tile_size;
  frame_options.threads = 2;
  return render_offline(state.context(), options_.settings, f, options_.samples, frame_options).image;
}

static void write_mismatch(const std::string& dir, int frame, const Image& image, const Image& reference) {
  const fs::path out = fs::path(dir) / "mismatch";
  fs::create_directories(out);
  char stem[32];
  std::snprintf(stem, sizeof stem, "frame-%04d", frame);
  write_image(image, (out / (std::string(stem) + ".exr")).string());
  write_image(reference, (out / (std::string(stem) + "-reference.exr")).string());
  if (image.width == reference.width && image.height == reference.height)
    write_image(abs_difference(image, reference), (out / (std::string(stem) + "-diff.png")).string(),
                ToneMapping{10.0f});
}

// Empty when identical; otherwise what differs first.
static std::string compare(const Image& image, const Image& reference) {
  if (image.width != reference.width || image.height != reference.height)
    return "size " + std::to_string(image.width) + "x" + std::to_string(image.height) + ", expected " +
           std::to_string(reference.width) + "x" + std::to_string(reference.height);
  size_t differing = 0, first = 0;
  for (size_t i = 0; i < image.pixels.size(); ++i)
    if (std::memcmp(&image.pixels[i], &reference.pixels[i], sizeof(glm::vec3)) != 0 && differing++ == 0) first = i;
  if (differing == 0) return "";
  char text[200];
  const glm::vec3 a = image.pixels[first], b = reference.pixels[first];
  std::snprintf(text, sizeof text, "%zu pixels differ, first (%zu, %zu): (%.9g, %.9g, %.9g) vs (%.9g, %.9g, %.9g)",
                differing, first % size_t(image.width), first / size_t(image.width), a.x, a.y, a.z, b.x, b.y, b.z);
  return text;
}

FrameVerdict check_frames(const std::string& dir, int frames, const ReferenceRenderer& reference) {
  FrameVerdict verdict;
  for (int i = 0; i < frames; ++i) {
    const std::string path = frame_file(dir, i);
    Image image;
    try {
      if (!fs::exists(path)) throw std::runtime_error("no file");
      image = read_image(path);
    } catch (const std::exception& e) {
      verdict.missing.push_back(i);
      if (verdict.missing.size() <= 10) verdict.notes.push_back("frame " + std::to_string(i) + " lost: " + path + ": " + e.what());
      continue;
    }
    const Image expected = reference.render(i);
    const std::string difference = compare(image, expected);
    if (difference.empty()) {
      ++verdict.identical;
      continue;
    }
    verdict.differing.push_back(i);
    write_mismatch(dir, i, image, expected);
    verdict.notes.push_back("frame " + std::to_string(i) + " differs from the single-process render: " + difference +
                            "; images in " + (fs::path(dir) / "mismatch").string());
  }
  if (verdict.missing.size() > 10)
    verdict.notes.push_back(std::to_string(verdict.missing.size() - 10) + " more frames lost, the last " +
                            std::to_string(verdict.missing.back()));
  const std::regex name(R"(frame-(\d+)\.exr)");
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::smatch m;
    const std::string file = entry.path().filename().string();
    if (file.rfind("frame", 0) != 0) continue;
    if (!std::regex_match(file, m, name) || std::stoi(m[1]) >= frames)
      verdict.notes.push_back("unexpected file " + entry.path().string());
  }
  return verdict;
}

}  // namespace igi::soak
