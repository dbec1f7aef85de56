#include "localization/reloc_trace.h"

#include <algorithm>
#include <utility>

#include "core/cpu_time.h"

namespace semchain::localization {
namespace {

// At most 'max_kept' of the particles, evenly strided (after resampling their order carries
// no meaning, so a stride is a fair sample).
ParticleSnapshot Subsample(const std::vector<Particle>& particles, int max_kept) {
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

}  // namespace

RelocTraceRecorder::RelocTraceRecorder(int particles_every, int particles_kept)
    : particles_every_(particles_every), particles_kept_(particles_kept) {}

void RelocTraceRecorder::AddScan(const StampedScan& scan, Localizer& localizer) {
  const double start = ThreadCpuSeconds();
  localizer.AddScan(scan);
  cpu_seconds_ += ThreadCpuSeconds() - start;
  const LocalizerStatistics& statistics = localizer.statistics();
  if (statistics.first_prelocalization && trace_.prelocalization_scan < 0) {
    trace_.prelocalization = statistics.first_prelocalization;
    trace_.prelocalization_scan = static_cast<int>(trace_.estimates.size());
  }
  trace_.estimates.push_back(localizer.pose());
  trace_.cpu_seconds.push_back(cpu_seconds_);
  trace_.search_cpu_seconds.push_back(statistics.search_cpu_seconds);
  trace_.iterations.push_back(statistics.iterations);
  if (particles_every_ > 0) RecordParticles(localizer.filter(), scan);
}

// After a filter update, keeps the particles when RelocTrace::particle_snapshots asks for them;
// any other update waits in 'unrecorded_' in case it turns out to be the last.
void RelocTraceRecorder::RecordParticles(const Amcl& filter, const StampedScan& scan) {
  const int updates = filter.counters().updates;
  if (updates == recorded_updates_) return;
  recorded_updates_ = updates;
  const bool after_prelocalization = trace_.prelocalization_scan >= 0 && !snapped_prelocalized_;
  ParticleSnapshot snapshot = Subsample(filter.particles(), particles_kept_);
  snapshot.scan = static_cast<int>(trace_.estimates.size()) - 1;
  snapshot.time = scan.scan.timestamp;
  unrecorded_.reset();
  if (trace_.particle_snapshots.empty() || after_prelocalization ||
      updates % particles_every_ == 0) {
    snapped_prelocalized_ = snapped_prelocalized_ || after_prelocalization;
    trace_.particle_snapshots.push_back(std::move(snapshot));
  } else {
    unrecorded_ = std::move(snapshot);
  }
}

RelocTrace RelocTraceRecorder::Finish(const Localizer& localizer) {
  if (unrecorded_) trace_.particle_snapshots.push_back(std::move(*unrecorded_));
  unrecorded_.reset();
  const LocalizerStatistics& statistics = localizer.statistics();
  trace_.prelocalizations = statistics.prelocalizations;
  trace_.single_object_prelocalizations = statistics.single_object_prelocalizations;
  trace_.hidden_object_prelocalizations = statistics.hidden_object_prelocalizations;
  trace_.undecided_prelocalizations = statistics.undecided_prelocalizations;
  trace_.lock_corrections = statistics.lock_corrections;
  trace_.lock_rechecks = statistics.lock_rechecks;
  return std::move(trace_);
}

}  // namespace semchain::localization
