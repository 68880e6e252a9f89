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
  const float top = *std::max_element(samples_.begin(), samples_.end());
  const float last = samples_[(next_ + samples_.size() - 1) % samples_.size()];
  char label[64];
  std::snprintf(label, sizeof label, "%.1f ms (max %.0f)", last, top);
  // Oldest first: the ring read from next_.
  ImGui::PlotLines("frame time", samples_.data(), int(samples_.size()), int(next_), label, 0.0f, 1.1f * top,
                   ImVec2(0, 48));
}

}  // namespace igi
