#include "ros/detector_thread.h"

#include <boost/make_shared.hpp>
#include <chrono>
#include <future>
#include <memory>

namespace semchain::ros1 {
namespace {

// A function queued as a callback.
class FunctionCallback : public ::ros::CallbackInterface {
 public:
  explicit FunctionCallback(std::function<void()> work) : work_(std::move(work)) {}
  CallResult call() override {
    work_();
    return Success;
  }

 private:
  std::function<void()> work_;
};

}  // namespace

DetectorThread::DetectorThread(const ::ros::NodeHandle& nh) : nh_(nh), spinner_(1, &queue_) {
  nh_.setCallbackQueue(&queue_);
}

void DetectorThread::Start() {
  spinner_.start();
  running_ = true;
}

void DetectorThread::Post(std::function<void()> work) {
  queue_.addCallback(boost::make_shared<FunctionCallback>(std::move(work)));
}

bool DetectorThread::Drain(double timeout_seconds) {
  if (!running_) return false;
  // Queued behind the others, it marks when they have run.
  auto ran = std::make_shared<std::promise<void>>();
  std::future<void> done = ran->get_future();
  Post([ran] { ran->set_value(); });
  return done.wait_for(std::chrono::duration<double>(timeout_seconds)) == std::future_status::ready;
}

void DetectorThread::Stop() {
  if (!running_) return;
  spinner_.stop();
  running_ = false;
}

bool DetectorThread::RunQueued(double timeout_seconds) {
  if (running_) return false;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_seconds);
  while (!queue_.isEmpty()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    queue_.callOne(::ros::WallDuration(0.0));
  }
  return true;
}

}  // namespace semchain::ros1
