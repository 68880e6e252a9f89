#pragma once
// Per-frame statistics of a master run, written as JSON.
#include <string>
#include <vector>

#include "master_session.h"

namespace igi {

void write_stats_json(const std::string& path, const std::vector<FrameRecord>& frames, uint64_t bad_messages);

}  // namespace igi
