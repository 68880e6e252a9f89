#include "methods/settings.h"

namespace igi {

const char* method_name(MethodKind kind) {
  switch (kind) {
    case MethodKind::PathTracer: return "pt";
    case MethodKind::InstantRadiosity: return "ir";
    case MethodKind::Igi: return "igi";
    case MethodKind::Lightcuts: return "lightcuts";
  }
  return "unknown";
}

std::optional<MethodKind> parse_method(const std::string& name) {
  for (MethodKind k : {MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi, MethodKind::Lightcuts})
    if (name == method_name(k)) return k;
  return std::nullopt;
}

}  // namespace igi
