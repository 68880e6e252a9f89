#include "trust/reports.h"

#include "scene/scene_file.h"

namespace igi {

std::string dispute_report(const HashDispute& d, const std::vector<VoterName>& workers,
                           const std::string& master_libraries) {
  std::string names, libraries;
  for (const VoterName& w : workers) {
    names += (names.empty() ? "" : ", ") + w.name;
    if (!w.libraries.empty() && w.libraries != master_libraries) libraries += "; " + w.name + " runs " + w.libraries;
  }
  return "frame " + std::to_string(d.frame_id) + ": the master's VPL-set hash " + hash_hex(d.callers_hash) +
         " differs from the one all its workers agree on (" + names + ": " + hash_hex(d.workers_hash) +
         "). The master is the odd one out: likely its maths library or CPU (the master runs " + master_libraries +
         (libraries.empty() ? ", as they do: a library that differs under one version, LD_PRELOAD, another libm"
                              " dispatch for this CPU"
                            : libraries) +
         ")";
}

std::string split_report(const HashSplit& split, const std::vector<std::string>& names) {
  std::string text = "frame " + std::to_string(split.frame_id) + " waits: its workers disagree on the VPL sets (";
  size_t i = 0;
  for (const auto& [hash, voters] : split.voters)
    for (size_t v = 0; v < voters.size(); ++v, ++i)
      text += (i == 0 ? "" : ", ") + names.at(i) + ": hash " + hash_hex(hash);
  return text + ") and no other worker breaks the tie; start another worker of this build";
}

}  // namespace igi
