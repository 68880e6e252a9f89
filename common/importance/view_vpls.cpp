#include "importance/view_vpls.h"

#include <optional>

#include "importance/bidirectional.h"
#include "importance/light_importance.h"
#include "sampling/content_hash.h"
#include "vpl/vpl_generator.h"

namespace igi::importance {

VplSets generate_view_vpls(const SceneContext& context, const RenderSettings& settings, const FrameSetup& frame,
                           RayCounts& rays) {
  std::optional<LightSelection> selection;
  LightPathOptions options;
  // With one light there is nothing to choose: its probability is 1 either way.
  if (settings.importance_paths > 0 && context.lights.lights().size() > 1) {
    selection = estimate_light_importance(context, settings, frame, rays);
    options.selection = &selection->distribution;
  }
  VplSets sets = settings.bidir_vpls > 0 ? generate_bidirectional(context, settings, frame, options, rays)
                                         : generate_vpls(context, settings, frame.seed, options);
  if (selection) sets.hash = combine_content_hashes(sets.hash, selection->hash);
  return sets;
}

}  // namespace igi::importance
