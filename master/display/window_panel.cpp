#include "display/window_panel.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include "display/cluster_panel.h"

namespace igi {

WindowPanel::WindowPanel(GLFWwindow* window, const RenderSettings& settings, float exposure, PanelOptions options)
    : gui_(window), settings_(settings, exposure), options_(std::move(options)) {}

void WindowPanel::frame_shown(const FrameRecord& record, std::vector<PeerView> peers) {
  graph_.add(1e3 * record.seconds);
  last_ = record;
  peers_ = std::move(peers);
}

// ImGui 1.86 indexes keys by GLFW's codes: IsKeyPressed sees each press once.
PanelActions WindowPanel::read_keys() {
  PanelActions a;
  if (gui_.wants_keyboard()) return a;  // typing a file name
  if (ImGui::IsKeyPressed(GLFW_KEY_F1, false)) options_.shown = !options_.shown;
  if (ImGui::IsKeyPressed(GLFW_KEY_F2, false)) options_.overlay = next_overlay(options_.overlay);
  a.save_camera = ImGui::IsKeyPressed(GLFW_KEY_F5, false);
  a.load_camera = ImGui::IsKeyPressed(GLFW_KEY_F9, false);
  a.save_image = ImGui::IsKeyPressed(GLFW_KEY_F12, false);
  return a;
}

void WindowPanel::draw_bookmarks(PanelActions& a) {
  ImGui::InputText("camera file", &options_.bookmark);
  if (ImGui::Button("save camera (F5)")) a.save_camera = true;
  ImGui::SameLine();
  if (ImGui::Button("load camera (F9)")) a.load_camera = true;
  ImGui::InputText("image prefix", &options_.shot_prefix);
  if (ImGui::Button("save EXR + PNG (F12)")) a.save_image = true;
  if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
}

PanelActions WindowPanel::draw(int accumulated) {
  const PanelActions actions = build(accumulated);
  gui_.render();
  return actions;
}

PanelActions WindowPanel::build(int accumulated) {
  gui_.begin_frame();
  PanelActions actions = read_keys();
  draw_tile_overlay(last_.tile_sources, options_.overlay);
  if (options_.shown) {
    ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Once);
    ImGui::SetNextWindowSize(ImVec2(400, 0.95f * ImGui::GetIO().DisplaySize.y), ImGuiCond_Once);
    ImGui::Begin("igi-master (F1 hides)");
    ImGui::PushItemWidth(190);
    ImGui::Text("%d frames accumulated", accumulated);
    if (ImGui::CollapsingHeader("settings", ImGuiTreeNodeFlags_DefaultOpen)) settings_.draw();
    if (ImGui::CollapsingHeader("cluster", ImGuiTreeNodeFlags_DefaultOpen)) {
      graph_.draw();
      draw_cluster_panel(peers_, last_);
      int overlay = int(options_.overlay);
      ImGui::Combo("tile overlay (F2)", &overlay, "off\0tint\0solid\0");
      options_.overlay = OverlayMode(overlay);
    }
    if (ImGui::CollapsingHeader("camera and images")) draw_bookmarks(actions);
    ImGui::PopItemWidth();
    ImGui::End();
  }
  ImGui::EndFrame();
  return actions;
}

}  // namespace igi
