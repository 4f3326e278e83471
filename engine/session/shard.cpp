#include "session/shard.h"

#include <fmt/format.h>

#include <cstdlib>

namespace tl::session {
namespace {

// Slurm's task ids are below its MaxArraySize, which is at most 4,000,001.
constexpr uint32_t kMaxSlurmTaskId = 4000000;

// A count, index or id as the scheduler or the user wrote it: decimal digits only (no sign,
// no spaces, no exponent), at most `limit`. `what` names the source in the error.
uint32_t parseNumber(const std::string& text, const std::string& what, uint32_t limit = kMaxShards) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    throw ShardError(fmt::format("{} `{}` is not a whole number", what, text));
  if (text.size() > 9 || std::stoul(text) > limit)
    throw ShardError(fmt::format("{} `{}` is above the limit of {}", what, text, limit));
  return uint32_t(std::stoul(text));
}

uint32_t parseCount(const std::string& text, const std::string& what, uint32_t limit = kMaxShards) {
  const uint32_t n = parseNumber(text, what, limit);
  if (n == 0) throw ShardError(fmt::format("{} is 0: a job has at least one shard", what));
  return n;
}

Shard checked(uint32_t index, uint32_t count, std::string source) {
  if (index >= count)
    throw ShardError(fmt::format("{}: shard index {} is not below the shard count {}", source, index, count));
  return {index, count, std::move(source)};
}

std::optional<std::string> nonEmpty(const Environment& env, const std::string& name) {
  std::optional<std::string> v = env(name);
  if (v && v->empty()) return std::nullopt;
  return v;
}

// A Slurm array task: its index is its id's place in the array (ids run from MIN in STEPs;
// --array=1-4 gives ids 1..4 and indices 0..3).
Shard fromSlurm(const Environment& env, const std::string& idText, const std::optional<uint32_t>& countOption) {
  auto need = [&](const char* name) {
    std::optional<std::string> v = nonEmpty(env, name);
    if (!v) throw ShardError(fmt::format("SLURM_ARRAY_TASK_ID is set but {} is not: not a Slurm job array task", name));
    return *v;
  };
  const uint32_t id = parseNumber(idText, "SLURM_ARRAY_TASK_ID", kMaxSlurmTaskId);
  const uint32_t count = parseCount(need("SLURM_ARRAY_TASK_COUNT"), "SLURM_ARRAY_TASK_COUNT");
  const uint32_t min = parseNumber(need("SLURM_ARRAY_TASK_MIN"), "SLURM_ARRAY_TASK_MIN", kMaxSlurmTaskId);
  const std::optional<std::string> stepText = nonEmpty(env, "SLURM_ARRAY_TASK_STEP");
  const uint32_t step = stepText ? parseCount(*stepText, "SLURM_ARRAY_TASK_STEP", kMaxSlurmTaskId) : 1;
  if (countOption && *countOption != count)
    throw ShardError(fmt::format("--shard-count {} disagrees with the Slurm array's {} tasks (SLURM_ARRAY_TASK_COUNT)",
                                 *countOption, count));
  const std::string source = fmt::format("Slurm array task {} (ids from {} in steps of {}, {} tasks)", id, min, step, count);
  if (id < min || (id - min) % step != 0 || (id - min) / step >= count)
    throw ShardError(fmt::format("{}: the task ids are not one range MIN, MIN+STEP, ... of COUNT ids (--array=A-B[:S]); "
                                 "give --shard i/N for other arrays",
                                 source));
  return checked((id - min) / step, count, source);
}

}  // namespace

std::optional<std::string> processEnvironment(const std::string& name) {
  const char* v = std::getenv(name.c_str());
  return v ? std::optional<std::string>(v) : std::nullopt;
}

Shard resolveShard(const std::string& spec, const std::optional<std::string>& countOption, const Environment& env) {
  std::optional<uint32_t> count;
  if (countOption) count = parseCount(*countOption, "--shard-count");
  if (spec != "auto") {
    if (count) throw ShardError("--shard-count goes with --shard auto (--shard i/N gives the count itself)");
    const size_t slash = spec.find('/');
    if (slash == std::string::npos)
      throw ShardError(fmt::format("--shard `{}` is not i/N (0 <= i < N) or auto", spec));
    const uint32_t i = parseNumber(spec.substr(0, slash), "--shard's index");
    const uint32_t n = parseCount(spec.substr(slash + 1), "--shard's count");
    return checked(i, n, fmt::format("--shard {}", spec));
  }
  if (std::optional<std::string> id = nonEmpty(env, "SLURM_ARRAY_TASK_ID")) return fromSlurm(env, *id, count);
  if (std::optional<std::string> index = nonEmpty(env, "JOB_COMPLETION_INDEX")) {
    if (!count) {
      if (std::optional<std::string> fromJob = nonEmpty(env, "TWINLIGHT_SHARD_COUNT"))
        count = parseCount(*fromJob, "TWINLIGHT_SHARD_COUNT");
      else
        throw ShardError("JOB_COMPLETION_INDEX is set (a Kubernetes Indexed Job) but not the shard count: give "
                         "--shard-count N or set TWINLIGHT_SHARD_COUNT to the Job's completions");
    }
    const uint32_t i = parseNumber(*index, "JOB_COMPLETION_INDEX");
    return checked(i, *count, fmt::format("Kubernetes completion index {} of {}", i, *count));
  }
  throw ShardError("--shard auto: no scheduler found: neither SLURM_ARRAY_TASK_ID (a Slurm job array) nor "
                   "JOB_COMPLETION_INDEX (a Kubernetes Indexed Job) is set; give --shard i/N outside a scheduler");
}

uint32_t blockShardOf(size_t item, size_t items, uint32_t count) {
  if (items == 0 || count <= 1) return 0;
  return uint32_t((uint64_t(item) * count) / items);
}

}  // namespace tl::session
