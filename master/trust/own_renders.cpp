#include "trust/own_renders.h"

#include <cstdio>
#include <utility>

namespace igi {
namespace {

constexpr uint64_t kLogFirst = 5;  // repeated conditions are logged this often, then counted

}  // namespace

OwnRenders::OwnRenders(Scene scene, bool quiet) : quiet_(quiet), renderer_(std::move(scene)) {}

void OwnRenders::expect(const FrameSetup& frame, const RenderSettings& settings) {
  if (follows_workers_ || expected_.count(frame.frame_id)) return;
  if (expected_.size() >= kMaxExpected) return;  // frames expected far ahead wait for their turn
  expected_[frame.frame_id];
  renderer_.request(frame, settings);
}

bool OwnRenders::take_expected(uint64_t frame_id, std::optional<std::optional<uint64_t>>& answer) {
  auto expected = expected_.find(frame_id);
  if (expected == expected_.end()) return false;
  if (expected->second) answer = expected->second->hash;
  expected_.erase(expected);
  return true;
}

void OwnRenders::request(const FrameSetup& frame, const RenderSettings& settings) {
  if (!follows_workers_) renderer_.request(frame, settings);
}

// One it could not compute (the scene does not fit here, say) is left to a vote among the workers.
std::vector<OwnRenders::Hash> OwnRenders::take_hashes() {
  std::vector<Hash> hashes;
  for (MasterRenderer::Answer& a : renderer_.take()) {
    ++hash_frames_;
    hash_seconds_ += a.seconds;
    if (auto expected = expected_.find(a.frame_id); expected != expected_.end()) {
      expected->second = std::move(a);  // the frame is not added yet: take_expected() takes it
      continue;
    }
    if (!a.hash && ++hash_errors_ <= kLogFirst && !quiet_)
      std::fprintf(stderr, "igi-master: frame %llu: the master cannot compute its VPL-set hash (%s): its workers "
                   "vote on it\n", static_cast<unsigned long long>(a.frame_id), a.error.c_str());
    hashes.push_back({a.frame_id, a.hash});
  }
  return hashes;
}

void OwnRenders::render_tile(const FrameSetup& frame, const RenderSettings& settings, uint64_t job_id,
                             const TileJob& tile, PixelFormat format, const std::string& what, bool say) {
  if (say && (++tiles_logged_ <= kLogFirst || tiles_logged_ % 100 == 0))  // always said, never a flood
    std::fprintf(stderr, "igi-master: %s: the master renders it itself (%llu so far)\n", what.c_str(),
                 static_cast<unsigned long long>(tiles_logged_));
  what_[job_id] = what;
  renderer_.request_tile(frame, settings, job_id, tile, format);
}

std::string OwnRenders::take_what(uint64_t job_id) {
  auto it = what_.find(job_id);
  if (it == what_.end()) return "job " + std::to_string(job_id);
  std::string what = std::move(it->second);
  what_.erase(it);
  return what;
}

}  // namespace igi
