#include "semantic/semantic_map_io.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "core/atomic_file.h"

namespace semchain::semantic {
namespace {

using nlohmann::json;

json Point(const Eigen::Vector2d& p) { return json::array({p.x(), p.y()}); }

json Link(const ChainLink& link) {
  return {{"from", link.from}, {"to", link.to}, {"distance", link.distance}};
}

// Field-by-field checks with the path of the field in every error.
class Reader {
 public:
  explicit Reader(std::string source) : source_(std::move(source)) {}

  Status Error(const std::string& path, const std::string& what) const {
    return Status::Error(source_ + ": " + path + ": " + what);
  }
  Result<const json*> Member(const json& object, const std::string& path,
                             const std::string& key) const {
    if (!object.is_object()) return Error(path, "expected an object");
    const auto it = object.find(key);
    if (it == object.end()) return Error(Join(path, key), "missing");
    return &*it;
  }
  Result<double> Number(const json& node, const std::string& path) const {
    if (!node.is_number()) return Error(path, "expected a number");
    const double value = node.get<double>();
    if (!std::isfinite(value)) return Error(path, "not finite");
    return value;
  }
  Result<int> Integer(const json& node, const std::string& path) const {
    if (!node.is_number_integer()) return Error(path, "expected an integer");
    return node.get<int>();
  }
  Result<Eigen::Vector2d> Point2(const json& node, const std::string& path) const {
    if (!node.is_array() || node.size() != 2 || !node[0].is_number() || !node[1].is_number()) {
      return Error(path, "expected 2 numbers");
    }
    const Eigen::Vector2d p(node[0].get<double>(), node[1].get<double>());
    if (!p.allFinite()) return Error(path, "not finite");
    return p;
  }
  Result<ChainLink> LinkOf(const json& node, const std::string& path) const {
    ChainLink link;
    for (const auto& [key, field] : {std::pair{"from", &link.from}, std::pair{"to", &link.to}}) {
      Result<const json*> member = Member(node, path, key);
      if (!member.ok()) return member.status();
      Result<int> value = Integer(**member, Join(path, key));
      if (!value.ok()) return value.status();
      *field = *value;
    }
    Result<const json*> distance = Member(node, path, "distance");
    if (!distance.ok()) return distance.status();
    Result<double> value = Number(**distance, Join(path, "distance"));
    if (!value.ok()) return value.status();
    link.distance = *value;
    return link;
  }
  static std::string Join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  static std::string Index(const std::string& path, std::size_t i) {
    return path + "[" + std::to_string(i) + "]";
  }

