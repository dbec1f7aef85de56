#pragma once

#include <memory>

#include "bow/keyframe_recognizer.h"
#include "localization/amcl_options.h"
#include "localization/localization_map.h"
#include "localization/prelocalization.h"
#include "localization/scan_match_relocalizer.h"
#include "mapping/map_io.h"
#include "semantic/semantic_map.h"

namespace semchain::localization {

// Everything a method may use about the environment, built once per map and shared (read only)
// by any number of localizers.
struct LocalizerMap {
  LocalizerMap(const mapping::MapImage& occupancy, const semantic::SemanticMap& semantic,
               const AmclOptions& amcl, const PreLocalizationOptions& prelocalization,
               const ScanMatchRelocalizerOptions& scan_match);

  mapping::MapImage occupancy;
  semantic::SemanticMap semantic;
  AmclOptions amcl_options;
  LocalizationMap localization;
  PreLocalizer prelocalizer;
  ScanMatchRelocalizer matcher;
  // The keyframes of the mapping run with their vocabulary (semantic-amcl-bow); may be null.
  std::shared_ptr<const bow::KeyframeRecognizer> recognizer;
};

}  // namespace semchain::localization
