#include "ros/scan_input.h"

#include <ros/console.h>

#include <algorithm>
#include <optional>
#include <utility>
#include <vector>

#include "ros/log_throttle.h"

namespace semchain::ros1 {

ScanInput::ScanInput(::ros::NodeHandle nh, const std::string& topic, std::uint32_t queue_size,
                     tf2_ros::Buffer& buffer, const std::string& odom_frame, Callback callback)
    : nh_(nh),
      buffer_(buffer),
      odom_frame_(odom_frame),
      callback_(std::move(callback)),
      subscriber_(nh, topic, queue_size) {
  // Registered before the filter connects to the subscriber: the arrival is noted before the
  // filter can release or drop the scan.
  subscriber_.registerCallback(&ScanInput::OnArrival, this);
  filter_ = std::make_unique<tf2_ros::MessageFilter<sensor_msgs::LaserScan>>(
      subscriber_, buffer, odom_frame, queue_size, nh);
  filter_->registerCallback(&ScanInput::OnReleased, this);
  filter_->registerFailureCallback(
      [this](const sensor_msgs::LaserScanConstPtr& scan,
             tf2_ros::filter_failure_reasons::FilterFailureReason reason) {
        OnDropped(scan, reason);
      });
  rescue_timer_ = nh_.createWallTimer(::ros::WallDuration(kRescueSeconds),
                                      [this](const ::ros::WallTimerEvent&) { Flush(); });
}

ScanInput::Entry* ScanInput::Waiting(const ::ros::Time& stamp) {
  for (Entry& entry : entries_) {
    if (entry.state == State::kWaiting && entry.stamp == stamp) return &entry;
  }
  return nullptr;
}

bool ScanInput::Rescued(const ::ros::Time& stamp) const {
  return std::find(rescued_stamps_.begin(), rescued_stamps_.end(), stamp) != rescued_stamps_.end();
}

void ScanInput::OnArrival(const sensor_msgs::LaserScanConstPtr& scan) {
  const std::lock_guard<std::mutex> lock(mutex_);
  entries_.push_back({scan->header.stamp, ::ros::WallTime::now(), State::kWaiting, scan, {}});
}

void ScanInput::OnReleased(const sensor_msgs::LaserScanConstPtr& scan) {
  const ::ros::WallTime now = ::ros::WallTime::now();
  bool noted = false;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    if (Rescued(scan->header.stamp)) {
      return;  // released here already
    }
    if (Entry* entry = Waiting(scan->header.stamp)) {
      entry->state = State::kReleased;
      entry->released = now;
      noted = true;
    }
  }
  // A scan passed by Flush after waiting too long goes on at once (its arrival is forgotten).
  if (!noted) callback_(scan, {now, now});
  Flush();
}

void ScanInput::OnDropped(const sensor_msgs::LaserScanConstPtr& scan,
                          tf2_ros::filter_failure_reasons::FilterFailureReason reason) {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    // A scan released here that the filter gives up on later (pushed out of its queue) was not
    // lost.
    if (Rescued(scan->header.stamp)) {
      return;
    }
    if (Entry* entry = Waiting(scan->header.stamp)) entry->state = State::kDropped;
  }
  ++dropped_;
  const char* why = reason == tf2_ros::filter_failure_reasons::OutTheBack ? "older than tf's cache"
                    : reason == tf2_ros::filter_failure_reasons::EmptyFrameID
                        ? "no frame_id"
                        : "tf did not know where the robot was at its stamp in time";
  SEMCHAIN_WARN_THROTTLE(5.0, "semchain_ros: scan at %.3f (frame '%s') dropped: %s",
                         scan->header.stamp.toSec(), scan->header.frame_id.c_str(), why);
}

void ScanInput::Rescue(const ::ros::WallTime& now) {
  // As many stamps as the filter can hold scans: a late release comes before that many more.
  constexpr std::size_t kRescuedStampsKept = 1000;
  for (Entry& entry : entries_) {
    if (entry.state != State::kWaiting ||
        now < entry.arrived + ::ros::WallDuration(kRescueSeconds) ||
        !buffer_.canTransform(odom_frame_, entry.scan->header.frame_id, entry.stamp)) {
      continue;
    }
    entry.state = State::kReleased;
    entry.released = now;
    rescued_stamps_.push_back(entry.stamp);
    if (rescued_stamps_.size() > kRescuedStampsKept) rescued_stamps_.pop_front();
    ++rescued_;
  }
}

void ScanInput::Flush() {
  std::vector<std::pair<sensor_msgs::LaserScanConstPtr, ScanArrival>> ready;
  std::optional<::ros::WallTime> deadline;
  const ::ros::WallTime now = ::ros::WallTime::now();
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    Rescue(now);
    while (!entries_.empty()) {
      Entry& front = entries_.front();
      if (front.state == State::kReleased) {
        ready.emplace_back(front.scan, ScanArrival{front.arrived, front.released});
      } else if (front.state == State::kWaiting) {
        const bool holding = std::any_of(entries_.begin(), entries_.end(), [](const Entry& e) {
          return e.state == State::kReleased;
        });
        if (!holding) break;
        const ::ros::WallTime pass_at = front.arrived + ::ros::WallDuration(kHoldSeconds);
        if (now < pass_at) {
          deadline = pass_at;
          break;
        }
      }
      entries_.pop_front();
    }
  }
  for (const auto& [scan, arrival] : ready) callback_(scan, arrival);
  if (deadline) {
    hold_timer_ = nh_.createWallTimer(
        *deadline - now, [this](const ::ros::WallTimerEvent&) { Flush(); }, true);
  }
}

}  // namespace semchain::ros1
