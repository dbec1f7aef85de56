#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace semchain {

// A one-line progress bar on stderr for work that takes more than a second. It draws only
// when stderr is a terminal (so logs and CI output stay clean) and at most ten times a second.
class ProgressBar {
 public:
  ProgressBar(std::string label, std::size_t total);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // Marks 'done' of 'total' units as finished.
  void Update(std::size_t done);
  // Draws the bar full and ends the line.
  void Finish();

 private:
  void Draw(std::size_t done);

  std::string label_;
  std::size_t total_;
  bool enabled_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
};

}  // namespace semchain
