#pragma once
// The last few seconds of frame times as a small line graph.
#include <cstddef>
#include <vector>

namespace igi {

class FrameGraph {
 public:
  explicit FrameGraph(size_t length = 240) : samples_(length, 0.0f) {}
  void add(double milliseconds);
  void draw() const;  // inside an ImGui window

 private:
  std::vector<float> samples_;  // a ring; next_ is the oldest
  size_t next_ = 0, count_ = 0;
};

}  // namespace igi
