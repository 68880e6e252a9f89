#pragma once
// What the log says of a verdict the session cannot settle by itself.
#include <string>
#include <vector>

#include "trust/referee.h"

namespace igi {

// A worker as a report names it: "worker-3", and the libraries its Hello named.
struct VoterName {
  std::string name;
  std::string libraries;
};

// Every worker agrees on a frame's VPL sets and the master's own differ: the
// likely cause (the master's maths library or CPU), naming the workers and
// the libraries that differ from `master_libraries`.
std::string dispute_report(const HashDispute& dispute, const std::vector<VoterName>& workers,
                           const std::string& master_libraries);
// No worker agrees with the master's VPL sets for a frame and the votes cannot
// outweigh it either (a lone worker, a split, anonymous workers, one key):
// why, and that the master renders the frame's contested tiles itself.
// `names` are the doubt's voters, hash by hash, in its order.
std::string doubt_report(const HashDoubt& doubt, const std::vector<std::string>& names);
// Two workers disagree on a frame's VPL sets and no third breaks the tie;
// `names` are the split's voters, hash by hash, in its order.
std::string split_report(const HashSplit& split, const std::vector<std::string>& names);

}  // namespace igi
