#include "apps/shipped_file.h"

#include <string>

#include "core/data_path.h"

namespace semchain::app {

CLI::Validator ShippedFile() {
  // No description or name: --help shows the option as the user writes it.
  return CLI::Validator(
      [](std::string& value) {
        value = ResolveDataPath(value, DefaultDataDirectories()).string();
        return std::string();
      },
      "", "");
}

}  // namespace semchain::app
