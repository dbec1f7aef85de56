#include "apps/reloc_drawing.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>

#include "apps/map_grey.h"
#include "apps/semantic_drawing.h"
#include "drawing/canvas.h"
#include "drawing/pixels.h"
#include "drawing/plots.h"
#include "drawing/png.h"

namespace semchain::app {
namespace {

// The time ramp of the particle clouds, light amber (oldest) over orange to dark brown
// (latest): the order reads at a glance, and the arrows drawn over the clouds keep colours
// outside it.
constexpr drawing::Color kRamp[] = {{255, 205, 110}, {240, 120, 20}, {120, 30, 0}};
constexpr drawing::Color kTruthColor = {0, 160, 60};
constexpr drawing::Color kEstimateColor = {0, 90, 255};
constexpr drawing::Color kPrelocalizationColor = {150, 50, 200};
constexpr drawing::Color kScanMatchColor = {0, 0, 0};
constexpr int kMarginPx = 30;  // room for the title above the map
constexpr int kLegendWidthPx = 380;

// The colour of the rank-th of 'count' clouds, piecewise linear along kRamp.
drawing::Color RampColor(std::size_t rank, std::size_t count) {
  const double t = count > 1 ? static_cast<double>(rank) / static_cast<double>(count - 1) : 1.0;
  const double position = t * static_cast<double>(std::size(kRamp) - 1);
  const std::size_t low = std::min(static_cast<std::size_t>(position), std::size(kRamp) - 2);
  const double f = position - static_cast<double>(low);
  drawing::Color color;
  for (std::size_t c = 0; c < color.size(); ++c) {
    color[c] =
        static_cast<std::uint8_t>(std::lround((1.0 - f) * kRamp[low][c] + f * kRamp[low + 1][c]));
  }
  return color;
}

std::string Seconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof(text), "t = %.1f s", seconds);
  return text;
}

// Scan matchers have no particles before their match: those drawn are of the AMCL that
// tracks from there.
bool IsScanMatcher(const std::string& method) {
  return method.find("scanmatch") != std::string::npos;
}

// The first snapshot at or after the pre-localization, if any.
std::optional<std::size_t> PrelocalizedSnapshot(
    const std::vector<localization::ParticleSnapshot>& snapshots, int prelocalization_scan) {
  for (std::size_t i = 0; prelocalization_scan >= 0 && i < snapshots.size(); ++i) {
    if (snapshots[i].scan >= prelocalization_scan) return i;
  }
  return std::nullopt;
}

double StartTime(const RelocPictureOptions& options) {
  return options.scan_times.empty() ? 0.0 : options.scan_times.front();
}

// An arrow 'length_px' long from the pose's position along its heading, over a dot.
void DrawPoseArrow(const Pose2& pose, const drawing::Color& color, double length_px,
                   drawing::TopDownCanvas& canvas) {
  const Eigen::Vector2d tip =
      pose.translation() +
      (length_px / canvas.scale()) * Eigen::Vector2d(std::cos(pose.theta), std::sin(pose.theta));
  const cv::Point from = canvas.ToPixel(pose.translation());
  cv::circle(canvas.image(), from, 5, drawing::Bgr(color), -1, cv::LINE_AA);
  cv::arrowedLine(canvas.image(), from, canvas.ToPixel(tip), drawing::Bgr(color), 3, cv::LINE_AA, 0,
                  0.35);
}

void DrawCloud(const localization::ParticleSnapshot& snapshot, const drawing::Color& color,
               drawing::TopDownCanvas& canvas) {
  for (const Pose2& pose : snapshot.poses) {
    cv::circle(canvas.image(), canvas.ToPixel(pose.translation()), 2, drawing::Bgr(color), -1);
  }
}

// The legend line of a drawn snapshot: its time and why it was chosen.
std::string SnapshotLabel(const localization::ParticleSnapshot& snapshot, std::size_t index,
                          std::size_t count, std::optional<std::size_t> prelocalized,
                          const RelocPictureOptions& options) {
  const bool tracking = IsScanMatcher(options.method);
  std::vector<std::string> tags;
  if (index == 0) tags.push_back(tracking ? "tracking starts" : "first update");
  if (!tracking && prelocalized && index == *prelocalized) tags.push_back("pre-localized");
  if (index + 1 == count) tags.push_back("last");
  std::string label = "particles, " + Seconds(snapshot.time - StartTime(options));
  for (std::size_t i = 0; i < tags.size(); ++i) label += (i == 0 ? " (" : ", ") + tags[i];
  return tags.empty() ? label : label + ")";
}

// The scan at which a scan matcher first gave a pose (its match), if any.
std::optional<std::size_t> FirstEstimate(const localization::RelocTrace& trace) {
  for (std::size_t i = 0; i < trace.estimates.size(); ++i) {
    if (trace.estimates[i]) return i;
  }
  return std::nullopt;
}

