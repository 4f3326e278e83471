#include "scene/input_limits.h"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

namespace tl::scene {
namespace {

const char* kindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& why) {
  throw InputFileError(fmt::format("{}: {}", file.string(), why));
}

// Closes on every path out.
struct Fd {
  int fd = -1;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

// O_NONBLOCK: opening a FIFO with no writer would otherwise wait for one. The descriptor is
// examined (fstat) before anything is read, so what is checked is what is read.
int openForReading(const std::filesystem::path& file, struct stat& st) {
  int fd = ::open(file.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    const int e = errno;
    if (e == ENOENT || e == ENOTDIR) fail(file, "file not found");
    fail(file, fmt::format("cannot open: {}", std::strerror(e)));
  }
  if (::fstat(fd, &st) != 0) {
    const int e = errno;
    ::close(fd);
    fail(file, fmt::format("cannot examine: {}", std::strerror(e)));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    fail(file, fmt::format("is {}, not a regular file", kindOf(st.st_mode)));
  }
  return fd;
}

}  // namespace

std::string byteSize(uint64_t bytes) {
  if (bytes >= (uint64_t(1) << 30)) return fmt::format("{:.1f} GiB", double(bytes) / double(uint64_t(1) << 30));
  if (bytes >= (uint64_t(1) << 20)) return fmt::format("{:.1f} MiB", double(bytes) / double(uint64_t(1) << 20));
  if (bytes >= (uint64_t(1) << 10)) return fmt::format("{:.1f} KiB", double(bytes) / 1024.0);
  return fmt::format("{} bytes", bytes);
}

std::vector<uint8_t> readRegularFile(const std::filesystem::path& file, uint64_t maxBytes) {
  struct stat st {};
  Fd fd{openForReading(file, st)};
  const uint64_t size = uint64_t(st.st_size);
  if (size > maxBytes)
    fail(file, fmt::format("is {} bytes, more than the {} bytes ({}) allowed", size, maxBytes, byteSize(maxBytes)));
  std::vector<uint8_t> bytes(size);
  size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd.fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(file, fmt::format("read error: {}", std::strerror(errno)));
    if (n == 0) fail(file, "the file shrank while it was read");
    done += size_t(n);
  }
  return bytes;
}

void requireRegularFile(const std::filesystem::path& file, bool mayBeMissing) {
  struct stat st {};
  if (::stat(file.c_str(), &st) != 0) {
    if (errno == ENOENT && mayBeMissing) return;
    if (errno == ENOENT || errno == ENOTDIR) fail(file, "file not found");
    fail(file, fmt::format("cannot examine: {}", std::strerror(errno)));
  }
  if (!S_ISREG(st.st_mode)) fail(file, fmt::format("is {}, not a regular file", kindOf(st.st_mode)));
}

size_t jsonNestingDepth(std::string_view text, size_t stopAt) {
  size_t depth = 0, deepest = 0;
  bool inString = false, escaped = false;
  for (char c : text) {
    if (inString) {
      if (escaped) escaped = false;
      else if (c == '\\') escaped = true;
      else if (c == '"') inString = false;
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '{' || c == '[') {
      deepest = std::max(deepest, ++depth);
      if (deepest >= stopAt) return deepest;
    } else if ((c == '}' || c == ']') && depth > 0) {
      --depth;
    }
  }
  return deepest;
}

void requireJsonDepth(std::string_view text, const std::string& what) {
  const size_t limit = InputLimits::kMaxJsonDepth;
  if (jsonNestingDepth(text, limit + 1) > limit)
    throw InputFileError(fmt::format("{}: JSON nests deeper than {} levels", what, limit));
}

bool isInsideFolder(const std::filesystem::path& folder, const std::filesystem::path& file) {
  std::error_code ec;
  const auto root = std::filesystem::weakly_canonical(folder.empty() ? "." : folder, ec);
  if (ec) return false;
  const auto target = std::filesystem::weakly_canonical(file, ec);
  if (ec) return false;
  const auto relative = target.lexically_relative(root);
  return !relative.empty() && *relative.begin() != "..";
}

}  // namespace tl::scene
