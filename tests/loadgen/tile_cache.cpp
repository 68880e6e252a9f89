#include "tile_cache.h"

#include <cstring>
#include <stdexcept>

#include "render/frame_job.h"
#include "protocol/codec.h"
#include "protocol/pixels.h"
#include "sampling/content_hash.h"
#include "scene/load_scene.h"

namespace igi::loadgen {
namespace {

// Where a TileResult's fields sit (protocol/codec.cpp writes them in declaration order
// after the 8-byte header); checked against the decoder the first time a tile is made.
constexpr size_t kFrameIdAt = 8, kJobIdAt = 16, kTileAt = 24, kHashAt = 48, kPixelsAt = 90;

void put_u64(uint8_t* at, uint64_t v) {
  for (int i = 0; i < 8; ++i) at[i] = uint8_t(v >> (8 * i));
}

void put_i32(uint8_t* at, int32_t v) {
  for (int i = 0; i < 4; ++i) at[i] = uint8_t(uint32_t(v) >> (8 * i));
}

}  // namespace

glm::vec3 expected_pixel(int x, int y) {
  return {float(x % 2048) / 1024.0f, float(y % 2048) / 1024.0f, 0.25f + 0.125f * float((x + y) % 4)};
}

glm::vec3 TileCache::pixel(int x, int y) const {
  if (!picture_) return expected_pixel(x, y);
  if (x >= picture_->width || y >= picture_->height)
    throw std::runtime_error("loadgen: the picture is " + std::to_string(picture_->width) + "x" +
                             std::to_string(picture_->height) + ", smaller than the frame");
  return picture_->at(x, y);
}

glm::vec3 TileCache::sent_pixel(int x, int y, PixelFormat format) const {
  protocol::TileResult r;
  r.tile = {0, 0, 1, 1, 0};
  r.pixel_format = format;
  r.pixels = {pixel(x, y)};
  protocol::wire_pixels(r.pixels, format);
  const protocol::DecodeResult d = protocol::decode(protocol::encode(r));
  if (!d.message) throw std::runtime_error("loadgen: a pixel of the picture does not travel: " + d.error);
  return std::get<protocol::TileResult>(*d.message).pixels[0];
}

bool TileCache::can_poison(PixelFormat format, protocol::PixelCodec codec) {
  return format != PixelFormat::Rgb9e5 && codec == protocol::PixelCodec::Raw;
}

const std::vector<uint8_t>& TileCache::encoded(const TileJob& t, PixelFormat format, protocol::PixelCodec codec) {
  const Key key{t.x, t.y, t.w, t.h, t.border, int(format), int(codec)};
  std::lock_guard lock(mutex_);
  auto it = tiles_.find(key);
  if (it != tiles_.end()) return *it->second;
  protocol::TileResult r;
  r.tile = t;
  r.render_seconds = 0.001f;
  r.rays = {uint64_t(t.w) * t.h, 0, 0};
  r.pixel_format = format;
  r.pixel_codec = codec;
  for (int y = 0; y < t.h; ++y)
    for (int x = 0; x < t.w; ++x) r.pixels.push_back(pixel(t.x + x, t.y + y));
  r.nonfinite_pixels = protocol::wire_pixels(r.pixels, format);
  auto bytes = std::make_unique<std::vector<uint8_t>>(protocol::encode(r));
  // The offsets above must still be the codec's: patch a copy and decode it.
  const TileJob moved{t.x + 1, t.y, t.w, t.h, t.border};
  zmq::message_t probe = answer(*bytes, 7, 9, 11, moved);
  protocol::DecodeResult d = protocol::decode({probe.data<uint8_t>(), probe.size()});
  const auto* back = d.message ? std::get_if<protocol::TileResult>(&*d.message) : nullptr;
  if (!back || back->frame_id != 7 || back->job_id != 9 || back->frame_state_hash != 11 || back->tile.x != t.x + 1)
    throw std::logic_error("loadgen: the TileResult layout changed (protocol/codec.cpp): " + d.error);
  if (can_poison(format, codec)) {
    poison(probe, format);
    d = protocol::decode({probe.data<uint8_t>(), probe.size()});
    if (d.message || d.error.find("pixel 0 is (nan") == std::string::npos)
      throw std::logic_error("loadgen: the TileResult's pixels moved (protocol/codec.cpp): " + d.error);
  }
  return *tiles_.emplace(key, std::move(bytes)).first->second;
}

const std::vector<uint8_t>& TileCache::bomb() {
  std::lock_guard lock(mutex_);
  if (!bomb_.empty()) return bomb_;
  protocol::TileResult r;
  r.tile = {0, 0, kBombSide, kBombSide, 0};
  r.pixel_format = PixelFormat::Float32;
  r.pixel_codec = protocol::PixelCodec::Zstd;
  r.pixels.assign(size_t(kBombSide) * kBombSide, glm::vec3(0.0f));
  r.surfaces.assign(size_t(kBombSide) * kBombSide, PixelSurface{});
  bomb_ = protocol::encode(r);
  return bomb_;
}

zmq::message_t TileCache::answer(const std::vector<uint8_t>& encoded, uint64_t frame_id, uint64_t job_id,
                                 uint64_t frame_state_hash, const TileJob& claimed) {
  zmq::message_t m(encoded.data(), encoded.size());
  uint8_t* bytes = m.data<uint8_t>();
  put_u64(bytes + kFrameIdAt, frame_id);
  put_u64(bytes + kJobIdAt, job_id);
  const int32_t tile[5] = {claimed.x, claimed.y, claimed.w, claimed.h, claimed.border};
  for (int i = 0; i < 5; ++i) put_i32(bytes + kTileAt + 4 * i, tile[i]);
  put_u64(bytes + kHashAt, frame_state_hash);
  return m;
}

void TileCache::poison(zmq::message_t& answer, PixelFormat format) {
  if (format == PixelFormat::Rgb9e5) throw std::logic_error("loadgen: a shared-exponent pixel cannot be NaN");
  uint8_t* first = answer.data<uint8_t>() + kPixelsAt;
  if (format == PixelFormat::Float16) {
    const uint16_t nan = 0x7e00;
    std::memcpy(first, &nan, 2);
  } else {
    const uint32_t nan = 0x7fc00000u;
    std::memcpy(first, &nan, 4);
  }
}

uint64_t TileCache::frame_hash(const FrameSetup& frame, const RenderSettings& settings) {
  const std::vector<uint8_t> setup = protocol::encode(protocol::FrameSetupMsg{frame, settings});
  const uint64_t key = content_hash(setup.data(), setup.size());
  std::lock_guard lock(hash_mutex_);
  if (auto it = hashes_.find(key); it != hashes_.end()) return it->second;
  if (!scene_) scene_ = std::make_unique<SceneState>(load_scene("cornell"));
  scene_->set_pose(frame.pose);
  FrameJob job(scene_->context(), settings);  // as a worker makes and begins its frames (render/frame_job.h)
  job.begin(frame);
  const uint64_t hash = job.state_hash();
  if (hashes_.size() >= 256) hashes_.erase(hashes_.begin());
  hashes_[key] = hash;
  return hash;
}

}  // namespace igi::loadgen
