#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/pose2.h"
#include "core/status.h"

// The keyframe database of semantic mapping (seed 000 §3.1 step 2): the camera frames in which
// mapped objects were detected, with their pose, the objects in view and those objects' chain
// neighbours. The bag-of-words stage describes these frames and searches them when an object
// is hidden. Written as MAP/keyframes.json:
//   {"version": 1, "run": "/abs/run", "keyframes": [{"frame": "frames/000012", "stamp": 6.0,
//     "pose": [x, y, theta], "objects": [{"id": 3, "class": "cabinet", "box": [x1, y1, x2, y2],
//     "depth_m": 2.1, "upstream": 7, "downstream": 5}]}]}
namespace semchain::semantic {

struct KeyframeObject {
  int id = 0;
  std::string class_name;
  double box[4] = {0.0, 0.0, 0.0, 0.0};
  double depth_m = 0.0;
  int upstream = -1;  // chain neighbours' ids, -1 when none
  int downstream = -1;
};

struct Keyframe {
  std::string frame;  // as in detections.jsonl, relative to the run
  double stamp = 0.0;
  Pose2 pose;  // robot pose from the SLAM trajectory
  std::vector<KeyframeObject> objects;
};

struct KeyframeDatabase {
  // The folder the frames' images are in: absolute, or relative to the keyframes.json that
  // names it (ReadKeyframes resolves it); empty when no images were kept.
  std::string run;
  std::vector<Keyframe> keyframes;
};

Status WriteKeyframes(const std::filesystem::path& path, const KeyframeDatabase& database);
// Errors name the file and field, e.g. "map/keyframes.json: keyframes[3].pose: expected 3 numbers".
Result<KeyframeDatabase> ReadKeyframes(const std::filesystem::path& path);

}  // namespace semchain::semantic
