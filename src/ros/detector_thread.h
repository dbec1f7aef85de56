#pragma once

#include <ros/callback_queue.h>
#include <ros/node_handle.h>
#include <ros/spinner.h>

#include <functional>

// The detector's own callback queue, served by a thread of its own (a ros::AsyncSpinner): the
// node subscribes its camera topics through nh(), so that the detector (tens of milliseconds a
// frame) runs beside the scans on the node's main queue instead of before them. One thread
// serves the queue, so the images are handled in the order they came and the frames reach the
// map in stamp order. What the callbacks share with the scans must be guarded by the node.
namespace semchain::ros1 {

class DetectorThread {
 public:
  // Subscriptions made through nh() are served by this thread once Start() is called.
  explicit DetectorThread(const ::ros::NodeHandle& nh);
  ~DetectorThread() { Stop(); }
  DetectorThread(const DetectorThread&) = delete;
  DetectorThread& operator=(const DetectorThread&) = delete;

  ::ros::NodeHandle& nh() { return nh_; }
  void Start();
  // Queues 'work' behind the callbacks queued now, to run on this thread.
  void Post(std::function<void()> work);
  // Waits until every callback queued now has run, at most 'timeout_seconds' of wall time;
  // false when the time ran out (or the thread is not running).
  bool Drain(double timeout_seconds);
  // Stops the thread once the callback it runs has returned; callbacks still queued are not
  // run. Call before destroying what the callbacks use.
  void Stop();
  // Runs the callbacks queued now on the calling thread, the thread stopped (after Stop), for
  // at most 'timeout_seconds' of wall time: at shutdown, the images that arrived after the
  // last save are still mapped. Returns whether the queue was emptied.
  bool RunQueued(double timeout_seconds);

 private:
  ::ros::CallbackQueue queue_;
  ::ros::NodeHandle nh_;
  ::ros::AsyncSpinner spinner_;
  bool running_ = false;
};

}  // namespace semchain::ros1
