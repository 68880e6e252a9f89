#include "fuzz/harness.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <exception>

#include "image/frame_buffer.h"
#include "lighting/lights.h"
#include "protocol/codec.h"
#include "protocol/pixels.h"
#include "scene/gltf_loader.h"
#include "viewer/display_messages.h"

namespace igi::fuzz {
namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

bool starts_with(const std::string& text, const std::string& prefix) { return text.rfind(prefix, 0) == 0; }

std::string check_camera(const Camera& camera, const char* which) {
  const bool ok = finite(camera.position) && finite(camera.forward) && finite(camera.up) &&
                  std::isfinite(camera.vfov);
  if (!ok)
    return std::string(which) + " camera is not finite";
  return {};
}

std::string check_lights(const Scene& scene) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const PunctualLight& light = scene.lights[i];
    if (!finite(light.position) || !finite(light.direction) || !finite(light.intensity))
      return "punctual light " + std::to_string(i) + " is not finite";
  }
  const LightSet lights(scene);
  if (lights.empty()) return "the light set is empty, yet the scene validated";
  return {};
}

// Every texture is looked up where its vertices map, as shading would.
std::string check_textures(const Scene& scene) {
  for (size_t i = 0; i < scene.textures.size(); ++i) {
    const Texture& t = scene.textures[i];
    const size_t held = t.bytes.empty() ? t.texels.size() : t.bytes.size() / 4;
    if (t.width <= 0 || t.height <= 0 || held != size_t(t.width) * size_t(t.height))
      return "texture " + std::to_string(i) + " has " + std::to_string(held) + " texels for " +
             std::to_string(t.width) + " x " + std::to_string(t.height);
    for (size_t v = 0; v < scene.uvs.size() && v < 4096; ++v) t.sample(scene.uvs[v]);
  }
  return {};
}

std::string check_loaded(const LoadedScene& loaded) {
  const Scene& scene = loaded.scene;
  const std::string prefix = std::string(kSceneInputName) + ": ";
  for (const std::string& warning : loaded.warnings)
    if (!starts_with(warning, prefix)) return "warning does not name the input: " + warning;
  try {
    scene.validate();
  } catch (const SceneError& e) {
    return std::string("a loaded scene fails validate(): ") + e.what();
  }
  if (scene.camera)
    if (std::string error = check_camera(*scene.camera, "the file's"); !error.empty()) return error;
  if (std::string error = check_camera(scene.camera_or_auto(), "the scene's"); !error.empty()) return error;
  if (std::string error = check_lights(scene); !error.empty()) return error;
  return check_textures(scene);
}

}  // namespace

// The master's in-place path for TileResults (decode_tile_result, then
// copy_tile_pixels into a frame) must accept exactly what decode() accepts,
// with the same error, and copy the same pixels and surfaces.
static std::string check_tile_result_view(std::span<const uint8_t> bytes, const protocol::DecodeResult& decoded) {
  if (!protocol::is_tile_result(bytes)) return {};
  std::string error;
  const std::optional<protocol::TileResultView> view = protocol::decode_tile_result(bytes, error);
  if (!view) {
    if (decoded.message) return "decode_tile_result refused what decode accepted: " + error;
    return error == decoded.error ? "" : "decode_tile_result's error differs: " + error + " / " + decoded.error;
  }
  const TileJob& t = view->fields.tile;
  FrameBuffer frame(t.w, t.h, view->fields.pixel_format);
  error = protocol::copy_tile_pixels(*view, frame.pixel(0, 0), frame.row_bytes());
  if (!decoded.message) return error == decoded.error ? "" : "the view accepted, the copy said: " + error + " / " + decoded.error;
  if (!error.empty()) return "copy_tile_pixels refused what decode accepted: " + error;
  const auto& pixels = std::get<protocol::TileResult>(*decoded.message).pixels;
  const Image image = frame.to_image();
  if (!std::equal(pixels.begin(), pixels.end(), image.pixels.begin(), image.pixels.end(), [](glm::vec3 a, glm::vec3 b) {
        return std::memcmp(&a, &b, sizeof a) == 0;
      }))
    return "the copied pixels differ from the decoded ones";
  const auto& surfaces = std::get<protocol::TileResult>(*decoded.message).surfaces;
  if (view->surface_bytes.empty() != surfaces.empty()) return "the view and decode disagree on the surfaces' presence";
  if (surfaces.empty()) return {};
  std::vector<PixelSurface> copied(surfaces.size());
  protocol::copy_tile_surfaces(*view, copied.data(), size_t(t.w));
  if (std::memcmp(copied.data(), surfaces.data(), surfaces.size() * sizeof(PixelSurface)) != 0)
    return "the copied surfaces differ from the decoded ones";
  return {};
}

