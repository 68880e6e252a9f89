#include "options/liveness_options.h"

#include <CLI/CLI.hpp>

#include "cli/option_checks.h"
#include "protocol/messages.h"

namespace igi {

void add_liveness_options(CLI::App& app, int& heartbeat_ms, int& timeout_ms, const std::string& group) {
  app.add_option("--heartbeat-ms", heartbeat_ms, "how often the master and its workers send a message at least")
      ->check(cli::integer<int>(protocol::kMinHeartbeatMs, protocol::kMaxHeartbeatMs))->capture_default_str()->type_name("MS")
      ->group(group);
  app.add_option("--timeout-ms", timeout_ms, "a silent worker is declared dead after this, > --heartbeat-ms")
      ->check(cli::integer<int>(protocol::kMinTimeoutMs, protocol::kMaxTimeoutMs))->capture_default_str()->type_name("MS")
      ->group(group);
}

void check_liveness(int heartbeat_ms, int timeout_ms) {
  if (timeout_ms <= heartbeat_ms)
    throw cli::OptionError("--timeout-ms " + std::to_string(timeout_ms) + " must be greater than --heartbeat-ms " +
                           std::to_string(heartbeat_ms) + ": a worker is declared dead after --timeout-ms without "
                           "a message, and sends one every --heartbeat-ms");
}

}  // namespace igi
