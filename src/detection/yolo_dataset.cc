#include "detection/yolo_dataset.h"

#include <algorithm>

#include "io/yaml_reader.h"

namespace semchain::detection {
namespace fs = std::filesystem;

Result<YoloDataset> LoadYoloDataset(const fs::path& data_yaml) {
  Result<yaml::Node> root = yaml::Node::LoadFile(data_yaml);
  if (!root.ok()) return root.status();
  YoloDataset dataset;
  dataset.root = data_yaml.parent_path();
  if (root->Has("path")) {
    Result<std::string> path = root->Get("path")->AsString();
    if (!path.ok()) return path.status();
    dataset.root = fs::path(*path).is_absolute() ? fs::path(*path) : dataset.root / *path;
  }
  Result<yaml::Node> names = root->Get("names");
  if (!names.ok()) return names.status();
  if (!names->IsSequence() || names->size() == 0) {
    return names->Error("expected a list of class names");
  }
  for (std::size_t i = 0; i < names->size(); ++i) {
    Result<std::string> name = names->At(i).AsString();
    if (!name.ok()) return name.status();
    dataset.names.push_back(*name);
  }
  if (root->Has("nc")) {
    int nc = 0;
    SEMCHAIN_RETURN_IF_ERROR(yaml::ReadOptional(*root, "nc", &nc));
    if (nc != static_cast<int>(dataset.names.size())) {
      return root->Get("nc")->Error("nc is " + std::to_string(nc) + " but names lists " +
                                    std::to_string(dataset.names.size()) + " classes");
    }
  }
  for (auto [key, folder] :
       {std::pair{"train", &dataset.train}, {"val", &dataset.val}, {"test", &dataset.test}}) {
    if (!root->Has(key)) continue;
    Result<std::string> text = root->Get(key)->AsString();
    if (!text.ok()) return text.status();
    *folder = fs::path(*text).is_absolute() ? fs::path(*text) : dataset.root / *text;
  }
  if (dataset.train.empty() && dataset.val.empty() && dataset.test.empty()) {
    return Status::Error(data_yaml.string() + ": no split (train, val or test) is given");
  }
  return dataset;
}

Result<std::vector<fs::path>> SplitImages(const YoloDataset& dataset, const std::string& split) {
  const fs::path folder = split == "train"  ? dataset.train
                          : split == "val"  ? dataset.val
                          : split == "test" ? dataset.test
                                            : fs::path();
  if (split != "train" && split != "val" && split != "test") {
    return Status::Error("split '" + split + "': expected train, val or test");
  }
  if (folder.empty()) return Status::Error("the data set has no " + split + " split");
  std::error_code error;
  if (!fs::is_directory(folder, error)) {
    return Status::Error(folder.string() + ": the " + split + " split's folder does not exist");
  }
  std::vector<fs::path> images;
  for (const auto& entry : fs::directory_iterator(folder)) {
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(), ::tolower);
    if (extension == ".png" || extension == ".jpg" || extension == ".jpeg" || extension == ".bmp") {
      images.push_back(entry.path());
    }
  }
  if (images.empty()) return Status::Error(folder.string() + ": no images");
  std::sort(images.begin(), images.end());
  return images;
}

fs::path LabelPathOf(const fs::path& image) {
  fs::path label;
  bool replaced = false;
  std::vector<fs::path> parts(image.begin(), image.end());
  // The last "images" component becomes "labels".
  for (std::size_t i = parts.size(); i-- > 0 && !replaced;) {
    if (parts[i] == "images") parts[i] = "labels", replaced = true;
  }
  for (const fs::path& part : parts) label /= part;
  return label.replace_extension(".txt");
}

}  // namespace semchain::detection
