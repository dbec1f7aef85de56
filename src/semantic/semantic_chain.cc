#include "semantic/semantic_chain.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <map>
#include <opencv2/imgproc.hpp>
#include <set>

#include "mapping/distance_field.h"

namespace semchain::semantic {
namespace {

// Signed distance from 'point' to the polygon (positive inside), metres.
double DistanceToFootprint(const SemanticObject& object, const Eigen::Vector2d& point) {
  if (object.footprint.size() < 3) return -(point - object.center).norm();
  std::vector<cv::Point2f> polygon;
  for (const Eigen::Vector2d& p : object.footprint) {
    polygon.emplace_back(static_cast<float>(p.x()), static_cast<float>(p.y()));
  }
  return cv::pointPolygonTest(
      polygon, cv::Point2f(static_cast<float>(point.x()), static_cast<float>(point.y())), true);
}

// True when the segment from 'from' to 'to' crosses no occupied cell of 'map' farther than a
// margin outside the footprints of 'own' (the objects at its ends, whose own cells are occupied).
bool SegmentClear(const mapping::MapImage& map, const Eigen::Vector2d& from,
                  const Eigen::Vector2d& to, std::initializer_list<const SemanticObject*> own) {
  constexpr double kObjectMargin = 0.1;
  const GridGeometry geometry = GeometryOf(map);
  const double length = (to - from).norm();
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (0.5 * map.resolution))));
  for (int i = 0; i <= steps; ++i) {
    const Eigen::Vector2d p = from + (to - from) * (double(i) / steps);
    if (std::any_of(own.begin(), own.end(), [&p](const SemanticObject* object) {
          return DistanceToFootprint(*object, p) > -kObjectMargin;
        })) {
      continue;
    }
    const Eigen::Vector2i cell = geometry.CellOf(p);
    if (geometry.Contains(cell) &&
        mapping::ClassifyMapCell(map, cell.x(), cell.y()) == mapping::CellState::kOccupied) {
      return false;
    }
  }
  return true;
}

}  // namespace

GridGeometry GeometryOf(const mapping::MapImage& map) {
  return {map.width, map.height, map.resolution, map.origin.head<2>()};
}

RegionMap SegmentRegions(const mapping::MapImage& map, const ChainOptions& options) {
  RegionMap regions;
  cv::Mat free = mapping::MapCellMask(map, mapping::CellState::kFree);
  cv::Mat occupied = mapping::MapCellMask(map, mapping::CellState::kOccupied);
  // Laser beams at grazing incidence punch holes into walls; closing the walls first keeps the
  // regions from leaking through them (doorways are far wider than the kernel).
  if (options.wall_closing_kernel > 1) {
    cv::morphologyEx(
        occupied, occupied, cv::MORPH_CLOSE,
        cv::getStructuringElement(
            cv::MORPH_RECT, cv::Size(options.wall_closing_kernel, options.wall_closing_kernel)));
    free.setTo(0, occupied);
  }
  regions.labels = cv::Mat(map.height, map.width, CV_32SC1, cv::Scalar(-1));
  if (map.width == 0 || map.height == 0) return regions;
  // Distance (cells) from each free cell to the nearest cell that is not free.
  cv::Mat distance;
  cv::distanceTransform(free, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  cv::Mat cores;
  cv::compare(distance, options.doorway_half_width / map.resolution, cores, cv::CMP_GT);
  cv::Mat core_labels, stats, centroids;
  const int count = cv::connectedComponentsWithStats(cores, core_labels, stats, centroids, 8);
  const double min_cells = options.min_region_area / (map.resolution * map.resolution);
  std::vector<int> region_of_core(count, -1);
  int regions_count = 0;
  for (int label = 1; label < count; ++label) {
    if (stats.at<int>(label, cv::CC_STAT_AREA) >= min_cells)
      region_of_core[label] = regions_count++;
  }
  // Multi-source breadth-first growth through free space: each free cell joins the core it
  // reaches first (a geodesic Voronoi partition of the free space).
  std::deque<cv::Point> queue;
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const int region = region_of_core[core_labels.at<int>(y, x)];
      if (core_labels.at<int>(y, x) > 0 && region >= 0) {
        regions.labels.at<int>(y, x) = region;
        queue.emplace_back(x, y);
      }
    }
  }
  while (!queue.empty()) {
    const cv::Point p = queue.front();
    queue.pop_front();
    const int region = regions.labels.at<int>(p.y, p.x);
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int x = p.x + dx;
        const int y = p.y + dy;
        if (x < 0 || y < 0 || x >= map.width || y >= map.height) continue;
        if (regions.labels.at<int>(y, x) >= 0 || !free.at<std::uint8_t>(y, x)) continue;
        regions.labels.at<int>(y, x) = region;
        queue.emplace_back(x, y);
      }
    }
  }
  std::vector<Eigen::Vector2d> sums(regions_count, Eigen::Vector2d::Zero());
  std::vector<int> counts(regions_count, 0);
  const GridGeometry geometry = GeometryOf(map);
  for (int y = 0; y < map.height; ++y) {
    for (int x = 0; x < map.width; ++x) {
      const int region = regions.labels.at<int>(y, x);
      if (region < 0) continue;
      sums[region] += geometry.CenterOf({x, y});
      ++counts[region];
    }
  }
  for (int r = 0; r < regions_count; ++r) regions.centers.push_back(sums[r] / counts[r]);
  return regions;
}

