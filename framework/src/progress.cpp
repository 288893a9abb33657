// ProgressBar: counts, rate and ETA, redrawn in place on a terminal and as
// occasional plain lines elsewhere.
#include <drape/progress.hpp>

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace drape {
namespace {

constexpr double kTerminalInterval = 0.1;  // s between redraws in place (~10 per second)
constexpr double kLogInterval = 30.0;      // s between plain lines when no 10% step was crossed

double steady_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

bool is_terminal(const std::ostream& out) {
  if (&out == &std::cerr || &out == &std::clog) return ::isatty(STDERR_FILENO) == 1;
  if (&out == &std::cout) return ::isatty(STDOUT_FILENO) == 1;
  return false;
}

}  // namespace

ProgressBar::ProgressBar(std::string label, std::size_t total, std::ostream& out)
    : ProgressBar(std::move(label), total, out, Options{}) {}

ProgressBar::ProgressBar(std::string label, std::size_t total, std::ostream& out, Options options)
    : label_(std::move(label)), total_(total), out_(out), options_(std::move(options)) {
  if (!options_.clock) options_.clock = steady_seconds;
  options_.width = std::max(options_.width, 1);
  terminal_ = options_.terminal.value_or(is_terminal(out_));
  done_ = std::min(options_.start, total_);
  options_.start = done_;
  start_time_ = options_.clock();
  last_decile_ = total_ ? 10 * done_ / total_ : 0;
  last_draw_ = start_time_;  // the 30 s between plain lines count from the start
  if (terminal_) {
    std::lock_guard lock(mutex_);
    draw_locked(start_time_, false);
  }
}

ProgressBar::~ProgressBar() {
  try {
    finish();
  } catch (...) {  // a destructor must not throw; a failed last line is not worth dying for
  }
}

std::string ProgressBar::format_duration(double seconds) {
  char buf[32];
  if (!std::isfinite(seconds) || seconds < 0) return "--";
  if (seconds < 60) {
    std::snprintf(buf, sizeof buf, "%.1f s", seconds);
  } else if (seconds < 3600) {
    const long s = std::lround(seconds);
    std::snprintf(buf, sizeof buf, "%ld min %02ld s", s / 60, s % 60);
  } else {
    const long m = std::lround(seconds / 60);
    std::snprintf(buf, sizeof buf, "%ld h %02ld min", m / 60, m % 60);
  }
  return buf;
}

std::string ProgressBar::line_locked(double now, bool final) const {
  const double fraction = total_ ? static_cast<double>(done_) / static_cast<double>(total_) : 1.0;
  const int filled = static_cast<int>(std::floor(fraction * options_.width));
  const double elapsed = std::max(0.0, now - start_time_);
  std::ostringstream s;
  s << label_ << " [" << std::string(filled, '#') << std::string(options_.width - filled, '.') << "] " << done_ << "/"
    << total_ << " " << static_cast<int>(std::floor(100 * fraction)) << "% " << format_duration(elapsed) << " elapsed";
  if (!final && done_ < total_) {
    // Rate from this run's items only: a resumed job's earlier items took no time here.
    const std::size_t this_run = done_ - options_.start;
    s << ", ETA ";
    if (this_run > 0 && elapsed > 0)
      s << format_duration(static_cast<double>(total_ - done_) * elapsed / static_cast<double>(this_run));
    else
      s << "--";
  }
  if (!status_.empty()) s << "  " << status_;
  return s.str();
}

void ProgressBar::draw_locked(double now, bool final) {
  const std::string text = line_locked(now, final);
  if (terminal_) {
    // Blank whatever a longer previous line left behind.
    const std::size_t pad = drawn_width_ > text.size() ? drawn_width_ - text.size() : 0;
    out_ << '\r' << text << std::string(pad, ' ');
    if (final) out_ << '\n';
    drawn_width_ = text.size();
  } else {
    out_ << text << '\n';
  }
  out_.flush();
  last_draw_ = now;
}

void ProgressBar::advance(std::size_t n) {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  done_ = std::min(total_, done_ + n);
  const double now = options_.clock();
  if (terminal_) {
    if (now - last_draw_ >= kTerminalInterval) draw_locked(now, false);
    return;
  }
  // Plain lines: each 10% step below 100% (finish() writes the last line), or
  // every 30 s while a step takes longer.
  const std::size_t decile = total_ ? 10 * done_ / total_ : 10;
  if (done_ < total_ && (decile > last_decile_ || now - last_draw_ >= kLogInterval)) {
    last_decile_ = decile;
    draw_locked(now, false);
  }
}

void ProgressBar::set_status(std::string status) {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  status_ = std::move(status);
  const double now = options_.clock();
  // (In a log, a status alone is written every 30 s too: an item that takes
  // minutes still shows what it is doing.)
  if (now - last_draw_ >= (terminal_ ? kTerminalInterval : kLogInterval)) draw_locked(now, false);
}

void ProgressBar::finish() {
  std::lock_guard lock(mutex_);
  if (finished_) return;
  finished_ = true;
  draw_locked(options_.clock(), true);
}

std::size_t ProgressBar::done() const {
  std::lock_guard lock(mutex_);
  return done_;
}

std::string ProgressBar::line() const {
  std::lock_guard lock(mutex_);
  return line_locked(options_.clock(), finished_);
}

}  // namespace drape
