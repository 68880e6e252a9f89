#include "display/frame_graph.h"

#include <algorithm>
#include <cstdio>

#include <imgui.h>

namespace igi {

void FrameGraph::add(double milliseconds) {
  samples_[next_] = float(milliseconds);
  next_ = (next_ + 1) % samples_.size();
  count_ = std::min(count_ + 1, samples_.size());
}

void FrameGraph::draw() const {
  if (count_ == 0) return ImGui::TextUnformatted("frame time: no frame yet");
  // Oldest first: the last count_ samples of the ring, ending before next_.
  std::vector<float> recent(count_);
  for (size_t i = 0; i < count_; ++i) recent[i] = samples_[(next_ + samples_.size() - count_ + i) % samples_.size()];
  const float top = *std::max_element(recent.begin(), recent.end());
  char label[64];
  std::snprintf(label, sizeof label, "%.1f ms (max %.0f)", recent.back(), top);
  ImGui::PlotLines("frame time", recent.data(), int(recent.size()), 0, label, 0.0f, 1.1f * top, ImVec2(0, 48));
}

}  // namespace igi