int RegionOf(const RegionMap& regions, const mapping::MapImage& map, const SemanticObject& object) {
  const GridGeometry geometry = GeometryOf(map);
  const Eigen::Vector2i cell = geometry.CellOf(object.center);
  int fallback = -1;
  long fallback_distance = std::numeric_limits<long>::max();
  // Rings outwards; in each ring the nearest cell in sight wins. Without any cell in sight
  // (an object inside unknown space), the nearest region cell is taken.
  const int max_radius = std::max(regions.labels.cols, regions.labels.rows);
  for (int radius = 0; radius <= max_radius; ++radius) {
    int best = -1;
    long best_distance = std::numeric_limits<long>::max();
    for (int y = cell.y() - radius; y <= cell.y() + radius; ++y) {
      for (int x = cell.x() - radius; x <= cell.x() + radius; ++x) {
        if (std::max(std::abs(x - cell.x()), std::abs(y - cell.y())) != radius) continue;
        if (x < 0 || y < 0 || x >= regions.labels.cols || y >= regions.labels.rows) continue;
        const int region = regions.labels.at<int>(y, x);
        if (region < 0) continue;
        const long d = static_cast<long>(x - cell.x()) * (x - cell.x()) +
                       static_cast<long>(y - cell.y()) * (y - cell.y());
        if (d < fallback_distance) {
          fallback_distance = d;
          fallback = region;
        }
        if (d < best_distance &&
            SegmentClear(map, object.center, geometry.CenterOf({x, y}), {&object})) {
          best_distance = d;
          best = region;
        }
      }
    }
    if (best >= 0) return best;
    if (fallback >= 0 && radius > 2 * (std::sqrt(static_cast<double>(fallback_distance)) + 1)) {
      break;
    }
  }
  return fallback;
}

std::vector<int> ClockwiseOrder(const std::vector<SemanticObject>& objects,
                                const Eigen::Vector2d& center) {
  std::vector<std::pair<double, int>> keyed;
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Eigen::Vector2d d = objects[i].center - center;
    // Angle clockwise from north, in [0, 2π).
    double key = M_PI / 2 - std::atan2(d.y(), d.x());
    key = std::fmod(key + 4 * M_PI, 2 * M_PI);
    keyed.emplace_back(key, static_cast<int>(i));
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<int> order;
  for (const auto& [key, index] : keyed) order.push_back(objects[index].id);
  const auto door = std::find_if(order.begin(), order.end(), [&](int id) {
    for (const SemanticObject& object : objects) {
      if (object.id == id) return object.class_name == "door";
    }
    return false;
  });
  if (door != order.end()) std::rotate(order.begin(), door, order.end());
  return order;
}

