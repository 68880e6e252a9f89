#include "display/window_panel.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_stdlib.h>

#include <algorithm>
#include <cstdio>
#include <functional>

#include "display/cluster_panel.h"
#include "display/interactive_window.h"
#include "display/window_keys.h"

namespace igi {
namespace {

// A box of text in a corner of the window, over the image: pivot (0, 0) top
// left ... (1, 1) bottom right.
void corner_box(const char* name, ImVec2 pivot, const std::function<void()>& contents) {
  const ImVec2 size = ImGui::GetIO().DisplaySize;
  const float margin = 6.0f;
  ImGui::SetNextWindowPos(ImVec2(margin + pivot.x * (size.x - 2 * margin), margin + pivot.y * (size.y - 2 * margin)),
                          ImGuiCond_Always, pivot);
  ImGui::SetNextWindowBgAlpha(0.88f);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_AlwaysAutoResize |
                                 ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing |
                                 ImGuiWindowFlags_NoNav | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoInputs;
  if (ImGui::Begin(name, nullptr, flags)) contents();
  ImGui::End();
}

// Lines of text on a dark box: pivot (0, 0) puts its top left at `at`,
// (1, 1) its bottom right; placed from its own size in this frame (an
// auto-sized window would lag a frame behind).
void text_box(const char* text, ImVec2 at, ImVec2 pivot) {
  const ImVec2 size = ImGui::CalcTextSize(text);
  const float pad = 5.0f;
  const ImVec2 box(size.x + 2 * pad, size.y + 2 * pad);
  const ImVec2 corner(at.x - pivot.x * box.x, at.y - pivot.y * box.y);
  ImDrawList* draw = ImGui::GetForegroundDrawList();
  draw->AddRectFilled(corner, ImVec2(corner.x + box.x, corner.y + box.y), IM_COL32(0, 0, 0, 150), 4.0f);
  draw->AddText(ImVec2(corner.x + pad, corner.y + pad), IM_COL32(255, 255, 255, 255), text);
}

// A text box in a corner of the window: pivot (0, 0) top left ... (1, 1) bottom right.
void corner_text(const char* text, ImVec2 pivot) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float margin = 6.0f;
  text_box(text, ImVec2(margin + pivot.x * (display.x - 2 * margin), margin + pivot.y * (display.y - 2 * margin)),
           pivot);
}

}  // namespace

WindowPanel::WindowPanel(GLFWwindow* window, const RenderSettings& settings, const ToneMapping& tone,
                         PanelOptions options)
    : gui_(window), settings_(settings, tone), options_(std::move(options)) {
  load_panel_fonts();
}

Viewport WindowPanel::image_viewport(float window_width, float window_height) const {
  const float panel = options_.shown ? panel_layout(options_.image_width).width : 0.0f;
  return igi::image_viewport(window_width, window_height, options_.image_width, options_.image_height, panel);
}

void WindowPanel::set_message(std::string message) {
  message_ = std::move(message);
  message_at_ = ImGui::GetTime();
}

void WindowPanel::frame_shown(const FrameRecord& record, std::vector<PeerView> peers, double fps, std::string level) {
  graph_.add(1e3 * record.seconds);
  fps_ = fps;
  waiting_ = 0.0;
  level_ = std::move(level);
  ++frames_;
  last_ = record;
  peers_ = std::move(peers);
}

