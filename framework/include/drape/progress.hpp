#pragma once
// A progress bar for long jobs (dataset generation, training, benchmarks):
//
//   simulate [########............] 37/100 37% 12.3 s elapsed, ETA 21.0 s  loss 0.012
//
// On a terminal the line is redrawn in place ('\r') at most ~10 times a second;
// elsewhere (CI logs, files) a plain line is written every 10% or every 30 s,
// whichever comes first, so logs stay short. advance() and set_status() may be
// called from several threads.
#include <cstddef>
#include <functional>
#include <iostream>
#include <mutex>
#include <optional>
#include <string>

namespace drape {

class ProgressBar {
 public:
  struct Options {
    // Items already done before this run (a resumed job): counted in the bar
    // but not in the rate, so the ETA reflects this run's speed only.
    std::size_t start = 0;
    // Redraw in place? Default: yes when `out` is std::cerr or std::cout and
    // that stream is a terminal (isatty).
    std::optional<bool> terminal;
    // Seconds on any monotonic clock (tests inject a fake one). Default: steady_clock.
    std::function<double()> clock;
    int width = 20;  // characters between the brackets
  };

  ProgressBar(std::string label, std::size_t total, std::ostream& out = std::cerr);
  ProgressBar(std::string label, std::size_t total, std::ostream& out, Options options);
  ~ProgressBar();  // finish() if not done yet (a terminal line is never left open)
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  // n more items done (clamped at total).
  void advance(std::size_t n = 1);
  // Free text after the numbers, e.g. the current losses. Redrawn on a
  // terminal as advance() is; in a log, written when 30 s have passed since
  // the last line (a long item's progress within it).
  void set_status(std::string status);
  // Writes the final line (no ETA) and ends it. Later calls do nothing.
  void finish();

  std::size_t done() const;
  std::size_t total() const { return total_; }
  // The line as it would be drawn now (without '\r' or '\n').
  std::string line() const;

  // "12.3 s", "4 min 05 s", "2 h 03 min".
  static std::string format_duration(double seconds);

 private:
  std::string line_locked(double now, bool final) const;
  void draw_locked(double now, bool final);

  std::string label_;
  std::size_t total_;
  std::ostream& out_;
  Options options_;
  bool terminal_ = false;

  mutable std::mutex mutex_;
  std::size_t done_ = 0;
  std::string status_;
  double start_time_ = 0;
  double last_draw_ = -1e300;  // when the line was last drawn
  std::size_t last_decile_ = 0;  // of the last plain line (not on a terminal)
  std::size_t drawn_width_ = 0;  // characters of the last terminal line, to blank leftovers
  bool finished_ = false;
};

}  // namespace drape