std::string check_decode(std::span<const uint8_t> bytes) {
  const protocol::DecodeResult first = protocol::decode(bytes);
  if (std::string error = check_tile_result_view(bytes, first); !error.empty()) return error;
  if (!first.message) return first.error.empty() ? "decode failed without an error message" : "";
  if (!first.error.empty()) return "decode succeeded with an error: " + first.error;
  const std::vector<uint8_t> encoded = protocol::encode(*first.message);
  // A packed block has many encodings of the same bytes (neither zstd frames
  // nor lz4 blocks are canonical), and a shared-exponent colour many words (a
  // larger exponent with smaller mantissas): such a tile re-encodes to the
  // same pixels, then to stable bytes.
  const auto* tile = std::get_if<protocol::TileResult>(&*first.message);
  const bool loose = tile && (tile->pixel_codec != protocol::PixelCodec::Raw || tile->pixel_format == PixelFormat::Rgb9e5);
  if (!loose && !std::equal(encoded.begin(), encoded.end(), bytes.begin(), bytes.end()))
    return "re-encoding a decoded message gave other bytes (" + std::to_string(encoded.size()) + " vs " +
           std::to_string(bytes.size()) + ")";
  const protocol::DecodeResult second = protocol::decode(encoded);
  if (!second.message) return "a re-encoded message does not decode: " + second.error;
  if (second.message->index() != first.message->index()) return "a re-encoded message changed its type";
  if (loose) {
    const auto& a = tile->pixels;
    const auto& b = std::get<protocol::TileResult>(*second.message).pixels;
    if (a.size() != b.size() || std::memcmp(a.data(), b.data(), a.size() * sizeof(glm::vec3)) != 0)
      return "a re-encoded packed or rgb9e5 tile has other pixels";
    if (protocol::encode(*second.message) != encoded) return "re-encoding a packed or rgb9e5 tile twice gave other bytes";
  }
  return {};
}

std::string check_display_decode(std::span<const uint8_t> bytes) {
  const display::Decoded first = display::decode(bytes);
  if (!first.message) return first.error.empty() ? "display decode failed without an error message" : "";
  if (!first.error.empty()) return "display decode succeeded with an error: " + first.error;
  const std::vector<uint8_t> encoded = display::encode(*first.message);
  if (!std::equal(encoded.begin(), encoded.end(), bytes.begin(), bytes.end()))
    return "re-encoding a decoded display message gave other bytes (" + std::to_string(encoded.size()) + " vs " +
           std::to_string(bytes.size()) + ")";
  const display::Decoded second = display::decode(encoded);
  if (!second.message || second.message->index() != first.message->index())
    return "a re-encoded display message does not decode as itself: " + second.error;
  const auto* frame = std::get_if<display::Frame>(&*first.message);
  if (frame && frame->codec == display::FrameCodec::Zstd) {  // H.264 needs its stream: video_codec.h's tests
    std::string error;
    const std::optional<std::vector<uint8_t>> rgb = display::unpack_pixels(*frame, error);
    if (rgb && rgb->size() != size_t(frame->width) * size_t(frame->height) * 3)
      return "a frame's pixels unpacked to " + std::to_string(rgb->size()) + " bytes, not its size";
    if (!rgb && error.empty()) return "a frame's pixels were refused without an error message";
  }
  return {};
}

std::string check_scene(std::span<const uint8_t> bytes) {
  try {
    return check_loaded(load_gltf_memory(bytes, kSceneInputName));
  } catch (const SceneError& e) {
    const std::string prefix = std::string(kSceneInputName) + ": ";
    return starts_with(e.what(), prefix) ? "" : std::string("error does not name the input: ") + e.what();
  } catch (const std::exception& e) {
    return std::string("unexpected exception (not SceneError): ") + e.what();
  }
}

}  // namespace igi::fuzz