// The window's taps (GLFW key codes; with Shift, | kShifted), not ImGui's
// IsKeyPressed: ImGui 1.86 sees a key only if it is still down at one of the
// panel's frames (20 a second when nothing else comes), and a quick tap is not.
PanelActions WindowPanel::read_keys(const std::set<int>& taps) {
  PanelActions a;
  if (gui_.wants_keyboard()) return a;  // typing a file name
  auto tapped = [&](int key) { return taps.count(key) || taps.count(key | InteractiveWindow::kShifted); };
  if (tapped(GLFW_KEY_TAB)) options_.shown = !options_.shown;
  const bool question = taps.count(GLFW_KEY_SLASH | InteractiveWindow::kShifted) > 0;
  if (tapped(GLFW_KEY_F1) || question) options_.help = !options_.help;
  if (tapped(GLFW_KEY_F2)) options_.overlay = next_overlay(options_.overlay);
  if (tapped(GLFW_KEY_V)) settings_.next_view();
  a.meter = tapped(GLFW_KEY_M);
  a.save_camera = tapped(GLFW_KEY_F5);
  a.load_camera = tapped(GLFW_KEY_F9);
  a.save_image = tapped(GLFW_KEY_F12);
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

// The last action's outcome (F5, F9, F12), top right for a few seconds
// (the panel is top left, the read-out bottom right), whether or not the
// panel and its section are open.
void WindowPanel::draw_message() {
  constexpr double kShownSeconds = 4.0;
  if (!message_.empty() && ImGui::GetTime() - message_at_ < kShownSeconds) corner_text(message_.c_str(), ImVec2(1, 0));
}

PanelActions WindowPanel::draw(int accumulated, const std::set<int>& taps) {
  const PanelActions actions = build(accumulated, taps);
  gui_.render();
  return actions;
}

PanelActions WindowPanel::build(int accumulated, const std::set<int>& taps) {
  gui_.begin_frame();
  PanelActions actions = read_keys(taps);
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  draw_tile_overlay(last_.tile_sources, options_.overlay, image_viewport(display.x, display.y));
  if (options_.shown) {
    draw_panel(actions);
    draw_readout(accumulated, panel_layout(options_.image_width).width);
  }
  if (options_.help) draw_help();
  draw_message();
  actions.meter = actions.meter || settings_.take_meter_request();
  ImGui::EndFrame();
  return actions;
}

// A column on the left, the window's height less the read-out's strip, as
// wide as panel_layout says; the image is beside it, never under it.
// Settings open, the rest closed; a scroll bar where the open sections are
// taller than the column.
void WindowPanel::draw_panel(PanelActions& actions) {
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const PanelLayout layout = panel_layout(options_.image_width);
  const PanelFont font = panel_font(layout.font_pixels);
  const float width = layout.width;
  ImGui::SetNextWindowPos(ImVec2(0, 0), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(width, std::max(display.y - kReadoutHeight, 0.0f)), ImGuiCond_Always);
  ImGui::SetNextWindowBgAlpha(1.0f);
  if (font.font) ImGui::PushFont(font.font);
  ImGui::Begin("igi-master (Tab hides, F1 help)", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings);
  ImGui::SetWindowFontScale(font.scale);
  ImGui::PushItemWidth(0.45f * width);  // the rest for labels of 15 characters
  settings_.draw();
  draw_preview_choice();
  if (ImGui::CollapsingHeader("cluster")) {
    graph_.draw();
    draw_cluster_panel(peers_, last_);
    int overlay = int(options_.overlay);
    ImGui::Combo("tile overlay (F2)", &overlay, "off\0tint\0solid\0");
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("who rendered which tile\n--overlay");
    options_.overlay = OverlayMode(overlay);
  }
  if (ImGui::CollapsingHeader("camera and images")) draw_bookmarks(actions);
  ImGui::PopItemWidth();
  ImGui::End();
  if (font.font) ImGui::PopFont();
}

// What frames take while the view changes: the budget's choice, or a level pinned.
void WindowPanel::draw_preview_choice() {
  if (options_.preview_levels.empty()) return;
  std::string items = "budget (--frame-budget-ms)";
  items.push_back('\0');
  for (const std::string& name : options_.preview_levels) items += (name == "full" ? "full frames only" : name) + '\0';
  int choice = options_.preview + 1;
  ImGui::Combo("while moving", &choice, items.c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("what frames render at while the camera or settings change:\n"
                      "the level the frame budget picks, or always this one");
  options_.preview = choice - 1;
}

// At the foot of the panel's column, in two lines: frame rate over the last
// second, the level of the frame shown, frame time; frames shown and passes
// accumulated. Or how long the window has waited for a frame.
void WindowPanel::draw_readout(int accumulated, float width) {
  char text[160] = "waiting for the first frame";
  if (frames_ > 0 && waiting_ > 1.0)
    std::snprintf(text, sizeof text, "waiting for a frame: %.1f s\nlast: %.0f ms, %s", waiting_, 1e3 * last_.seconds,
                  level_.c_str());
  else if (frames_ > 0)
    std::snprintf(text, sizeof text, "%.1f fps  %s  %.0f ms\nframe %llu  %d pass%s", fps_, level_.c_str(),
                  1e3 * last_.seconds, (unsigned long long)frames_, accumulated, accumulated == 1 ? "" : "es");
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::GetForegroundDrawList()->AddRectFilled(ImVec2(0, display.y - kReadoutHeight), ImVec2(width, display.y),
                                                IM_COL32(15, 15, 15, 255));
  text_box(text, ImVec2(4.0f, display.y - 2.0f), ImVec2(0, 1));
}

void WindowPanel::draw_help() {
  corner_box("##help", ImVec2(0.5f, 0.5f), [] {
    ImGui::TextUnformatted("keys (F1 or ? closes)");
    ImGui::Separator();
    if (!ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingFixedFit)) return;
    for (const WindowKey& k : kWindowKeys) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(k.keys);
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(k.action);
    }
    ImGui::EndTable();
    ImGui::TextUnformatted("still camera and settings: frames accumulate");
  });
}

}  // namespace igi
