#include "ros/detector_thread.h"

#include <boost/make_shared.hpp>
#include <chrono>
#include <future>
#include <memory>

namespace semchain::ros1 {
namespace {

// A callback that only says it ran: queued behind the others, it marks when they have run.
class Marker : public ::ros::CallbackInterface {
 public:
  explicit Marker(std::shared_ptr<std::promise<void>> ran) : ran_(std::move(ran)) {}
  CallResult call() override {
    ran_->set_value();
    return Success;
  }

 private:
  std::shared_ptr<std::promise<void>> ran_;
};

}  // namespace

DetectorThread::DetectorThread(const ::ros::NodeHandle& nh) : nh_(nh), spinner_(1, &queue_) {
  nh_.setCallbackQueue(&queue_);
}

void DetectorThread::Start() {
  spinner_.start();
  running_ = true;
}

bool DetectorThread::Drain(double timeout_seconds) {
  if (!running_) return false;
  auto ran = std::make_shared<std::promise<void>>();
  std::future<void> done = ran->get_future();
  queue_.addCallback(boost::make_shared<Marker>(ran));
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
