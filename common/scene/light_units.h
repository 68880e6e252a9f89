#pragma once
// How a glTF file's KHR_lights_punctual intensities are read (--light-units).
// The renderer's own units are radiometric (scene/scene.h); the
// specification's are photometric.
#include <cstdint>

namespace igi {

enum class LightUnits : uint8_t {
  // The specification's: point and spot in candela, directional in lux,
  // turned into W/sr and W/m^2 at kLumensPerWatt (as Blender's exporter
  // writes them, and igi-cluster's own gltf_writer).
  Photometric = 0,
  // W/sr and W/m^2 as they stand (files written for renderers that read them so).
  Radiometric = 1,
};

inline constexpr double kLumensPerWatt = 683.0;  // the luminous efficacy glTF and Blender convert at

inline const char* light_units_name(LightUnits units) {
  return units == LightUnits::Radiometric ? "radiometric" : "photometric";
}

}  // namespace igi
