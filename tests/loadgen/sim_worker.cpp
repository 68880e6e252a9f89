#include "sim_worker.h"

#include <algorithm>

#include "build_id.h"
#include "protocol/codec.h"
#include "protocol/socket.h"

namespace igi::loadgen {
namespace {

constexpr size_t kFramesKept = 8;
constexpr auto kIdleTick = std::chrono::milliseconds(20);

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
}

bool contains(const TileJob& t, std::pair<int, int> pixel) {
  return pixel.first >= t.x && pixel.first < t.x + t.w && pixel.second >= t.y && pixel.second < t.y + t.h;
}

}  // namespace

SimWorker::SimWorker(zmq::context_t& context, SimConnection connection, SimBehaviour behaviour, TileCache& tiles,
                     Clock::time_point start)
    : context_(context), connection_(std::move(connection)), behaviour_(behaviour), tiles_(tiles), start_(start) {
  lanes_.assign(size_t(std::max(1, behaviour_.threads)), start);
  if (connection_.curve && !behaviour_.key_file.empty())
    connection_.curve->own = protocol::read_secret_key_file(behaviour_.key_file);
}

double SimWorker::since_start(Clock::time_point now) const {
  return std::chrono::duration<double>(now - start_).count();
}

bool SimWorker::stalled(Clock::time_point now) const {
  const double t = since_start(now);
  return t >= behaviour_.stall_from && t < behaviour_.stall_until;
}

zmq::socket_t* SimWorker::socket(Clock::time_point now) {
  return socket_ && !stalled(now) ? socket_.get() : nullptr;
}

void SimWorker::connect(Clock::time_point now) {
  socket_ = std::make_unique<zmq::socket_t>(context_, zmq::socket_type::dealer);
  protocol::configure(*socket_);
  if (connection_.curve) protocol::make_curve_client(*socket_, *connection_.curve);
  socket_->connect(connection_.endpoint);
  welcome_.reset();
  frames_.clear();
  due_.clear();
  std::fill(lanes_.begin(), lanes_.end(), now);
  last_heard_ = now;
  ++outcome_.connections;
  send(protocol::Hello{igi::build_id(), "simulated", uint32_t(std::max(1, behaviour_.threads))}, now);
}

void SimWorker::disconnect() {
  socket_.reset();  // linger 0: gone at once, like a killed process's connection
  welcome_.reset();
  due_.clear();
}

void SimWorker::send(const protocol::Message& m, Clock::time_point now) {
  if (socket_ && protocol::try_send(*socket_, m)) last_sent_ = now;
}

void SimWorker::on_readable(Clock::time_point now) {
  while (socket_) {
    std::optional<protocol::Received> got = protocol::receive(*socket_, 0, false);
    if (!got) return;
    last_heard_ = now;
    if (got->message) handle(*got->message, now);
  }
}

void SimWorker::handle(const protocol::Message& m, Clock::time_point now) {
  if (auto* w = std::get_if<protocol::Welcome>(&m)) {
    welcome_ = *w;
    outcome_.welcomed = true;
  } else if (auto* f = std::get_if<protocol::FrameSetupMsg>(&m)) {
    frames_[f->frame.frame_id] = *f;
    while (frames_.size() > kFramesKept) frames_.erase(frames_.begin());
  } else if (auto* j = std::get_if<protocol::TileJobMsg>(&m)) {
    take_job(*j, now);
  } else if (auto* bye = std::get_if<protocol::Bye>(&m)) {
    outcome_.last_bye = bye->reason;
    if (bye->kind == protocol::ByeKind::Quarantined) outcome_.quarantined_at = since_start(now);
    (bye->kind == protocol::ByeKind::Quarantined ? outcome_.quarantined : outcome_.said_bye) = true;
    disconnect();
    finished_ = true;
  } else if (std::holds_alternative<protocol::Refuse>(m)) {
    outcome_.refused = true;
    disconnect();
    finished_ = true;
  }
}

// One tile at a time per lane: it is done tile_seconds after its lane is free.
void SimWorker::take_job(const protocol::TileJobMsg& job, Clock::time_point now) {
  if (behaviour_.hoard) return;
  auto lane = std::min_element(lanes_.begin(), lanes_.end());
  const Clock::time_point begin = std::max(now, *lane);
  *lane = begin + seconds(behaviour_.tile_seconds);
  due_.push_back({*lane, job.frame_id, job.job_id, job.tile});
}

