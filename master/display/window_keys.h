#pragma once
// The master window's keys: one list for the help overlay (F1) and --help.
#include <string>

namespace igi {

struct WindowKey {
  const char* keys;
  const char* action;
};

inline constexpr WindowKey kWindowKeys[] = {
    {"left drag", "look around"},
    {"W S / A D / Q E", "move forward, back / left, right / down, up"},
    {"R", "the scene's camera again"},
    {"J L / U O / I K", "move the scene's lights along x / y / z"},
    {"M", "meter the exposure from the image again (auto)"},
    {"V", "the next view transform: standard, neutral, agx"},
    {"Tab", "the panel and the frame rate on and off"},
    {"F1 or ?", "this help"},
    {"F2", "tile overlay: off, tint (who rendered which tile), solid"},
    {"F5 / F9", "save / load the camera (the panel's camera file)"},
    {"F12", "save the accumulated image as EXR and PNG"},
    {"Esc", "quit"},
};

// The list as lines of text, for --help.
inline std::string window_keys_text(const char* indent) {
  std::string text;
  for (const WindowKey& k : kWindowKeys) text += std::string(indent) + k.keys + ": " + k.action + "\n";
  return text;
}

}  // namespace igi
