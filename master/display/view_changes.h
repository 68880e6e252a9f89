#pragma once
// What the user changed in a window since the last look, in the order the
// window loop acts on it: new settings or moved lights start the image over
// (a new settings generation), a moved camera carries it (a new camera
// generation), a new preview pin only changes what frames are planned.
// igi-master's window and igi-view's both count their views with it.
#include <cstdint>

#include "display/camera_controller.h"
#include "display/window_panel.h"

namespace igi {

class ViewChanges {
 public:
  enum class Change { None, Settings, Camera, Preview };

  explicit ViewChanges(const CameraController& controller)
      : seen_camera_(controller.generation()), light_offset_(controller.light_offset()) {}
  // `published_preview`: the pin of the view published last.
  Change take(WindowPanel& panel, const CameraController& controller, int published_preview) {
    Change change = Change::None;
    const bool lights_moved = controller.light_offset() != light_offset_;
    if (panel.settings().take_change() || lights_moved) {
      light_offset_ = controller.light_offset();
      ++settings_generation_;
      change = Change::Settings;
    } else if (controller.generation() != seen_camera_) {
      ++camera_generation_;
      change = Change::Camera;
    } else if (panel.options().preview != published_preview) {
      change = Change::Preview;
    }
    seen_camera_ = controller.generation();
    return change;
  }
  // A new controller (a loaded bookmark): the next take() sees a new camera.
  void forget_camera(const CameraController& controller) { seen_camera_ = ~controller.generation(); }
  uint64_t camera_generation() const { return camera_generation_; }
  uint64_t settings_generation() const { return settings_generation_; }

 private:
  uint64_t camera_generation_ = 0, settings_generation_ = 0, seen_camera_;
  glm::vec3 light_offset_;
};

}  // namespace igi
