#include "cli_output.h"

#include <fmt/format.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <unistd.h>

namespace tl::editor {
namespace {

Verbosity currentVerbosity = Verbosity::Normal;

bool envSet(const char* name) {
  const char* v = std::getenv(name);
  return v && *v && std::strcmp(v, "0") != 0;
}

// A terminal that redraws a line in place: a bar there, plain lines anywhere else.
bool stderrIsTerminal() {
  const char* term = std::getenv("TERM");
  return ::isatty(STDERR_FILENO) && !(term && std::strcmp(term, "dumb") == 0);
}

}  // namespace

void configureLogging(Verbosity verbosity, bool cli) {
  if (verbosity == Verbosity::Normal && envSet("TWINLIGHT_VERBOSE")) verbosity = Verbosity::Verbose;
  currentVerbosity = verbosity;
  // stderr, coloured only on a terminal (spdlog's automatic mode).
  auto logger = std::make_shared<spdlog::logger>("twinlight", std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  logger->set_pattern(cli ? "%^[%l]%$ %v" : "[%H:%M:%S.%e] %^[%l]%$ %v");
  logger->set_level(verbosity == Verbosity::Quiet     ? spdlog::level::err
                    : verbosity == Verbosity::Verbose ? spdlog::level::debug
                                                      : spdlog::level::warn);
  logger->flush_on(spdlog::level::warn);
  spdlog::set_default_logger(logger);
}

Verbosity verbosity() { return currentVerbosity; }

double progressLineInterval() {
  if (const char* v = std::getenv("TWINLIGHT_PROGRESS_INTERVAL"); v && *v) {
    char* end = nullptr;
    const double seconds = std::strtod(v, &end);
    if (end && *end == '\0' && std::isfinite(seconds) && seconds >= 0.0) return seconds;
  }
  return 5.0;
}

std::string formatDuration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "?";
  const long s = std::lround(seconds);
  if (s >= 3600) return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
  return fmt::format("{}:{:02}", s / 60, s % 60);
}

Progress::Progress(std::string task)
    : task_(std::move(task)),
      enabled_(currentVerbosity != Verbosity::Quiet),
      terminal_(stderrIsTerminal()),
      interval_(progressLineInterval()),
      stageStart_(Clock::now()),
      lastPrint_(stageStart_) {}

Progress::~Progress() { finish(); }

void Progress::update(double fraction, const std::string& what) {
  if (!enabled_ || finished_) return;
  fraction = std::clamp(std::isfinite(fraction) ? fraction : 0.0, 0.0, 1.0);
  const Clock::time_point now = Clock::now();
  if (fraction < lastFraction_) stageStart_ = now;  // a new stage: its own rate
  const double elapsed = std::chrono::duration<double>(now - stageStart_).count();
  // The rate so far, extrapolated; unknown before anything is done.
  const double eta = fraction >= 1.0 ? 0.0 : fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : -1.0;
  const double sinceLast = std::chrono::duration<double>(now - lastPrint_).count();
  const bool stageDone = fraction >= 1.0 && lastFraction_ < 1.0;
  bool print;
  if (terminal_) print = !printedAny_ || stageDone || sinceLast >= 0.1;
  else print = !printedAny_ || stageDone || sinceLast >= interval_;
  lastFraction_ = fraction;
  lastWhat_ = what;
  lastPrinted_ = print;
  if (!print) return;
  if (terminal_) {
    bar(fraction, what, elapsed, eta);
    // A finished stage keeps its line: what is printed next (a stage's results) starts below.
    if (fraction >= 1.0) fmt::print(stderr, "\n"), barWidth_ = 0;
  } else {
    line(fraction, what, elapsed, eta);
  }
  printedAny_ = true;
  lastPrint_ = now;
}

void Progress::bar(double fraction, const std::string& what, double elapsed, double eta) {
  constexpr int kCells = 30;
  const int filled = int(fraction * kCells + 0.5);
  std::string text = fmt::format("{} [{}{}] {:3.0f}% {}  {}{}", task_, std::string(size_t(filled), '#'),
                                 std::string(size_t(kCells - filled), ' '), fraction * 100.0, what, formatDuration(elapsed),
                                 eta >= 0.0 ? fmt::format(", {} left", formatDuration(eta)) : std::string());
  const size_t width = text.size();
  if (width < barWidth_) text += std::string(barWidth_ - width, ' ');  // blank the longer last bar
  barWidth_ = width;
  std::fflush(stdout);  // as in line()
  fmt::print(stderr, "\r{}", text);
  std::fflush(stderr);
}

void Progress::line(double fraction, const std::string& what, double elapsed, double eta) {
  // What the command printed before comes first: stdout is buffered when it is a pipe, and a
  // reader of both streams (a log, a test) would find this line in the middle of one of its lines.
  std::fflush(stdout);
  fmt::print(stderr, "{}: {:3.0f}% {}, {} elapsed{}\n", task_, fraction * 100.0, what, formatDuration(elapsed),
             eta >= 0.0 ? fmt::format(", {} left", formatDuration(eta)) : std::string());
  std::fflush(stderr);
}

void Progress::finish() {
  if (!enabled_ || finished_) return;
  finished_ = true;
  if (!lastPrinted_ && lastFraction_ >= 0.0) {
    // The last state, which the interval held back.
    const double elapsed = std::chrono::duration<double>(Clock::now() - stageStart_).count();
    const double eta = lastFraction_ >= 1.0 ? 0.0 : -1.0;
    if (terminal_) bar(lastFraction_, lastWhat_, elapsed, eta);
    else line(lastFraction_, lastWhat_, elapsed, eta);
    printedAny_ = true;
  }
  if (terminal_ && barWidth_ > 0) fmt::print(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace tl::editor

namespace tl::editor {

std::string helpFooter() {
  return R"(Output:
  stdout carries results only (tables, figures, the files written; with --json - one JSON
  document and nothing else). Logs, warnings, Vulkan validation messages and progress go to
  stderr: a bar on a terminal, else a plain line every few seconds. -q: errors only, no
  progress. -v: debug messages too.

Exit codes:
  0  success
  1  failure: a bad value, a file that cannot be read or written, an error at run time, or
     Vulkan validation errors (when TWINLIGHT_VALIDATION=1)
  2  usage: a command line that does not parse or options that contradict each other
  3  a regression gate failed (compare --fail-above): the figures are printed and written
  4  the GPU did not finish its work within TWINLIGHT_GPU_TIMEOUT (a hung device)
  5  a regression gate is undecided (compare --fail-above): no figure is above its threshold, but
     one lies within the reference's noise of it (its 95% interval holds it); render the
     reference with more samples
  Every error is one line on stderr that starts with the program's name and "error:".

Environment:
  TWINLIGHT_VALIDATION=1         Vulkan validation layers (synchronization validation included);
                                 a validation error makes the exit code 1
  TWINLIGHT_DEVICE=NAME          use the Vulkan device whose name contains NAME
  TWINLIGHT_NO_RAY_TRACING=1     behave as on a device without ray tracing
  TWINLIGHT_GPU_TIMEOUT=S        seconds a GPU wait may take before the process stops with exit
                                 code 4 (default 600)
  TWINLIGHT_VERBOSE=1            as --verbose
  TWINLIGHT_PROGRESS_INTERVAL=S  seconds between plain progress lines when stderr is not a
                                 terminal (default 5; 0: every step)
  TWINLIGHT_ROOT=DIR             the content folder is DIR/content
  TWINLIGHT_SHADER_DIR=DIR       compiled shaders (SPIR-V) from DIR
  TWINLIGHT_SHADER_SOURCES=DIR   GLSL sources the editor watches for hot reload
  TWINLIGHT_SHARD_COUNT=N        --shard auto under a Kubernetes Indexed Job: the shard count
  SLURM_ARRAY_TASK_ID, SLURM_ARRAY_TASK_MIN, SLURM_ARRAY_TASK_COUNT, SLURM_ARRAY_TASK_STEP,
  JOB_COMPLETION_INDEX           read by --shard auto (a Slurm job array, a Kubernetes job)
  XDG_CACHE_HOME                 the reference cache lives in $XDG_CACHE_HOME/twinlight
  XDG_CONFIG_HOME                editor settings and camera bookmarks ($HOME/.config default)
  DISPLAY, WAYLAND_DISPLAY       without either, `twinlight SCENE` renders headless
  LP_NUM_THREADS=N               lavapipe's (software Vulkan) worker threads
)";
}

}  // namespace tl::editor
