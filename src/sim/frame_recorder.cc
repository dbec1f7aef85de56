#include "sim/frame_recorder.h"

#include "core/atomic_file.h"
#include "io/detections_io.h"
#include "sim/detection_model.h"
#include "sim/rgbd_renderer.h"
#include "sim/run_directory.h"
#include "sim/simulator.h"

namespace semchain::sim {

FrameRecorder::FrameRecorder(const Scene& scene, std::uint64_t seed,
                             const std::filesystem::path& run_dir)
    : scene_(scene),
      camera_(MakeMountedCamera(scene.world().robot.camera)),
      run_dir_(run_dir),
      period_s_(1.0 / scene.world().robot.frame_rate_hz),
      detection_rng_(MakeRng(seed, static_cast<std::uint64_t>(SimStream::kDetections))),
      depth_noise_rng_(MakeRng(seed, static_cast<std::uint64_t>(SimStream::kDepthNoise))) {}

Status FrameRecorder::Open() { return EnsureWritableDirectory(run_dir_ / "frames"); }

Status FrameRecorder::MaybeCapture(const TrajectorySample& sample) {
  // A small tolerance keeps 0.1 s steps summed in floating point from skipping a frame.
  if (sample.time + 1e-6 < next_time_s_) return Status::Ok();
  next_time_s_ += period_s_;
  const int index = count();
  RenderOptions render = MakeRenderOptions(scene_.world().robot.camera, depth_noise_rng_());
  render.count_unoccluded = HasObjectParts(scene_.world());
  const RgbdImage image = RenderRgbd(scene_, camera_, sample.pose, render);
  SEMCHAIN_RETURN_IF_ERROR(WriteFrame(run_dir_ / "frames", index, image));
  FrameDetections frame;
  frame.frame = FrameName(index);
  frame.stamp = sample.time;
  frame.detections = DetectObjects(scene_, camera_, sample.pose, image, detection_rng_);
  detections_.push_back(std::move(frame));
  return Status::Ok();
}

Status FrameRecorder::Close() {
  return WriteDetectionsJsonl(run_dir_ / "detections.jsonl", detections_);
}

}  // namespace semchain::sim
