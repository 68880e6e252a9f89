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

namespace {

// Why a doubt is not a dispute: what the master would need to follow its workers.
std::string why_in_doubt(const HashDoubt& d, size_t voters) {
  if (d.voters.size() > 1) return "its workers disagree among themselves too";
  if (d.anonymous)
    return "its workers have no CURVE keys, so two that agree could be two fakes (authenticate them with "
           "--authorized-keys, and the master follows workers that all agree)";
  if (voters > d.keys) return "its workers share one key, which is one voter however many connections use it";
  return "a lone worker against the master is one voice against another (start another worker: two that agree "
         "and no other present outweigh the master)";
}

}  // namespace

std::string doubt_report(const HashDoubt& d, const std::vector<std::string>& names) {
  std::string text = "frame " + std::to_string(d.frame_id) + ": no worker agrees with the master's VPL-set hash " +
                     hash_hex(d.callers_hash) + " (";
  size_t i = 0;
  for (const auto& [hash, voters] : d.voters)
    for (size_t v = 0; v < voters.size(); ++v, ++i)
      text += (i == 0 ? "" : ", ") + names.at(i) + ": " + hash_hex(hash);
  return text + ") and the master cannot tell who is wrong: " + why_in_doubt(d, i) +
         ". It renders the frame's contested tiles itself and quarantines no one";
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
