#include "eval/reloc_methods.h"

namespace semchain::eval {

localization::RelocTrace RunRelocMethod(localization::LocalizationMethod method,
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
  localization::RelocTraceRecorder recorder(inputs.record_particles_every,
                                            inputs.record_particles_max);
  for (const StampedScan& scan : inputs.scans) recorder.AddScan(scan, localizer);
  return recorder.Finish(localizer);
}

}  // namespace semchain::eval
