#include "soak_options.h"

#include <stdexcept>

namespace igi::soak {

std::string soak_usage() {
  return "usage: igi-soak [options]\n"
         "Runs igi-master and igi-worker processes on loopback for a number of frames while injecting\n"
         "faults from a seeded schedule, then checks every frame bit for bit against the single-process\n"
         "render and the master's memory for growth. Exit 0 only when nothing was lost, nothing differs\n"
         "and memory stayed bounded.\n"
         "  --frames N            frames to render [300]\n"
         "  --size WxH            [128x96]\n"
         "  --render-args \"...\"   scene, method and settings, as igi-render takes them\n"
         "                        [--scene cornell --method igi --vpl-paths 16 --clamp 0.05 --tile 16]\n"
         "  --workers K           loopback workers [3]\n"
         "  --seed S              fault schedule seed; 0 = from the clock [0]\n"
         "  --faults F            faults to inject; 0 = one per 10 frames [0]\n"
         "  --kinds LIST          of kill,stop,slow,garbage,restart,cut [all]\n"
         "  --heartbeat-ms MS     master heartbeat [100]   --timeout-ms MS  master's dead-worker timeout [500]\n"
         "  --deadline S          give up (and fail) after S seconds; 0 = 30 + 0.6 x frames [0]\n"
         "  --netns auto|on|off   also run a worker in a network namespace behind a veth link that is cut\n"
         "                        and restored; auto skips (and says why) where the machine does not allow it [auto]\n"
         "  --real-oversized      also send one real 512 MB + 64 KB + 1 message (the limit is checked on the header)\n"
         "  --rss-margin MIB      allowed growth of the master's median RSS, first half to second half [2]\n"
         "  --memory-check off    report the master's memory but do not judge it (sanitizer builds keep freed\n"
         "                        memory in quarantine, so their RSS grows without a leak)\n"
         "  --dir DIR             working folder, emptied first [soak-run]\n"
         "  --master PATH  --worker PATH   the binaries [next to igi-soak]\n"
         "  --corrupt-frame I     self-test: alter frame I's file by one ulp before the check (the run must fail)\n"
         "  --delete-frame I      self-test: delete frame I's file before the check (the run must fail)\n";
}

static int to_int(const std::string& option, const std::string& value, int min) {
  try {
    size_t end = 0;
    long v = std::stol(value, &end);
    if (end == value.size() && v >= min && v <= 1000000000) return int(v);
  } catch (const std::exception&) {
  }
  throw std::invalid_argument(option + ": expected an integer >= " + std::to_string(min) + ", got '" + value + "'");
}

static double to_double(const std::string& option, const std::string& value) {
  try {
    size_t end = 0;
    double v = std::stod(value, &end);
    if (end == value.size() && v >= 0) return v;
  } catch (const std::exception&) {
  }
  throw std::invalid_argument(option + ": expected a non-negative number, got '" + value + "'");
}

static void parse_size(const std::string& value, SoakOptions& o) {
  const size_t x = value.find('x');
  if (x == std::string::npos) throw std::invalid_argument("--size: expected WxH, got '" + value + "'");
  o.width = to_int("--size", value.substr(0, x), 1);
  o.height = to_int("--size", value.substr(x + 1), 1);
}

SoakOptions parse_soak_options(const std::vector<std::string>& args) {
  SoakOptions o;
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw std::invalid_argument(a + ": missing value");
      return args[++i];
    };
    if (a == "--help" || a == "-h") o.help = true;
    else if (a == "--frames") o.frames = to_int(a, value(), 2);
    else if (a == "--size") parse_size(value(), o);
    else if (a == "--render-args") o.render_args = value();
    else if (a == "--workers") o.workers = to_int(a, value(), 1);
    else if (a == "--seed") o.seed = std::stoull(value());
    else if (a == "--faults") o.faults = to_int(a, value(), 0);
    else if (a == "--kinds") o.kinds = value();
    else if (a == "--heartbeat-ms") o.heartbeat_ms = to_int(a, value(), 10);
    else if (a == "--timeout-ms") o.timeout_ms = to_int(a, value(), 50);
    else if (a == "--deadline") o.deadline_seconds = to_double(a, value());
    else if (a == "--netns") o.netns = value();
    else if (a == "--real-oversized") o.real_oversized = true;
    else if (a == "--rss-margin") o.rss_margin_mib = to_double(a, value());
    else if (a == "--memory-check") o.memory_check = value() != "off";
    else if (a == "--dir") o.dir = value();
    else if (a == "--master") o.master_binary = value();
    else if (a == "--worker") o.worker_binary = value();
    else if (a == "--corrupt-frame") o.corrupt_frame = to_int(a, value(), 0);
    else if (a == "--delete-frame") o.delete_frame = to_int(a, value(), 0);
    else throw std::invalid_argument("unknown option '" + a + "' (see --help)");
  }
  if (o.netns != "auto" && o.netns != "on" && o.netns != "off")
    throw std::invalid_argument("--netns: expected auto, on or off, got '" + o.netns + "'");
  if (o.faults == 0) o.faults = o.frames / 10;
  if (o.deadline_seconds == 0) o.deadline_seconds = 30.0 + 0.6 * o.frames;
  return o;
}

}  // namespace igi::soak
