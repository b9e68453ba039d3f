#pragma once
/// \file timer.h
/// Wall-clock timing of pipeline stages, for the `time per stage` entries of
/// report.json and for progress lines.

#include <chrono>

namespace knitforge {

/// A stopwatch started at construction.
class Timer {
 public:
  Timer() : start_(std::chrono::steady_clock::now()) {}
  /// Seconds since construction or the last reset().
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void reset() { start_ = std::chrono::steady_clock::now(); }

 private:
  std::chrono::steady_clock::time_point start_;
};

}  // namespace knitforge
