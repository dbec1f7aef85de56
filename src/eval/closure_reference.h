#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "core/pose2.h"
#include "eval/relations.h"
#include "io/trajectory_io.h"

// What a loop-closure candidate is judged against (`semchain bench closures`): the reference's
// pose of one scan of the log in the frame of another. Three kinds of reference: poses paired
// with the scans by index (a corrected log's own poses), timed reference poses (a simulated
// run's truth, the Killian reference), and Kümmerle relations. Where a scan has no reference
// of its own, the log's odometry bridges it to the nearest scan that has one, over a short
// stretch only (its error grows with the travel and the turning); a pair the reference cannot
// join within that is left unlabelled.
namespace semchain::eval {

// The log's scans as the reference joins them: their timestamps and odometry, in log order.
struct ScanTrack {
  std::vector<double> timestamps;
  std::vector<Pose2> odometry;
};

struct ClosureReferenceOptions {
  // A reference timestamp belongs to the scan stamped within this many seconds of it.
  double timestamp_tolerance_s = 1e-3;
  // The odometry bridges at most this much travel (metres, summed along the log) and this much
  // turning (radians, summed: a robot turning on the spot travels nowhere, but its odometry's
  // heading error grows with the turn)...
  double max_bridge_meters = 2.0;
  double max_bridge_radians = 0.2;
  // ...and the relation reference joins two scans only along a path whose error, estimated as
  // relation_sigma_meters a relation plus bridge_sigma_meters + bridge_sigma_per_meter × travel
  // a bridge, stays within max_path_error_meters (well inside the 0.3 m a candidate may be off).
  double relation_sigma_meters = 0.01;
  double bridge_sigma_meters = 0.01;
  double bridge_sigma_per_meter = 0.03;
  double max_path_error_meters = 0.1;
};

class ClosureReference {
 public:
  virtual ~ClosureReference() = default;
  // The pose of scan 'to' in the frame of scan 'from' (indices into the log's scans), or
  // nothing where the reference cannot say.
  virtual std::optional<Pose2> Relative(int from, int to) const = 0;
};

// 'poses' paired with the scans by index (one per scan, in log order).
std::unique_ptr<ClosureReference> MakeIndexedReference(std::vector<Pose2> poses);

// Timed reference poses, each at the scan stamped with its time (others are ignored); a scan
// without one takes the nearest one (by travel) within max_bridge_meters and
// max_bridge_radians, moved by the odometry between them.
std::unique_ptr<ClosureReference> MakeTimedReference(const std::vector<StampedPose>& reference,
                                                     ScanTrack scans,
                                                     const ClosureReferenceOptions& options = {});

// Relations, each between the two scans stamped with its times (others are ignored); two scans
// are joined by the path of relations and odometry bridges (within max_bridge_meters and
// max_bridge_radians each, between
// scans of the log that are next to each other among those with a relation) of least
// estimated error, when that is within max_path_error_meters.
std::unique_ptr<ClosureReference> MakeRelationReference(
    const std::vector<Relation>& relations, ScanTrack scans,
    const ClosureReferenceOptions& options = {});

}  // namespace semchain::eval
