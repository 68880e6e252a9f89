#pragma once
// One soak run: a master and workers on loopback render frames while the
// fault plan is carried out; then every frame is checked and the summary
// printed. Every child process dies with the run (or with the driver), and
// the run ends by its deadline whatever happens.
#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <string>
#include <vector>

#include "child_process.h"
#include "fault_plan.h"
#include "garbage_client.h"
#include "hostile_peer.h"
#include "memory_monitor.h"
#include "net_namespace.h"
#include "options/render_options.h"
#include "soak_options.h"
#include "soak_report.h"
#include "tcp_relay.h"
#include "worker_pool.h"

namespace igi::soak {

class SoakRun {
 public:
  // `stop` is set from a signal handler: the run ends, reports and fails.
  SoakRun(SoakOptions options, const std::atomic<bool>& stop);
  int run();

 private:
  using Clock = std::chrono::steady_clock;
  void prepare();
  void set_up_namespace();
  bool start_master(int first_frame, bool wait_until_listening);
  void kill_master(double restart_delay);
  void advance_frames();
  bool loop_once();  // false when the run is over
  bool master_finished();
  void fire_due_faults();
  bool inject(Fault& fault);
  void judge_hostile(const HostileReport& report);
  void corrupt_frame_file(int frame) const;
  double seconds_since_start() const;

  SoakOptions o_;
  const std::atomic<bool>& stop_;
  RenderOptions render_;
  std::vector<std::string> render_args_;
  std::string logs_;
  int port_ = 0;
  Clock::time_point start_, deadline_;

  std::vector<Fault> plan_;
  std::vector<bool> injected_;  // by plan index; a fault that must wait (no worker free) holds up no other
  std::unique_ptr<NetNamespace> ns_;
  std::unique_ptr<TcpRelay> relay_;
  std::unique_ptr<WorkerPool> workers_;
  std::unique_ptr<GarbageClient> garbage_;
  std::vector<std::future<GarbageCounts>> garbage_bursts_;  // may overlap: frames can outpace a burst
  std::vector<std::future<HostileReport>> hostile_runs_;

  Child master_;
  int master_runs_ = 0;
  int segment_first_ = 0;      // the current master process's first frame
  bool master_down_ = false;   // killed, its successor not started yet
  bool finished_ = false;      // the last master process wrote the last frame and left
  Clock::time_point restart_at_, killed_at_;
  bool timing_restart_ = false;
  int frames_on_disk_ = 0;     // frames 0 .. frames_on_disk_ - 1 are written
  int unexpected_master_exits_ = 0;
  MemoryMonitor memory_;
  Clock::time_point next_sample_;
  SoakTotals totals_;
};

}  // namespace igi::soak