SemanticChain MakeChain(int region, const std::vector<int>& order,
                        const std::vector<SemanticObject>& objects) {
  SemanticChain chain;
  chain.region = region;
  chain.order = order;
  const auto center_of = [&](int id) {
    for (const SemanticObject& object : objects) {
      if (object.id == id) return object.center;
    }
    return Eigen::Vector2d(Eigen::Vector2d::Zero());
  };
  if (order.size() < 2) return chain;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int from = order[i];
    const int to = order[(i + 1) % order.size()];
    chain.links.push_back({from, to, (center_of(from) - center_of(to)).norm()});
  }
  return chain;
}

bool MutuallyVisible(const mapping::MapImage& map, const SemanticObject& a,
                     const SemanticObject& b) {
  return SegmentClear(map, a.center, b.center, {&a, &b});
}

int RegionOfViewed(const RegionMap& regions, const mapping::MapImage& map,
                   const SemanticObject& object, const std::vector<Eigen::Vector2d>& viewpoints) {
  const GridGeometry geometry = GeometryOf(map);
  std::map<int, int> votes;
  for (const Eigen::Vector2d& p : viewpoints) {
    const Eigen::Vector2i cell = geometry.CellOf(p);
    if (!geometry.Contains(cell)) continue;
    const int region = regions.labels.at<int>(cell.y(), cell.x());
    if (region >= 0) ++votes[region];
  }
  if (votes.empty()) return RegionOf(regions, map, object);
  return std::max_element(votes.begin(), votes.end(),
                          [](const auto& a, const auto& b) { return a.second < b.second; })
      ->first;
}

void BuildChainsAndNeighbours(const mapping::MapImage& occupancy, const ChainOptions& options,
                              const Viewpoints& viewpoints, SemanticMap* map) {
  map->chains.clear();
  map->neighbours.clear();
  const RegionMap regions = SegmentRegions(occupancy, options);
  std::map<int, std::vector<SemanticObject>> by_region;
  for (const SemanticObject& object : map->objects) {
    const auto seen_from = viewpoints.find(object.id);
    by_region[seen_from == viewpoints.end()
                  ? RegionOf(regions, occupancy, object)
                  : RegionOfViewed(regions, occupancy, object, seen_from->second)]
        .push_back(object);
  }
  for (const auto& [region, objects] : by_region) {
    Eigen::Vector2d center = Eigen::Vector2d::Zero();
    if (region >= 0) {
      center = regions.centers[region];
    } else {
      for (const SemanticObject& object : objects) center += object.center / objects.size();
    }
    map->chains.push_back(MakeChain(region, ClockwiseOrder(objects, center), objects));
  }

  std::set<std::pair<int, int>> edges;
  for (const SemanticObject& object : map->objects) {
    std::vector<std::pair<double, const SemanticObject*>> others;
    for (const SemanticObject& other : map->objects) {
      const double d = (other.center - object.center).norm();
      if (other.id != object.id && d <= options.max_neighbour_distance) {
        others.emplace_back(d, &other);
      }
    }
    std::sort(others.begin(), others.end(),
              [](const auto& x, const auto& y) { return x.first < y.first; });
    int taken = 0;
    for (const auto& [d, other] : others) {
      if (taken >= options.neighbours) break;
      if (!MutuallyVisible(occupancy, object, *other)) continue;
      edges.insert({std::min(object.id, other->id), std::max(object.id, other->id)});
      ++taken;
    }
  }
  for (const auto& [from, to] : edges) {
    map->neighbours.push_back({from, to, (map->Find(from)->center - map->Find(to)->center).norm()});
  }
}

}  // namespace semchain::semantic
