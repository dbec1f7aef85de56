#include "localization/localization_method.h"

#include <algorithm>

namespace semchain::localization {

const std::vector<std::string>& LocalizationMethodNames() {
  static const std::vector<std::string> kNames = {"amcl", "semantic-amcl", "semantic-amcl-bow",
                                                  "semantic-scanmatch", "scanmatch-global"};
  return kNames;
}

std::optional<LocalizationMethod> ParseLocalizationMethod(const std::string& name) {
  const std::vector<std::string>& names = LocalizationMethodNames();
  const auto found = std::find(names.begin(), names.end(), name);
  if (found == names.end()) return std::nullopt;
  return static_cast<LocalizationMethod>(found - names.begin());
}

std::string LocalizationMethodList() {
  std::string list;
  for (const std::string& name : LocalizationMethodNames()) {
    list += (list.empty() ? "" : ", ") + name;
  }
  return list;
}

const std::string& LocalizationMethodName(LocalizationMethod method) {
  return LocalizationMethodNames()[static_cast<std::size_t>(method)];
}

bool IsScanMatcherMethod(LocalizationMethod method) {
  return method == LocalizationMethod::kSemanticScanMatch ||
         method == LocalizationMethod::kScanMatchGlobal;
}

bool IsSemanticMethod(LocalizationMethod method) {
  return method == LocalizationMethod::kSemanticAmcl ||
         method == LocalizationMethod::kSemanticAmclBow ||
         method == LocalizationMethod::kSemanticScanMatch;
}

}  // namespace semchain::localization
