#include "display/cluster_panel.h"

#include <algorithm>

#include <imgui.h>
#include <imgui_internal.h>  // ImGuiTable::ColumnsAutoFitWidth

#include "display/tile_overlay.h"

namespace igi {

WorkerLoad worker_load(const PeerView& peer, const FrameRecord& frame) {
  auto it = frame.workers.find(peer.name);
  if (it == frame.workers.end() || frame.seconds <= 0.0) return {};
  const double threads = std::max<uint32_t>(peer.threads, 1);
  return {double(it->second.tiles) / frame.seconds, it->second.busy_seconds / (threads * frame.seconds)};
}

float draw_cluster_panel(const std::vector<PeerView>& peers, const FrameRecord& f) {
  ImGui::TextWrapped("%zu workers; frame %llu: %llu tiles in %.1f ms", peers.size(), (unsigned long long)f.frame_id,
              (unsigned long long)f.tiles, 1e3 * f.seconds);
  ImGui::TextWrapped("reissued %llu  duplicated %llu  late %llu  quarantined %llu", (unsigned long long)f.reissued,
              (unsigned long long)f.duplicated, (unsigned long long)f.late_dropped, (unsigned long long)f.quarantined);
  // As wide as its columns (NoHostExtendX), narrow enough for a third of a 640-pixel window.
  const ImGuiTableFlags flags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit |
                                ImGuiTableFlags_NoHostExtendX;
  ImGui::PushStyleVar(ImGuiStyleVar_CellPadding, ImVec2(3.0f, 1.0f));
  const bool shown = ImGui::BeginTable("workers", 5, flags);
  ImGui::PopStyleVar();
  if (!shown) return 0.0f;
  for (const char* heading : {"worker", "tiles/s", "busy", "rtt", "heard"}) ImGui::TableSetupColumn(heading);
  ImGui::TableHeadersRow();
  for (const PeerView& p : peers) {
    const WorkerLoad load = worker_load(p, f);
    const auto c = worker_colour(p.number);
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextColored(ImVec4(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1.0f), "%s", p.name.c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s: %u threads", p.name.c_str(), p.threads);
    ImGui::TableNextColumn();
    ImGui::Text("%.0f", load.tiles_per_second);
    ImGui::TableNextColumn();
    ImGui::Text("%.0f %%", 100.0 * load.busy_share);
    ImGui::TableNextColumn();
    ImGui::Text("%.1f", p.round_trip_ms);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f", p.since_heard_s);
  }
  // What the columns need for nothing to be clipped (ImGui narrows the table to the window, cutting them off).
  const float width = ImGui::GetCurrentTable()->ColumnsAutoFitWidth;
  ImGui::EndTable();
  ImGui::TextDisabled("rtt: round trip, ms; heard: s ago; threads: hover a name");
  return width;
}

}  // namespace igi
