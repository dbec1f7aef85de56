#include "ros/object_markers.h"

#include <unordered_map>

#include "ros/ros_geometry.h"

namespace semchain::ros1 {
namespace {

visualization_msgs::Marker MakeMarker(const std::string& frame_id, const std::string& ns, int id,
                                      int type) {
  visualization_msgs::Marker marker;
  marker.header.frame_id = frame_id;
  marker.ns = ns;
  marker.id = id;
  marker.type = type;
  marker.action = visualization_msgs::Marker::ADD;
  marker.pose.orientation.w = 1.0;
  marker.scale.x = marker.scale.y = marker.scale.z = 0.05;
  marker.color.a = 1.0f;
  return marker;
}

geometry_msgs::Point Point(const Eigen::Vector2d& p, double z = 0.0) {
  geometry_msgs::Point point;
  point.x = p.x();
  point.y = p.y();
  point.z = z;
  return point;
}

// A colour per class name, fixed by the name (the same class looks the same on every map).
void ClassColor(const std::string& name, std::uint8_t* rgb) {
  std::uint32_t hash = 2166136261u;
  for (const char c : name) hash = (hash ^ static_cast<std::uint8_t>(c)) * 16777619u;
  rgb[0] = static_cast<std::uint8_t>(80 + hash % 176);
  rgb[1] = static_cast<std::uint8_t>(80 + (hash >> 8) % 176);
  rgb[2] = static_cast<std::uint8_t>(80 + (hash >> 16) % 176);
}

}  // namespace

visualization_msgs::MarkerArray ObjectMarkers(
    const semantic::SemanticMap& map, const std::vector<localization::PoseHypothesis>& hypotheses,
    const std::string& frame_id) {
  visualization_msgs::MarkerArray array;
  // A DELETEALL first: fewer hypotheses than last time must not leave old arrows behind.
  visualization_msgs::Marker clear;
  clear.header.frame_id = frame_id;
  clear.action = visualization_msgs::Marker::DELETEALL;
  array.markers.push_back(clear);

  std::unordered_map<int, Eigen::Vector2d> centers;
  for (const semantic::SemanticObject& object : map.objects) {
    centers[object.id] = object.center;
    std::uint8_t rgb[3];
    ClassColor(object.class_name, rgb);
    visualization_msgs::Marker outline =
        MakeMarker(frame_id, "objects", object.id, visualization_msgs::Marker::LINE_STRIP);
    outline.color.r = rgb[0] / 255.0f;
    outline.color.g = rgb[1] / 255.0f;
    outline.color.b = rgb[2] / 255.0f;
    for (const Eigen::Vector2d& corner : object.footprint) outline.points.push_back(Point(corner));
    if (!object.footprint.empty()) outline.points.push_back(Point(object.footprint.front()));
    array.markers.push_back(outline);

    visualization_msgs::Marker label =
        MakeMarker(frame_id, "labels", object.id, visualization_msgs::Marker::TEXT_VIEW_FACING);
    label.pose.position = Point(object.center, 0.3);
    label.scale.z = 0.2;
    label.color.r = label.color.g = label.color.b = 1.0f;
    label.text = object.class_name + " " + std::to_string(object.id);
    array.markers.push_back(label);
  }

  int chain_id = 0;
  for (const semantic::SemanticChain& chain : map.chains) {
    visualization_msgs::Marker line =
        MakeMarker(frame_id, "chains", chain_id++, visualization_msgs::Marker::LINE_STRIP);
    line.scale.x = 0.03;
    line.color.r = 1.0f;
    line.color.g = 0.8f;
    for (const int id : chain.order) {
      const auto found = centers.find(id);
      if (found != centers.end()) line.points.push_back(Point(found->second, 0.05));
    }
    if (line.points.size() > 2) line.points.push_back(line.points.front());
    if (line.points.size() >= 2) array.markers.push_back(line);
  }

  int hypothesis_id = 0;
  for (const localization::PoseHypothesis& h : hypotheses) {
    visualization_msgs::Marker arrow =
        MakeMarker(frame_id, "hypotheses", hypothesis_id++, visualization_msgs::Marker::ARROW);
    arrow.pose = ToPoseMsg(h.pose);
    arrow.scale.x = 0.5;
    arrow.scale.y = arrow.scale.z = 0.08;
    arrow.color.g = 1.0f;
    arrow.color.b = 1.0f;
    array.markers.push_back(arrow);
  }
  return array;
}

}  // namespace semchain::ros1
