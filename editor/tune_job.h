// Lighting › Tune for this view: `twinlight tune` on the editor's scene, camera and settings, in a
// child process. The editor goes on rendering while it measures (its own device, its own
// memory); the job belongs to the scene: opening another or quitting stops it (SIGTERM to its
// process group, waited for with a bound), and what it measured stays in its folder, so the
// same request resumes. When it finishes, its presets are copied into the presets folder.
#pragma once

#include "session/session.h"

#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace tl::editor {

struct TuneRequest {
  std::filesystem::path scene;
  std::string path;  // "": the editor's path
  session::View view;
  lighting::RenderSettings settings;  // the editor's: the search starts from them (the image size is --size)
  std::vector<std::string> budgets{"1x-legacy"};
  std::string size = "320x180";
  uint32_t candidates = 81, rungs = 3, frames = 32, spp = 256;
  std::filesystem::path out;  // the tune's folder (resumes what it holds)
};

class TuneJob {
 public:
  // Starts the child; SessionError when it cannot (the folder or the program).
  static std::unique_ptr<TuneJob> start(const TuneRequest& request);
  ~TuneJob();  // stops a running child and waits for it

  // Whether the child still runs (reaps it when it has ended).
  bool running();
  // Its exit status once ended (0: every budget has a preset; 1: an error or a budget unmet).
  std::optional<int> exitStatus() const { return status_; }
  // SIGTERM to its process group, then waits up to `seconds`, then SIGKILL; true when it ended
  // before the bound.
  bool stop(double seconds);
  // The last line it printed (its stage), for the panel.
  std::string lastLine() const;
  const TuneRequest& request() const { return request_; }
  // The presets it wrote (preset-*.json in its folder).
  std::vector<std::filesystem::path> presets() const;

 private:
  explicit TuneJob(TuneRequest request) : request_(std::move(request)) {}
  TuneRequest request_;
  pid_t pid_ = -1;
  std::optional<int> status_;
  mutable std::string lastLine_;                                  // lastLine's, between reads of the log
  mutable std::chrono::steady_clock::time_point lastLineReadAt_;
};

// The arguments of `twinlight tune` for a request (without the program name).
std::vector<std::string> tuneArguments(const TuneRequest& request);

}  // namespace tl::editor
