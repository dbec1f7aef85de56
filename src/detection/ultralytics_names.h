#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/status.h"

// The class names ultralytics' exporter stores in an ONNX model's metadata_props under "names":
// str() of the model's names dict, a Python literal such as
//   {0: 'person', 1: 'bicycle', 2: "men's shoes"}
namespace semchain::detection {

// The names in class-id order from a Python dict literal {id: 'name', ...} whose ids are 0 to
// n - 1 in any order, or a list literal ['name', ...]. Strings are quoted with ' or " and may hold
// the escapes Python's repr() writes (\\, \', \", \n, \t, \r, \xNN, \uNNNN, \UNNNNNNNN; as UTF-8).
// An error says what is wrong and where ("character 17: expected ':'").
Result<std::vector<std::string>> ParseUltralyticsNames(std::string_view text);

}  // namespace semchain::detection
