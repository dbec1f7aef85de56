#include "localization/localizer_map.h"

namespace semchain::localization {

LocalizerMap::LocalizerMap(const mapping::MapImage& occupancy_in,
                           const semantic::SemanticMap& semantic_in, const AmclOptions& amcl,
                           const PreLocalizationOptions& prelocalization,
                           const ScanMatchRelocalizerOptions& scan_match)
    : occupancy(occupancy_in),
      semantic(semantic_in),
      amcl_options(amcl),
      localization(occupancy_in, amcl.laser_likelihood_max_dist),
      prelocalizer(semantic_in, occupancy_in, prelocalization),
      matcher(occupancy_in, scan_match) {}

}  // namespace semchain::localization
