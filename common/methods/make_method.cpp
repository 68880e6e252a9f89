#include "core/method.h"
#include "lightcuts/lightcuts_method.h"
#include "methods/path_tracer.h"
#include "methods/vpl_method.h"

namespace igi {

std::unique_ptr<Method> make_method(const SceneContext& context, const RenderSettings& settings) {
  switch (settings.method) {
    case MethodKind::PathTracer: return std::make_unique<PathTracer>(context, settings);
    case MethodKind::InstantRadiosity:
    case MethodKind::Igi: return std::make_unique<VplMethod>(context, settings);
    case MethodKind::Lightcuts: return std::make_unique<lightcuts::LightcutsMethod>(context, settings);
  }
  return nullptr;
}

}  // namespace igi
