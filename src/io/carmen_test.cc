#include "io/carmen.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/angles.h"

namespace semchain::carmen {
namespace {

const std::filesystem::path kData = SEMCHAIN_SHARED_DATA_DIR;

std::filesystem::path TempPath(const std::string& name) {
  return std::filesystem::path(testing::TempDir()) / name;
}

// Writes 'text' to a temporary file and returns its path.
std::filesystem::path WriteText(const std::string& name, const std::string& text) {
  const std::filesystem::path path = TempPath(name);
  std::ofstream(path) << text;
  return path;
}

std::string ErrorOf(const Result<Log>& log) { return log.ok() ? "" : log.status().message(); }

Pose2 RawPose(double x, double y, double theta) {
  Pose2 pose;
  pose.x = x;
  pose.y = y;
  pose.theta = theta;
  return pose;
}

// One record of every type, with values that need all 17 significant digits.
Log EveryRecordType() {
  Log log;
  log.records.push_back(Param{"laser_front_laser_resolution", "0.5", "1071078718.4676 merci 1.5"});
  log.records.push_back(Param{"robot_use_laser", "on", ""});
  Odometry odometry;
  odometry.pose = RawPose(0.1, -2.0 / 3.0, 3.141592653589793);
  odometry.tv = 0.3;
  odometry.rv = -1e-17;
  odometry.stamp = {1134864629.895182, "b21", 0.086295};
  log.records.push_back(odometry);
  Laser flaser;
  flaser.scan.scan.ranges = {1.4, 81.91, 0.0, 1.0 / 3.0};
  flaser.scan.laser_pose = RawPose(576.536523, 0.106594, -2.255213);
  flaser.scan.odometry = RawPose(576.5, 0.1, -2.25);
  flaser.stamp = {12.5, "pippo", 12.5};
  log.records.push_back(flaser);
  Laser robot_laser;
  robot_laser.kind = Laser::Kind::kRobotLaser1;
  robot_laser.laser_type = 3;
  robot_laser.scan.scan.angle_min = -kPi;
  robot_laser.scan.scan.angle_increment = DegToRad(120.0);
  robot_laser.scan.scan.max_range = 12.0;
  robot_laser.scan.scan.ranges = {2.0, 12.0, 0.7};
  robot_laser.fov = 2.0 * kPi;
  robot_laser.accuracy = 0.01;
  robot_laser.remission_mode = 1;
  robot_laser.remissions = {0.5, 0.25};
  robot_laser.scan.laser_pose = RawPose(1.1, 2.2, 0.3);
  robot_laser.scan.odometry = RawPose(1.0, 2.0, 0.3);
  robot_laser.tv = 0.2;
  robot_laser.rv = 0.1;
  robot_laser.forward_safety = 0.15;
  robot_laser.side_safety = 0.05;
  robot_laser.turn_axis = 1e6;
  robot_laser.stamp = {99.25, "semchain", 99.5};
  log.records.push_back(robot_laser);
  log.records.push_back(TruePose{RawPose(1, 2, -0.5), RawPose(1.5, 2.5, -0.25), {7.0, "sim", 7.1}});
  log.records.push_back(Other{"NEFF 29.9086"});
  log.records.push_back(Other{"# a comment"});
  return log;
}

void ExpectSameLaser(const Laser& a, const Laser& b) {
  EXPECT_EQ(a.kind, b.kind);
  EXPECT_EQ(a.scan.scan.ranges, b.scan.scan.ranges);
  EXPECT_EQ(a.remissions, b.remissions);
  EXPECT_EQ(a.stamp.timestamp, b.stamp.timestamp);
  EXPECT_EQ(b.scan.scan.timestamp, b.stamp.timestamp);
  if (a.kind == Laser::Kind::kRobotLaser1) {
    EXPECT_EQ(a.scan.scan.angle_min, b.scan.scan.angle_min);
    EXPECT_EQ(a.scan.scan.angle_increment, b.scan.scan.angle_increment);
    EXPECT_EQ(a.scan.scan.max_range, b.scan.scan.max_range);
    EXPECT_EQ(a.fov, b.fov);
    EXPECT_EQ(a.turn_axis, b.turn_axis);
  }
}

void ExpectSameLog(const Log& a, const Log& b) {
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t i = 0; i < a.records.size(); ++i) {
    ASSERT_EQ(a.records[i].index(), b.records[i].index()) << "record " << i;
    // The formatting is the shortest exact decimal form, so equal text means equal values.
    EXPECT_EQ(FormatRecord(a.records[i]), FormatRecord(b.records[i])) << "record " << i;
    if (const Laser* laser = std::get_if<Laser>(&a.records[i])) {
      ExpectSameLaser(*laser, std::get<Laser>(b.records[i]));
    }
  }
}

TEST(CarmenTest, EveryRecordTypeRoundTripsPlainAndGzip) {
  const Log log = EveryRecordType();
  for (const char* name : {"round_trip.clf", "round_trip.clf.gz"}) {
    const std::filesystem::path path = TempPath(name);
    ASSERT_TRUE(WriteLog(path, log).ok());
    const Result<Log> read = ReadLog(path);
    ASSERT_TRUE(read.ok()) << read.status().message();
    ExpectSameLog(log, *read);
    const auto& odometry = *read->Odometries().at(0);
    EXPECT_EQ(odometry.pose.y, -2.0 / 3.0);
    EXPECT_EQ(odometry.pose.theta, 3.141592653589793);
    EXPECT_EQ(odometry.stamp.host, "b21");
    EXPECT_EQ(std::get<Param>(read->records[0]).rest, "1071078718.4676 merci 1.5");
    EXPECT_EQ(read->TruePoses().at(0)->truth.theta, -0.5);
  }
  // The compressed file really is gzip (magic bytes 1f 8b).
  std::ifstream gz(TempPath("round_trip.clf.gz"), std::ios::binary);
  EXPECT_EQ(gz.get(), 0x1f);
  EXPECT_EQ(gz.get(), 0x8b);
}

TEST(CarmenTest, FormatsShortReadableNumbers) {
  const Result<Record> record =
      ParseLine("ODOM 0.000485382 6.20016e-05 -0.001534 0 0 0 0.227623 pippo 0.227623", "x:1");
  ASSERT_TRUE(record.ok());
  EXPECT_EQ(FormatRecord(*record),
            "ODOM 0.000485382 6.20016e-05 -0.001534 0 0 0 0.227623 pippo 0.227623");
  const Result<Record> param = ParseLine("PARAM robot_use_laser on nohost 0", "x:2");
  EXPECT_EQ(FormatRecord(*param), "PARAM robot_use_laser on nohost 0");
}

TEST(CarmenTest, FlaserGeometryFollowsBeamCountAndParams) {
  const std::string ranges180 = [] {
    std::string text;
    for (int i = 0; i < 180; ++i) text += " 1";
    return text;
  }();
  const std::string line = "FLASER 180" + ranges180 + " 0 0 0 0 0 0 1 h 1";
  const Laser laser = std::get<Laser>(*ParseLine(line, "x:1"));
  EXPECT_DOUBLE_EQ(laser.scan.scan.angle_min, -kPi / 2);
  EXPECT_DOUBLE_EQ(laser.scan.scan.angle_increment, DegToRad(1.0));  // CARMEN: 180 beams = 1°
  EXPECT_DOUBLE_EQ(laser.scan.scan.max_range, 80.0);
  ReadOptions options;
  ASSERT_TRUE(ApplyParam({"laser_front_laser_fov", "100", ""}, "x:1", &options).ok());
  ASSERT_TRUE(ApplyParam({"laser_front_laser_resolution", "0.25", ""}, "x:1", &options).ok());
  ASSERT_TRUE(ApplyParam({"robot_front_laser_max", "30", ""}, "x:1", &options).ok());
  const Laser narrow = std::get<Laser>(*ParseLine(line, "x:1", options));
  EXPECT_DOUBLE_EQ(narrow.scan.scan.angle_min, DegToRad(-50.0));
  EXPECT_DOUBLE_EQ(narrow.scan.scan.angle_increment, DegToRad(0.25));
  EXPECT_DOUBLE_EQ(narrow.scan.scan.max_range, 30.0);
  EXPECT_EQ(ApplyParam({"laser_front_laser_fov", "wide", ""}, "f:3", &options).message(),
            "f:3: PARAM laser_front_laser_fov: 'wide' is not a positive number");
}

TEST(CarmenTest, ReadsRawMitCsailLog) {
  const Result<Log> log = ReadLog(kData / "mit-csail" / "mit-csail.clf");
  ASSERT_TRUE(log.ok()) << log.status().message();
  const std::vector<const Laser*> lasers = log->Lasers();
  ASSERT_EQ(lasers.size(), 1988u);
  EXPECT_EQ(log->records.size(), 1988u + 3u);  // three '#' header lines kept as Other
  for (const Laser* laser : lasers) ASSERT_EQ(laser->scan.scan.size(), 361u);
  const LaserScan& first = lasers.front()->scan.scan;
  EXPECT_EQ(first.timestamp, 1134864629.895182);
  EXPECT_EQ(lasers.front()->stamp.host, "b21");
  EXPECT_EQ(lasers.front()->scan.odometry.x, 576.536523);
  EXPECT_EQ(lasers.front()->scan.laser_pose.theta, -2.255213);
  EXPECT_NEAR(RadToDeg(first.BeamAngle(0)), -90.0, 1e-12);
  EXPECT_NEAR(RadToDeg(first.BeamAngle(180)), 0.0, 1e-12);
  EXPECT_NEAR(RadToDeg(first.BeamAngle(360)), 90.0, 1e-12);
  // The first scan starts "1.40 1.39 ..." and has "no return" readings of 81.91.
  EXPECT_EQ(first.ranges[0], 1.40);
  EXPECT_TRUE(first.IsReturn(0));
  EXPECT_EQ(first.ranges[24], 81.91);
  EXPECT_FALSE(first.IsReturn(24));
}

struct CorrectedLog {
  const char* path;
  std::size_t scans;
  std::size_t beams;
  double last_beam_deg;
};

TEST(CarmenTest, ReadsCorrectedLogs) {
  const CorrectedLog logs[] = {{"fr079/freiburg-079-corrected.log.gz", 4791, 360, 89.5},
                               {"intel/intel-corrected.log.gz", 910, 180, 89.0},
                               {"mit-killian/infinite-corridor-corrected.log.gz", 1941, 180, 89.0},
                               {"aces/aces-corrected.log.gz", 440, 180, 89.0},
                               {"fr-campus/freiburg-campus-corrected.log.gz", 2008, 360, 89.5}};
  for (const CorrectedLog& expected : logs) {
    const Result<Log> log = ReadLog(kData / expected.path);
    ASSERT_TRUE(log.ok()) << log.status().message();
    const std::vector<const Laser*> lasers = log->Lasers();
    EXPECT_EQ(lasers.size(), expected.scans) << expected.path;
    for (const Laser* laser : lasers) ASSERT_EQ(laser->scan.scan.size(), expected.beams);
    const LaserScan& scan = lasers.front()->scan.scan;
    EXPECT_NEAR(RadToDeg(scan.BeamAngle(0)), -90.0, 1e-9) << expected.path;
    EXPECT_NEAR(RadToDeg(scan.BeamAngle(scan.size() - 1)), expected.last_beam_deg, 1e-9);
    EXPECT_FALSE(log->Odometries().empty());
  }
}

TEST(CarmenTest, RealLogRoundTripsThroughGzip) {
  const Result<Log> log = ReadLog(kData / "intel" / "intel-corrected.log.gz");
  ASSERT_TRUE(log.ok());
  const std::filesystem::path path = TempPath("intel_copy.log.gz");
  ASSERT_TRUE(WriteLog(path, *log).ok());
  const Result<Log> copy = ReadLog(path);
  ASSERT_TRUE(copy.ok()) << copy.status().message();
  ExpectSameLog(*log, *copy);
}

std::string FlaserLine(const std::string& ranges, int count) {
  return "FLASER " + std::to_string(count) + " " + ranges + " 0 0 0 0 0 0 1.5 host 1.5";
}

TEST(CarmenTest, MalformedLinesNameFileAndLine) {
  const std::string good = FlaserLine("1 2 3", 3);
  struct Case {
    std::string bad_line;
    std::string message;
  };
  const Case cases[] = {
      {"FLASER 3 1 2",
       "FLASER: truncated line: expected 12 fields after the number of ranges, got 2"},
      {FlaserLine("1 2 3", 4), "FLASER: expected 4 ranges, got 3"},
      {FlaserLine("1 nan 3", 3), "FLASER: range 1: 'nan' is not finite"},
      {FlaserLine("1 2 inf", 3), "FLASER: range 2: 'inf' is not finite"},
      {FlaserLine("1 2.5x 3", 3), "FLASER: range 1: '2.5x' is not a number"},
      {"FLASER many 1 2", "FLASER: number of ranges: 'many' is not an integer"},
      {"ODOM 1 2 3 0 0 0 1.5 host", "ODOM: truncated line: missing logger timestamp"},
      {"ODOM 1 2 3 0 0 0 1.5 host 1.5 extra", "ODOM: 1 unexpected extra field(s), first 'extra'"},
      {"TRUEPOS 1 2 3 4 5 six 7 h 7", "TRUEPOS: odometry theta: 'six' is not a number"},
      {"ROBOTLASER1 0 -1.5 3 0.5 20 0.01 0 2 1 2",
       "ROBOTLASER1: truncated line: expected 17 fields after the number of ranges, got 2"},
      {"ROBOTLASER1 0 -1.5 3 0.5 20 0.01 0 2 1 2 1 0.5 0 0 0 0 0 0 0 0 0 0 0 h 0",
       "ROBOTLASER1: expected 1 remissions, got 0"},
      {"PARAM lonely", "PARAM: truncated line: missing value"},
  };
  for (const Case& c : cases) {
    const std::filesystem::path path =
        WriteText("bad.clf", "# header\n" + good + "\n\n" + c.bad_line + "\n" + good + "\n");
    EXPECT_EQ(ErrorOf(ReadLog(path)), path.string() + ":4: " + c.message) << c.bad_line;
  }
  const std::filesystem::path param =
      WriteText("bad_param.clf", "PARAM laser_front_laser_resolution fine 0 h 0\n");
  EXPECT_EQ(
      ErrorOf(ReadLog(param)),
      param.string() + ":1: PARAM laser_front_laser_resolution: 'fine' is not a positive number");
}

TEST(CarmenTest, UnreadableFilesAreErrors) {
  const std::filesystem::path missing = TempPath("no_such_log.clf");
  const std::string error = ErrorOf(ReadLog(missing));
  EXPECT_EQ(error.rfind(missing.string() + ": cannot open", 0), 0u) << error;
  EXPECT_NE(ErrorOf(ReadLog(testing::TempDir())).find("is a directory"), std::string::npos);
  // A gzip file cut in half: zlib reports the damage instead of returning half a log.
  ASSERT_TRUE(WriteLog(TempPath("cut.clf.gz"), EveryRecordType()).ok());
  std::ifstream in(TempPath("cut.clf.gz"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::filesystem::path cut = WriteText("cut2.clf.gz", bytes.substr(0, bytes.size() / 2));
  EXPECT_EQ(ErrorOf(ReadLog(cut)).rfind(cut.string() + ": read error", 0), 0u)
      << ErrorOf(ReadLog(cut));
}

TEST(CarmenTest, UnknownLinesAreKeptVerbatim) {
  const Result<Record> record = ParseLine("SYNC   a b\tc", "x:1");
  ASSERT_TRUE(record.ok());
  EXPECT_EQ(std::get<Other>(*record).line, "SYNC   a b\tc");
  EXPECT_EQ(FormatRecord(*record), "SYNC   a b\tc");
}

}  // namespace
}  // namespace semchain::carmen
