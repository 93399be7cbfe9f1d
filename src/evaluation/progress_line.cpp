#include "mrs_vpr/evaluation/progress_line.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>

namespace mrs_vpr {
namespace {

std::string fixed(double value, int decimals) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

/// Rates below 10 per second keep a decimal, so that a slow run does not read "0 frames/s".
std::string rateText(double rate, const std::string& unit) {
  return fixed(rate, rate < 10.0 ? 1 : 0) + " " + unit + "/s";
}

}  // namespace

ProgressLine::ProgressLine(std::string what, std::string unit, long long total, std::ostream& out, bool terminal,
                           Clock clock)
    : what_(std::move(what)),
      unit_(std::move(unit)),
      total_(total),
      out_(out),
      terminal_(terminal),
      clock_(std::move(clock)),
      start_(clock_()),
      last_write_(start_) {}

ProgressLine ProgressLine::onStderr(std::string what, std::string unit, long long total) {
  return ProgressLine(std::move(what), std::move(unit), total, std::cerr, isatty(STDERR_FILENO) == 1);
}

double ProgressLine::steadySeconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

std::string ProgressLine::formatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  if (seconds < 60.0) return fixed(seconds, 1) + " s";
  const long long whole = std::llround(seconds);
  char text[64];
  if (whole < 3600) {
    std::snprintf(text, sizeof(text), "%lld min %02lld s", whole / 60, whole % 60);
  } else {
    std::snprintf(text, sizeof(text), "%lld h %02lld min", whole / 3600, (whole % 3600) / 60);
  }
  return text;
}

std::string ProgressLine::format(const std::string& what, const std::string& unit, long long done, long long total,
                                 double rate) {
  std::ostringstream text;
  text << what << ": " << done;
  if (total > 0) text << "/" << total;
  text << " " << unit;
  if (total > 0) text << " (" << (100 * done / total) << "%)";
  if (rate > 0.0) {
    text << ", " << rateText(rate, unit);
    if (total > 0 && done < total) {
      text << ", " << formatDuration(static_cast<double>(total - done) / rate) << " left";
    }
  }
  return text.str();
}

void ProgressLine::update(long long done) {
  done_ = done;
  if (finished_) return;
  const double now = clock_();
  if (!counting_) {
    counting_ = true;
    first_done_ = done;
    first_time_ = now;
  }
  if (now - last_write_ < (terminal_ ? kTerminalPeriod : kPlainPeriod)) return;
  last_write_ = now;
  const double rate =
      now > first_time_ ? static_cast<double>(done - first_done_) / (now - first_time_) : 0.0;
  write(format(what_, unit_, done_, total_, rate));
}

ProgressLine::~ProgressLine() {
  if (terminal_ && !finished_ && last_length_ > 0) out_ << '\n' << std::flush;
}

void ProgressLine::finish(const std::string& detail) {
  if (finished_) return;
  finished_ = true;
  const double elapsed = clock_() - start_;
  std::string text = what_ + ": " + std::to_string(done_) + " " + unit_ + (detail.empty() ? "" : " " + detail) +
                     " in " + formatDuration(elapsed);
  if (done_ > 0 && elapsed > 0.0) text += ", " + rateText(static_cast<double>(done_) / elapsed, unit_);
  write(text);
  if (terminal_) out_ << '\n';
  out_.flush();
}

void ProgressLine::write(const std::string& text) {
  if (!terminal_) {
    out_ << text << '\n';
    return;
  }
  // Spaces over what a longer previous line left behind: no terminal escape sequences needed.
  const std::size_t padding = last_length_ > text.size() ? last_length_ - text.size() : 0;
  out_ << '\r' << text << std::string(padding, ' ') << std::flush;
  last_length_ = text.size();
}

}  // namespace mrs_vpr
