// Where the command line's words go. stdout carries results only (tables, figures, what was
// written), so it can be piped into another tool; logs, warnings, validation messages and
// progress go to stderr. Progress is a bar redrawn in place on a terminal and plain lines,
// one every few seconds, anywhere else (no carriage returns in a log file).
#pragma once

#include <chrono>
#include <string>

namespace tl::editor {

enum class Verbosity { Quiet, Normal, Verbose };

// spdlog to stderr. `cli`: "[warning] text" lines without timestamps (a headless subcommand);
// otherwise (the editor) with the time of day. Quiet: errors only, no progress; Verbose:
// debug messages too. TWINLIGHT_VERBOSE=1 in the environment is the same as --verbose.
void configureLogging(Verbosity verbosity, bool cli);
Verbosity verbosity();

// Seconds between two plain progress lines: TWINLIGHT_PROGRESS_INTERVAL, else 5.
double progressLineInterval();

// "1:05" (minutes:seconds), "1:02:03" past an hour; "?" for a negative or non-finite value.
std::string formatDuration(double seconds);

// One progress report on stderr for a long command, e.g. "render", with the elapsed time and
// an estimate of the time left from the rate so far. A fraction lower than the last starts a
// new stage (its rate is measured afresh): compare renders the reference, then each path.
class Progress {
 public:
  explicit Progress(std::string task);
  ~Progress();  // finish()
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // `fraction` of the work (or of the stage) done, in [0, 1]; `what` says what is being done.
  void update(double fraction, const std::string& what);
  // Ends the report: the bar's line is closed, and a plain report gets its last line.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  void bar(double fraction, const std::string& what, double elapsed, double eta);
  void line(double fraction, const std::string& what, double elapsed, double eta);

  std::string task_;
  bool enabled_;
  bool terminal_;
  double interval_;
  Clock::time_point stageStart_;
  Clock::time_point lastPrint_;
  double lastFraction_ = -1.0;
  std::string lastWhat_;
  bool printedAny_ = false, lastPrinted_ = false, finished_ = false;
  size_t barWidth_ = 0;  // characters of the last bar drawn, to blank it out
};

}  // namespace tl::editor

namespace tl::editor {

// `twinlight --help`'s footer: the exit codes and the environment variables the program reads.
std::string helpFooter();

}  // namespace tl::editor
