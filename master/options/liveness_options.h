#pragma once
// --heartbeat-ms and --timeout-ms, declared once for every program that
// starts a master (igi-master, igi-soak, igi-loadgen), within the wire's limits.
#include <string>

namespace CLI {
class App;
}

namespace igi {

// Declares both options on `app` (defaults: the variables' values); call
// check_liveness() after the parse.
void add_liveness_options(CLI::App& app, int& heartbeat_ms, int& timeout_ms, const std::string& group = "Options");
// A worker is declared dead after --timeout-ms without a message and sends one
// every --heartbeat-ms, so the timeout must be the longer: throws cli::OptionError naming both.
void check_liveness(int heartbeat_ms, int timeout_ms);

}  // namespace igi