void SimWorker::send_answer(const Due& due) {
  auto frame = frames_.find(due.frame_id);
  if (frame == frames_.end() || !welcome_) return;  // a frame we were not told about: a real worker drops it too
  const PixelFormat format = welcome_->pixel_format;
  const std::vector<uint8_t>& encoded = tiles_.encoded(due.tile, format, welcome_->pixel_codec);
  ++answers_;
  TileJob claimed = due.tile;
  if (behaviour_.wrong_tile_every > 0 && answers_ % uint64_t(behaviour_.wrong_tile_every) == 0)
    claimed.x = claimed.x >= claimed.w ? claimed.x - claimed.w : claimed.x + claimed.w;  // a neighbour's place
  const uint64_t hash = tiles_.frame_hash(frame->second.frame, frame->second.settings) + behaviour_.hash_offset;
  zmq::message_t message = TileCache::answer(encoded, due.frame_id, due.job_id, hash, claimed);
  const bool nan = (behaviour_.nan_every > 0 && answers_ % uint64_t(behaviour_.nan_every) == 0) ||
                   (behaviour_.poison_pixel && contains(due.tile, *behaviour_.poison_pixel));
  if (nan) TileCache::poison(message, format);
  if (behaviour_.truncate_every > 0 && answers_ % uint64_t(behaviour_.truncate_every) == 0)
    message = zmq::message_t(message.data<uint8_t>(), message.size() - 5);  // cut inside the pixels
  if (socket_->send(message, zmq::send_flags::dontwait)) ++outcome_.answers;
}

// Results for job ids far above any the master issues, for its newest frame.
Clock::time_point SimWorker::flood(Clock::time_point now) {
  const auto period = seconds(1.0 / behaviour_.flood_per_second);
  if (!next_flood_) next_flood_ = now;
  const uint64_t frame_id = frames_.empty() ? 0 : frames_.rbegin()->first;
  const std::vector<uint8_t>& bomb = tiles_.bomb();
  for (; *next_flood_ <= now && socket_; *next_flood_ += period) {
    zmq::message_t m = TileCache::answer(bomb, frame_id, (uint64_t(1) << 40) + outcome_.flooded, 0,
                                         TileJob{0, 0, TileCache::kBombSide, TileCache::kBombSide, 0});
    if (!socket_->send(m, zmq::send_flags::dontwait)) continue;
    if (outcome_.flooded++ == 0) outcome_.first_flood_at = since_start(now);
  }
  return *next_flood_;
}

Clock::time_point SimWorker::tick(Clock::time_point now) {
  Clock::time_point next = now + kIdleTick;
  if (finished_) return next;
  const double t = since_start(now);
  if (!socket_ && !dead_ && t >= behaviour_.join_at) connect(now);
  if (!socket_ && !dead_) return std::min(next, start_ + seconds(behaviour_.join_at));
  if (socket_ && behaviour_.die_at >= 0 && t >= behaviour_.die_at && !dead_) {
    dead_ = true;
    disconnect();
    if (behaviour_.rejoin_after >= 0) rejoin_at_ = now + seconds(behaviour_.rejoin_after);
  }
  if (dead_) {
    if (!rejoin_at_) return next;
    if (now < *rejoin_at_) return std::min(next, *rejoin_at_);
    dead_ = false;  // the replacement: a new connection, a new identity
    rejoin_at_.reset();
    behaviour_.die_at = -1.0;
    connect(now);
  }
  if (stalled(now)) return std::min(next, start_ + seconds(behaviour_.stall_until));
  // A real worker that heard nothing for longer than the master's timeout starts over.
  if (welcome_ && now - last_heard_ > std::chrono::milliseconds(welcome_->timeout_ms + 2 * welcome_->heartbeat_ms))
    connect(now);
  std::sort(due_.begin(), due_.end(), [](const Due& a, const Due& b) { return a.at < b.at; });
  size_t sent = 0;
  while (sent < due_.size() && due_[sent].at <= now) send_answer(due_[sent++]);
  due_.erase(due_.begin(), due_.begin() + long(sent));
  if (!due_.empty()) next = std::min(next, due_.front().at);
  if (behaviour_.flood_per_second > 0 && welcome_) next = std::min(next, flood(now));
  const auto heartbeat = std::chrono::milliseconds(welcome_ ? welcome_->heartbeat_ms : 250);
  if (now - last_sent_ >= heartbeat) send(protocol::Heartbeat{}, now);
  return std::min(next, last_sent_ + heartbeat);
}

}  // namespace igi::loadgen
