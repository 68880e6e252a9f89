#pragma once
// Reads igi-master's --stats file (JSON Lines, master/output/frame_stats.h) into one
// object: the last totals line's fields, and "frames", every frame's line in
// order. A line that does not parse (a killed master's last, half written) is skipped.
#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace igi::test {

inline nlohmann::json read_stats(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": no statistics");
  nlohmann::json frames = nlohmann::json::array(), totals = nlohmann::json::object();
  for (std::string text; std::getline(in, text);) {
    nlohmann::json line = nlohmann::json::parse(text, nullptr, false);
    if (!line.is_object()) continue;
    if (line.contains("frame")) frames.push_back(std::move(line));
    else totals = std::move(line);
  }
  totals["frames"] = std::move(frames);
  return totals;
}

}  // namespace igi::test
