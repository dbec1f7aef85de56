#pragma once

#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <string>

#include "apps/semantic_outputs.h"
#include "core/status.h"
#include "mapping/slam_pipeline.h"
#include "semantic/live_semantic_run.h"

// `slam --semantic RUN`: the semantic map grown while SLAM runs, one pass (DESIGN.md §1).
namespace semchain::app {

struct SlamSemanticArgs {
  std::string run;  // empty: no semantic mapping
  DetectorArgs detector;
  double scale = 50.0;  // pixels per metre of semantic.png
  // Detections scoring lower do not enter the map (DetectionPointOptions::min_score).
  double min_detection_score = semantic::DetectionPointOptions().min_score;
};

class SlamSemantic {
 public:
  // Checks the run (and runs the detector) before SLAM starts; 'resolution' is the SLAM grid's.
  static Result<std::unique_ptr<SlamSemantic>> Open(const SlamSemanticArgs& args,
                                                    double resolution);

  // Starts reading the run's depth frames on another thread (LiveSemanticRun::Prepare) while
  // SLAM starts.
  void StartPreparing();

  // Feeds SLAM's progress to the semantic mapper (RunSlam's 'observe'); the first error stops
  // it and is returned by Finish.
  void Observe(const mapping::SlamStep& step);

  // The semantic map on SLAM's final trajectory and map.
  Result<semantic::LiveSemanticResult> Finish(const std::vector<StampedPose>& trajectory,
                                              const mapping::MapImage& map);

  // The keyframes of 'result' with the run they are in (MAP/keyframes.json).
  semantic::KeyframeDatabase Keyframes(const semantic::LiveSemanticResult& result) const;

  // Writes OUT/semantic.png and OUT/semantic_growth.json (the map folder writer writes
  // semantic.json and keyframes.json).
  Status WriteExtras(const std::filesystem::path& out, const mapping::MapImage& map,
                     const semantic::LiveSemanticResult& result) const;

 private:
  SlamSemantic(SlamSemanticArgs args, std::unique_ptr<semantic::LiveSemanticRun> live);

  SlamSemanticArgs args_;
  std::unique_ptr<semantic::LiveSemanticRun> live_;
  std::future<Status> prepared_;
  Status status_ = Status::Ok();
  double seconds_ = 0.0;  // spent in the semantic mapping during SLAM
};

}  // namespace semchain::app
