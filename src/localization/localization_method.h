#pragma once

#include <optional>
#include <string>
#include <vector>

// The relocalization methods of DESIGN.md §4 (what Localizer runs) and their names.
namespace semchain::localization {

enum class LocalizationMethod {
  kAmcl,
  kSemanticAmcl,
  kSemanticAmclBow,
  kSemanticScanMatch,
  kScanMatchGlobal,
};

// The stable names of DESIGN.md §4, in the order above.
const std::vector<std::string>& LocalizationMethodNames();
std::optional<LocalizationMethod> ParseLocalizationMethod(const std::string& name);
// "amcl, semantic-amcl, …" for messages.
std::string LocalizationMethodList();
const std::string& LocalizationMethodName(LocalizationMethod method);
// semantic-scanmatch and scanmatch-global: a scan matcher finds the robot, AMCL then tracks.
bool IsScanMatcherMethod(LocalizationMethod method);
// The methods that read the camera's detections.
bool IsSemanticMethod(LocalizationMethod method);

}  // namespace semchain::localization
