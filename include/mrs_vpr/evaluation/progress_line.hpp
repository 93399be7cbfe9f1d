#pragma once

#include <functional>
#include <ostream>
#include <string>

namespace mrs_vpr {

/**
 * The progress of a long offline run (describing a reference, writing a bag, answering queries) as one
 * line: "reference: 1200/1761 frames (68%), 118 frames/s, 4.7 s left".
 *
 * On a terminal the line is rewritten in place (carriage return) at most a few times a second; into a
 * file or a pipe, where rewriting would leave a line per update, a plain line is written every
 * `kPlainPeriod` seconds instead. `finish` ends it with the totals. It writes only to the stream it is
 * given (the tools give stderr, so that stdout stays pure data).
 */
class ProgressLine {
 public:
  /// Seconds on a monotonic clock; injected so that tests do not depend on wall time.
  using Clock = std::function<double()>;

  /// Seconds between rewrites on a terminal, and between plain lines elsewhere.
  static constexpr double kTerminalPeriod = 0.2;
  static constexpr double kPlainPeriod = 10.0;

  /// `what` names the work ("reference"), `unit` what is counted ("frames"); `total` <= 0 when unknown.
  ProgressLine(std::string what, std::string unit, long long total, std::ostream& out, bool terminal,
               Clock clock = steadySeconds);

  /// The same on stderr, rewritten in place when stderr is a terminal.
  static ProgressLine onStderr(std::string what, std::string unit, long long total);

  /// Records that `done` items are finished; writes when its period has passed since the last write.
  void update(long long done);

  /// Ends the line when a run stops early (an exception), so that the error starts on a line of its own.
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Writes the final line ("reference: 1761 frames of 64x32 px in 14.9 s, 118 frames/s", `detail`
  /// being "of 64x32 px") and ends it. Only the first call writes.
  void finish(const std::string& detail = "");

  /// The text of one update: done/total, percentage, rate and time left (the pure part, for tests).
  /// `rate` is in items per second, <= 0 when not known yet.
  static std::string format(const std::string& what, const std::string& unit, long long done, long long total,
                            double rate);

  /// "4.7 s", "2 min 05 s", "1 h 02 min".
  static std::string formatDuration(double seconds);

  /// steady_clock in seconds.
  static double steadySeconds();

 private:
  void write(const std::string& text);

  std::string what_;
  std::string unit_;
  long long total_;
  std::ostream& out_;
  bool terminal_;
  Clock clock_;
  double start_;
  double last_write_;
  // The rate is measured from the first update on, so that a slow first item (libraries loaded, files
  // opened) does not make the estimate of the time left far too long.
  bool counting_ = false;
  long long first_done_ = 0;
  double first_time_ = 0.0;
  long long done_ = 0;
  std::size_t last_length_ = 0;
  bool finished_ = false;
};

}  // namespace mrs_vpr
