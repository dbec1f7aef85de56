#include "eval/reloc_methods.h"

#include <algorithm>

#include "core/cpu_time.h"

namespace semchain::eval {
namespace {

// At most 'max_kept' of the particles, evenly strided (after resampling their order carries
// no meaning, so a stride is a fair sample).
ParticleSnapshot Subsample(const std::vector<localization::Particle>& particles, int max_kept) {
  ParticleSnapshot snapshot;
  snapshot.particles = static_cast<int>(particles.size());
  const std::size_t kept = static_cast<std::size_t>(std::max(1, max_kept));
  const std::size_t stride = std::max<std::size_t>(1, (particles.size() + kept - 1) / kept);
  for (std::size_t i = 0; i < particles.size(); i += stride) {
    snapshot.poses.push_back(particles[i].pose);
    snapshot.weights.push_back(particles[i].weight);
  }
  return snapshot;
}

// After a filter update, keeps the particles when RelocTrace::particle_snapshots asks for them;
// any other update waits in 'unrecorded_' in case it turns out to be the last.
class ParticleRecorder {
 public:
  explicit ParticleRecorder(const RelocRunInputs& inputs) : inputs_(inputs) {}

  void Record(const localization::Amcl& filter, const StampedScan& scan, RelocTrace* trace) {
    const int updates = filter.counters().updates;
    if (updates == recorded_updates_) return;
    recorded_updates_ = updates;
    const bool after_prelocalization = trace->prelocalization_scan >= 0 && !snapped_prelocalized_;
    ParticleSnapshot snapshot = Subsample(filter.particles(), inputs_.record_particles_max);
    snapshot.scan = static_cast<int>(trace->estimates.size()) - 1;
    snapshot.time = scan.scan.timestamp;
    unrecorded_.reset();
    if (trace->particle_snapshots.empty() || after_prelocalization ||
        updates % inputs_.record_particles_every == 0) {
      snapped_prelocalized_ = snapped_prelocalized_ || after_prelocalization;
      trace->particle_snapshots.push_back(std::move(snapshot));
    } else {
      unrecorded_ = std::move(snapshot);
    }
  }

  void Finish(RelocTrace* trace) {
    if (unrecorded_) trace->particle_snapshots.push_back(std::move(*unrecorded_));
    unrecorded_.reset();
  }

 private:
  const RelocRunInputs& inputs_;
  int recorded_updates_ = 0;  // the filter's update count when last looked at
  bool snapped_prelocalized_ = false;
  std::optional<ParticleSnapshot> unrecorded_;
};

}  // namespace

RelocTrace RunRelocMethod(localization::LocalizationMethod method,
                          const localization::LocalizerMap& map,
                          const localization::LocalizerOptions& options,
                          const RelocRunInputs& inputs) {
  localization::LocalizerOptions seeded = options;
  seeded.seed = inputs.seed;
  localization::Localizer localizer(map, method, seeded);
  // The localizer keeps the frames until the scan they belong to; it reads an image only when
  // the bag of words asks for one.
  for (const RelocFrame& frame : inputs.frames) {
    localizer.AddFrame({frame.stamp, frame.detections, inputs.camera, cv::Mat(), frame.image});
  }
  RelocTrace trace;
  ParticleRecorder recorder(inputs);
  double cpu = 0.0;
  for (const StampedScan& scan : inputs.scans) {
    const double start = ThreadCpuSeconds();
    localizer.AddScan(scan);
    cpu += ThreadCpuSeconds() - start;
    const localization::LocalizerStatistics& statistics = localizer.statistics();
    if (statistics.first_prelocalization && trace.prelocalization_scan < 0) {
      trace.prelocalization = statistics.first_prelocalization;
      trace.prelocalization_scan = static_cast<int>(trace.estimates.size());
    }
    trace.estimates.push_back(localizer.pose());
    trace.cpu_seconds.push_back(cpu);
    trace.search_cpu_seconds.push_back(statistics.search_cpu_seconds);
    trace.iterations.push_back(statistics.iterations);
    if (inputs.record_particles_every > 0) recorder.Record(localizer.filter(), scan, &trace);
  }
  recorder.Finish(&trace);
  const localization::LocalizerStatistics& statistics = localizer.statistics();
  trace.prelocalizations = statistics.prelocalizations;
  trace.single_object_prelocalizations = statistics.single_object_prelocalizations;
  trace.hidden_object_prelocalizations = statistics.hidden_object_prelocalizations;
  trace.undecided_prelocalizations = statistics.undecided_prelocalizations;
  trace.lock_corrections = statistics.lock_corrections;
  trace.lock_rechecks = statistics.lock_rechecks;
  return trace;
}

}  // namespace semchain::eval