 private:
  std::string source_;
};

Result<SemanticObject> ReadObject(const Reader& r, const json& node, const std::string& path,
                                  const std::set<std::string>& classes) {
  SemanticObject object;
  Result<const json*> id = r.Member(node, path, "id");
  if (!id.ok()) return id.status();
  Result<int> id_value = r.Integer(**id, Reader::Join(path, "id"));
  if (!id_value.ok()) return id_value.status();
  object.id = *id_value;
  Result<const json*> name = r.Member(node, path, "class");
  if (!name.ok()) return name.status();
  if (!(*name)->is_string() || !classes.count((*name)->get<std::string>())) {
    return r.Error(Reader::Join(path, "class"), "not one of \"classes\"");
  }
  object.class_name = (*name)->get<std::string>();
  Result<const json*> center = r.Member(node, path, "center");
  if (!center.ok()) return center.status();
  Result<Eigen::Vector2d> center_value = r.Point2(**center, Reader::Join(path, "center"));
  if (!center_value.ok()) return center_value.status();
  object.center = *center_value;
  Result<const json*> footprint = r.Member(node, path, "footprint");
  if (!footprint.ok()) return footprint.status();
  if (!(*footprint)->is_array()) return r.Error(Reader::Join(path, "footprint"), "expected a list");
  for (std::size_t i = 0; i < (*footprint)->size(); ++i) {
    Result<Eigen::Vector2d> p =
        r.Point2((**footprint)[i], Reader::Index(Reader::Join(path, "footprint"), i));
    if (!p.ok()) return p.status();
    object.footprint.push_back(*p);
  }
  Result<const json*> observations = r.Member(node, path, "observations");
  if (!observations.ok()) return observations.status();
  Result<int> count = r.Integer(**observations, Reader::Join(path, "observations"));
  if (!count.ok()) return count.status();
  object.observations = *count;
  Result<const json*> confidence = r.Member(node, path, "confidence");
  if (!confidence.ok()) return confidence.status();
  Result<double> value = r.Number(**confidence, Reader::Join(path, "confidence"));
  if (!value.ok()) return value.status();
  if (*value < 0.0 || *value > 1.0)
    return r.Error(Reader::Join(path, "confidence"), "not in [0, 1]");
  object.confidence = *value;
  return object;
}

}  // namespace

std::string FormatSemanticJson(const SemanticMap& map) {
  json objects = json::array();
  for (const SemanticObject& object : map.objects) {
    json footprint = json::array();
    for (const Eigen::Vector2d& p : object.footprint) footprint.push_back(Point(p));
    objects.push_back({{"id", object.id},
                       {"class", object.class_name},
                       {"center", Point(object.center)},
                       {"footprint", footprint},
                       {"observations", object.observations},
                       {"confidence", object.confidence}});
  }
  json chains = json::array();
  for (const SemanticChain& chain : map.chains) {
    json links = json::array();
    for (const ChainLink& link : chain.links) links.push_back(Link(link));
    chains.push_back({{"region", chain.region}, {"order", chain.order}, {"links", links}});
  }
  json neighbours = json::array();
  for (const ChainLink& link : map.neighbours) neighbours.push_back(Link(link));
  const json root = {{"version", 1},       {"frame", "map"},   {"classes", map.classes},
                     {"objects", objects}, {"chains", chains}, {"neighbours", neighbours}};
  return root.dump(1) + "\n";
}

Status WriteSemanticJson(const std::filesystem::path& path, const SemanticMap& map) {
  return WriteFileAtomically(path, FormatSemanticJson(map));
}

Result<SemanticMap> ReadSemanticJson(const std::filesystem::path& path) {
  Result<std::string> text = ReadFile(path);
  if (!text.ok()) return text.status();
  const Reader r(path.string());
  json root;
  try {
    root = json::parse(*text);
  } catch (const json::parse_error& error) {
    // nlohmann reports a byte offset; users want the line.
    const std::size_t byte = std::min<std::size_t>(error.byte, text->size());
    const long line = 1 + std::count(text->begin(), text->begin() + static_cast<long>(byte), '\n');
    return Status::Error(path.string() + ":" + std::to_string(line) + ": not valid JSON");
  } catch (const json::exception&) {  // out_of_range: a number beyond a double's range
    return Status::Error(path.string() + ": not valid JSON (a number out of range)");
  }
  SemanticMap map;
  Result<const json*> version = r.Member(root, "", "version");
  if (!version.ok()) return version.status();
  if (!(*version)->is_number_integer() || (*version)->get<int>() != 1) {
    return r.Error("version", "unsupported (expected 1)");
  }
  Result<const json*> classes = r.Member(root, "", "classes");
  if (!classes.ok()) return classes.status();
  if (!(*classes)->is_array()) return r.Error("classes", "expected a list of names");
  std::set<std::string> class_set;
  for (const json& name : **classes) {
    if (!name.is_string()) return r.Error("classes", "expected a list of names");
    map.classes.push_back(name.get<std::string>());
    class_set.insert(map.classes.back());
  }
  Result<const json*> objects = r.Member(root, "", "objects");
  if (!objects.ok()) return objects.status();
  if (!(*objects)->is_array()) return r.Error("objects", "expected a list");
  std::set<int> ids;
  for (std::size_t i = 0; i < (*objects)->size(); ++i) {
    const std::string where = Reader::Index("objects", i);
    Result<SemanticObject> object = ReadObject(r, (**objects)[i], where, class_set);
    if (!object.ok()) return object.status();
    if (!ids.insert(object->id).second) return r.Error(where + ".id", "repeated");
    map.objects.push_back(*object);
  }
  const auto check_link = [&](const ChainLink& link, const std::string& where) {
    if (!ids.count(link.from) || !ids.count(link.to)) {
      return r.Error(where, "names an object that is not in \"objects\"");
    }
    return Status::Ok();
  };
  Result<const json*> chains = r.Member(root, "", "chains");
  if (!chains.ok()) return chains.status();
  if (!(*chains)->is_array()) return r.Error("chains", "expected a list");
  for (std::size_t i = 0; i < (*chains)->size(); ++i) {
    const std::string where = Reader::Index("chains", i);
    const json& node = (**chains)[i];
    SemanticChain chain;
    Result<const json*> region = r.Member(node, where, "region");
    if (!region.ok()) return region.status();
    Result<int> region_value = r.Integer(**region, where + ".region");
    if (!region_value.ok()) return region_value.status();
    chain.region = *region_value;
    Result<const json*> order = r.Member(node, where, "order");
    if (!order.ok()) return order.status();
    if (!(*order)->is_array()) return r.Error(where + ".order", "expected a list of ids");
    for (const json& id : **order) {
      if (!id.is_number_integer() || !ids.count(id.get<int>())) {
        return r.Error(where + ".order", "names an object that is not in \"objects\"");
      }
      chain.order.push_back(id.get<int>());
    }
    Result<const json*> links = r.Member(node, where, "links");
    if (!links.ok()) return links.status();
    if (!(*links)->is_array()) return r.Error(where + ".links", "expected a list");
    for (std::size_t j = 0; j < (*links)->size(); ++j) {
      const std::string link_where = Reader::Index(where + ".links", j);
      Result<ChainLink> link = r.LinkOf((**links)[j], link_where);
      if (!link.ok()) return link.status();
      SEMCHAIN_RETURN_IF_ERROR(check_link(*link, link_where));
      chain.links.push_back(*link);
    }
    map.chains.push_back(std::move(chain));
  }
  Result<const json*> neighbours = r.Member(root, "", "neighbours");
  if (!neighbours.ok()) return neighbours.status();
  if (!(*neighbours)->is_array()) return r.Error("neighbours", "expected a list");
  for (std::size_t i = 0; i < (*neighbours)->size(); ++i) {
    const std::string where = Reader::Index("neighbours", i);
    Result<ChainLink> link = r.LinkOf((**neighbours)[i], where);
    if (!link.ok()) return link.status();
    SEMCHAIN_RETURN_IF_ERROR(check_link(*link, where));
    map.neighbours.push_back(*link);
  }
  return map;
}

}  // namespace semchain::semantic
