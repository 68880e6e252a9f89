#include "methods/settings.h"

namespace igi {

const char* method_name(MethodKind kind) {
  switch (kind) {
    case MethodKind::PathTracer: return "pt";
    case MethodKind::InstantRadiosity: return "ir";
    case MethodKind::Igi: return "igi";
  }
  return "unknown";
}

std::optional<MethodKind> parse_method(const std::string& name) {
  for (MethodKind k : {MethodKind::PathTracer, MethodKind::InstantRadiosity, MethodKind::Igi})
    if (name == method_name(k)) return k;
  return std::nullopt;
}

}  // namespace igi
