#include "scene/libraries.h"

#include <embree3/rtcore.h>
#include <gnu/libc-version.h>

namespace igi {

std::string runtime_libraries() {
  static const std::string text = [] {
    std::string embree = "unknown";
    if (RTCDevice device = rtcNewDevice("threads=1")) {
      const long v = long(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION));  // e.g. 31305
      embree = std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
      rtcReleaseDevice(device);
    }
    return std::string("glibc ") + gnu_get_libc_version() + ", Embree " + embree;
  }();
  return text;
}

}  // namespace igi
