#include "tune_job.h"

#include "session/presets.h"

#include <fmt/format.h>
#include <glm/glm.hpp>

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <thread>

extern char** environ;

namespace tl::editor {

namespace fs = std::filesystem;

std::vector<std::string> tuneArguments(const TuneRequest& r) {
  const glm::dvec3 at = r.view.position + r.view.forward;
  std::vector<std::string> args{"tune",
                                "--scene", r.scene.string(),
                                "--path", r.path,
                                "--size", r.size,
                                "--look-from", fmt::format("{:.9g},{:.9g},{:.9g}", r.view.position.x, r.view.position.y, r.view.position.z),
                                "--look-at", fmt::format("{:.9g},{:.9g},{:.9g}", at.x, at.y, at.z),
                                "--fov", fmt::format("{:.9g}", glm::degrees(double(r.view.yfovRadians))),
                                "--settings", (r.out / "start-settings.json").string(),
                                "--candidates", std::to_string(r.candidates),
                                "--rungs", std::to_string(r.rungs),
                                "--frames", std::to_string(r.frames),
                                "--spp", std::to_string(r.spp),
                                "--out", r.out.string(),
                                "--stop-with-parent"};  // an editor that dies takes its tune with it
  for (const std::string& b : r.budgets) args.insert(args.end(), {"--budget", b});
  return args;
}

std::unique_ptr<TuneJob> TuneJob::start(const TuneRequest& request) {
  if (request.view.orthographic)
    throw session::SessionError("Tune for this view: an orthographic view cannot be given to tune; look through a perspective camera");
  std::error_code ec;
  fs::create_directories(request.out, ec);
  if (ec) throw session::SessionError(fmt::format("Tune for this view: cannot create {}: {}", request.out.string(), ec.message()));
  session::savePresetFile(request.out / "start-settings.json", request.settings);

  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw session::SessionError(fmt::format("Tune for this view: cannot find the twinlight program: {}", ec.message()));
  std::vector<std::string> args = tuneArguments(request);
  args.insert(args.begin(), self.string());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);

  const std::string log = (request.out / "tune.log").string();
  posix_spawn_file_actions_t files;
  posix_spawnattr_t attributes;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawnattr_init(&attributes);
  // Its own process group: stopping it stops whatever it started.
  posix_spawnattr_setpgroup(&attributes, 0);
  posix_spawnattr_setflags(&attributes, POSIX_SPAWN_SETPGROUP);
  auto job = std::unique_ptr<TuneJob>(new TuneJob(request));
  const int error = posix_spawn(&job->pid_, argv[0], &files, &attributes, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  posix_spawnattr_destroy(&attributes);
  if (error != 0) throw session::SessionError(fmt::format("Tune for this view: cannot start {}: {}", argv[0], std::strerror(error)));
  return job;
}

TuneJob::~TuneJob() {
  if (pid_ > 0 && !status_) stop(5.0);
}

bool TuneJob::running() {
  if (status_ || pid_ <= 0) return false;
  int raw = 0;
  pid_t done = 0;
  do done = waitpid(pid_, &raw, WNOHANG);
  while (done < 0 && errno == EINTR);
  if (done == 0) return true;
  if (done < 0) {  // not our child any more (reaped elsewhere): it has ended, how is unknown
    status_ = 128;
    return false;
  }
  status_ = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + (WIFSIGNALED(raw) ? WTERMSIG(raw) : 0);
  return false;
}

bool TuneJob::stop(double seconds) {
  if (!running()) return true;
  kill(-pid_, SIGTERM);
  const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  while (std::chrono::steady_clock::now() < until) {
    if (!running()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(-pid_, SIGKILL);
  // SIGKILL ends it unless it is stuck in the kernel (a driver): wait a little, then leave it.
  const auto killedUntil = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  while (running() && std::chrono::steady_clock::now() < killedUntil) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  if (!status_) status_ = 128 + SIGKILL;
  return false;
}

std::string TuneJob::lastLine() const {
  // The panel asks every frame: while the tune runs, the log is read at most twice a second, and
  // only its end; once it has ended, always (its last words).
  const auto now = std::chrono::steady_clock::now();
  if (!status_ && now - lastLineReadAt_ < std::chrono::milliseconds(500)) return lastLine_;
  lastLineReadAt_ = now;
  std::ifstream in(request_.out / "tune.log", std::ios::binary | std::ios::ate);
  if (!in) return lastLine_;
  constexpr std::streamoff kTail = 4096;
  const std::streamoff size = in.tellg();
  in.seekg(std::max<std::streamoff>(0, size - kTail));
  std::string line, last;
  while (std::getline(in, line)) {
    // The progress bar rewrites its line with carriage returns: keep what was written last.
    if (const size_t cr = line.find_last_of('\r'); cr != std::string::npos) line = line.substr(cr + 1);
    if (!line.empty()) last = line;
  }
  if (!last.empty()) lastLine_ = last;
  return lastLine_;
}

std::vector<fs::path> TuneJob::presets() const {
  std::vector<fs::path> files;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(request_.out, ec))
    if (e.path().extension() == ".json" && e.path().filename().string().rfind("preset-", 0) == 0) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

}  // namespace tl::editor
