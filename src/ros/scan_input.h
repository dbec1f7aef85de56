#pragma once

#include <message_filters/subscriber.h>
#include <ros/node_handle.h>
#include <ros/time.h>
#include <ros/wall_timer.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/message_filter.h>

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

// The scans of both modes of semchain_ros, taken as amcl and slam_gmapping take them: /scan
// through a tf2_ros::MessageFilter whose target is the odometry frame, so that a scan reaches
// the node once tf can say where the robot was at its stamp (odom → base_link → the laser),
// without polling tf in the scan callback.
//
// The filter may release scans out of their order of arrival: a scan that arrives while tf's
// listener thread is adding the transform that releases the scan before it passes that one.
// SLAM needs its scans in time order, so a scan released before an earlier one is held until
// that one is released or dropped, at most kHoldSeconds.
//
// The filter may also never release a scan whose transform came in while the scan was being
// added (its request is answered before the scan is in its list: Intel's log played at rate 4
// lost 80 of 13 631 scans so, none of them reported dropped). A scan still waiting after
// kRescueSeconds whose transform tf now has is therefore released here, and the filter's own
// release of it, should it come, is ignored.
namespace semchain::ros1 {

// When a scan reached the node, for the latency figures.
struct ScanArrival {
  ::ros::WallTime arrived;   // its subscriber's callback ran
  ::ros::WallTime released;  // the filter let it through (tf known at its stamp)
};

class ScanInput {
 public:
  using Callback =
      std::function<void(const sensor_msgs::LaserScanConstPtr& scan, const ScanArrival& arrival)>;

  // Wall seconds a released scan waits at most for an earlier one still in the filter.
  static constexpr double kHoldSeconds = 0.5;
  // Wall seconds after which a scan still in the filter is released here if tf has its
  // transform: longer than the filter takes once the transform is in (well under a millisecond),
  // short against kHoldSeconds.
  static constexpr double kRescueSeconds = 0.05;

  // Subscribes 'topic' on 'nh' (its callback queue runs 'callback') with 'queue_size' scans
  // waiting in the subscriber and as many waiting for tf in the filter (the oldest is dropped
  // beyond). 'buffer' must outlive this object.
  ScanInput(::ros::NodeHandle nh, const std::string& topic, std::uint32_t queue_size,
            tf2_ros::Buffer& buffer, const std::string& odom_frame, Callback callback);
  ScanInput(const ScanInput&) = delete;
  ScanInput& operator=(const ScanInput&) = delete;

  // Scans the filter gave up on: pushed out of its queue while tf did not know them, older
  // than tf's cache, or without a frame_id.
  int dropped() const { return dropped_.load(); }
  // Scans the filter held although tf had their transform, released here.
  int rescued() const { return rescued_.load(); }

 private:
  enum class State { kWaiting, kReleased, kDropped };
  struct Entry {
    ::ros::Time stamp;
    ::ros::WallTime arrived;
    State state = State::kWaiting;
    sensor_msgs::LaserScanConstPtr scan;
    ::ros::WallTime released;
  };

  void OnArrival(const sensor_msgs::LaserScanConstPtr& scan);
  void OnReleased(const sensor_msgs::LaserScanConstPtr& scan);
  void OnDropped(const sensor_msgs::LaserScanConstPtr& scan,
                 tf2_ros::filter_failure_reasons::FilterFailureReason reason);
  // The first scan still waiting with 'stamp'; null when none (mutex_ held).
  Entry* Waiting(const ::ros::Time& stamp);
  // Whether the scan with 'stamp' was released here (mutex_ held).
  bool Rescued(const ::ros::Time& stamp) const;
  // Marks released the waiting scans older than kRescueSeconds whose transform tf has
  // (mutex_ held).
  void Rescue(const ::ros::WallTime& now);
  // Hands the released scans at the front over in arrival order, passing a scan that waited
  // longer than kHoldSeconds; arms the timer for the next deadline when some are held. Also
  // run every kRescueSeconds.
  void Flush();

  ::ros::NodeHandle nh_;
  tf2_ros::Buffer& buffer_;
  std::string odom_frame_;
  Callback callback_;
  // The subscriber's and the filter's callbacks run on nh_'s callback queue; the filter reports
  // drops from tf's listener thread too.
  std::mutex mutex_;
  std::deque<Entry> entries_;  // arrival order
  // Stamps of the scans released here, so that the filter's late release of one is ignored.
  std::deque<::ros::Time> rescued_stamps_;
  std::atomic<int> dropped_{0};
  std::atomic<int> rescued_{0};
  ::ros::WallTimer hold_timer_;
  ::ros::WallTimer rescue_timer_;
  message_filters::Subscriber<sensor_msgs::LaserScan> subscriber_;
  std::unique_ptr<tf2_ros::MessageFilter<sensor_msgs::LaserScan>> filter_;
};

}  // namespace semchain::ros1