// The truth, the pre-localization, a scan matcher's match and the final estimate.
void DrawPoses(const localization::RelocTrace& trace, const RelocPictureOptions& options,
               drawing::TopDownCanvas& canvas) {
  if (!options.truth.empty()) drawing::DrawTrajectory(options.truth, kTruthColor, "truth", canvas);
  if (trace.prelocalization) {
    DrawPoseArrow(*trace.prelocalization, kPrelocalizationColor, 30.0, canvas);
    canvas.AddLegend("pre-localization (best hypothesis)", kPrelocalizationColor,
                     drawing::TopDownCanvas::Swatch::kLine);
  }
  // A scan matcher has no particles before its match; where and when it matched is its story.
  const std::optional<std::size_t> matched = FirstEstimate(trace);
  if (IsScanMatcher(options.method) && matched) {
    DrawPoseArrow(*trace.estimates[*matched], kScanMatchColor, 30.0, canvas);
    const double time = *matched < options.scan_times.size()
                            ? options.scan_times[*matched] - StartTime(options)
                            : 0.0;
    canvas.AddLegend("scan match, " + Seconds(time), kScanMatchColor,
                     drawing::TopDownCanvas::Swatch::kLine);
  }
  if (!trace.estimates.empty() && trace.estimates.back()) {
    DrawPoseArrow(*trace.estimates.back(), kEstimateColor, 40.0, canvas);
    canvas.AddLegend("final estimate", kEstimateColor, drawing::TopDownCanvas::Swatch::kLine);
  }
}

}  // namespace

std::vector<std::size_t> SelectSnapshots(
    const std::vector<localization::ParticleSnapshot>& snapshots, int prelocalization_scan,
    int max_count) {
  if (snapshots.empty() || max_count <= 0) return {};
  const std::size_t n = snapshots.size();
  std::set<std::size_t> chosen = {0, n - 1};
  if (const auto prelocalized = PrelocalizedSnapshot(snapshots, prelocalization_scan)) {
    chosen.insert(*prelocalized);
  }
  const std::size_t wanted = std::min(n, static_cast<std::size_t>(std::max(2, max_count)));
  for (std::size_t k = 1; chosen.size() < wanted && k + 1 < wanted; ++k) {
    chosen.insert((k * (n - 1) + (wanted - 1) / 2) / (wanted - 1));
  }
  for (std::size_t i = 0; chosen.size() < wanted; ++i) chosen.insert(i);
  std::vector<std::size_t> picked(chosen.begin(), chosen.end());
  if (picked.size() > static_cast<std::size_t>(max_count)) picked.erase(picked.begin());
  return picked;
}

Status WriteRelocalizationPng(const mapping::MapImage& map, const semantic::SemanticMap& semantic,
                              const localization::RelocTrace& trace,
                              const RelocPictureOptions& options,
                              const std::filesystem::path& path) {
  if (map.origin.z() != 0.0) {
    return Status::Error(path.string() + ": rotated map origins are not supported");
  }
  const Eigen::Vector2d size = map.resolution * Eigen::Vector2d(map.width, map.height);
  drawing::Bounds bounds;
  bounds.Add(map.origin.head<2>());
  bounds.Add(map.origin.head<2>() + size);
  drawing::DrawingOptions drawing;
  drawing.pixels_per_meter = options.long_side_px / std::max(size.x(), size.y());
  drawing.margin_px = kMarginPx;
  drawing.legend_width_px = kLegendWidthPx;
  Result<drawing::TopDownCanvas> canvas = drawing::TopDownCanvas::Create(bounds, drawing);
  if (!canvas.ok()) return canvas.status().WithContext(path.string());
  drawing::DrawGreyImage(MapToGrey(map), map.origin.head<2>(), map.resolution, *canvas);
  DrawSemanticMap(semantic, *canvas);

  const std::vector<localization::ParticleSnapshot>& snapshots = trace.particle_snapshots;
  const std::vector<std::size_t> drawn =
      SelectSnapshots(snapshots, trace.prelocalization_scan, options.max_snapshots);
  const std::optional<std::size_t> prelocalized =
      PrelocalizedSnapshot(snapshots, trace.prelocalization_scan);
  for (std::size_t rank = 0; rank < drawn.size(); ++rank) {
    const std::size_t i = drawn[rank];
    const drawing::Color color = RampColor(rank, drawn.size());
    DrawCloud(snapshots[i], color, *canvas);
    canvas->AddLegend(SnapshotLabel(snapshots[i], i, snapshots.size(), prelocalized, options),
                      color, drawing::TopDownCanvas::Swatch::kDot);
  }
  if (snapshots.empty()) {
    canvas->AddLegend("no particles: the filter never updated", kRamp[std::size(kRamp) - 1],
                      drawing::TopDownCanvas::Swatch::kDot);
  }
  DrawPoses(trace, options, *canvas);
  cv::putText(canvas->image(), "semchain localize --method " + options.method, {kMarginPx, 20},
              cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  return drawing::WritePng(canvas->Compose(), path);
}

}  // namespace semchain::app
