// sphbasis CLI support: one progress bar for a long run.
//
// Drawn on stderr only when stderr is a terminal (a log or a pipe stays clean): the label, a
// bar, the percentage, the rate and the estimated time left, redrawn at most ten times a
// second. update() may be called from any thread; the thread that finds the bar due redraws it
// (no drawing thread of its own). The idea is pbrt-v4's ProgressReporter.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace sphbasis::cli {

/// The clock of the tool's timings, and the seconds on it since t0.
using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

class Progress {
  public:
    /// A bar for `total` units of work labelled `label`; draws the empty bar at once.
    Progress(std::string label, long long total);
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;
    /// Finishes the bar if done() was not called.
    ~Progress();

    /// Records `units` more units of work done. Thread-safe, cheap when not drawing.
    void update(long long units = 1);
    /// Draws the full bar and ends its line. Idempotent.
    void done();

  private:
    using Clock = std::chrono::steady_clock;
    void draw(long long done_units, bool final);

    std::string label_;
    long long total_;
    bool enabled_;
    std::atomic<long long> done_{0};
    std::atomic<bool> finished_{false};
    Clock::time_point start_;
    std::atomic<long long> next_draw_ns_{0};  // nanoseconds since start_
    std::mutex draw_mutex_;
};

}  // namespace sphbasis::cli
