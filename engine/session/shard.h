// Which part of a job this process does: `--shard i/N` given by hand, or `--shard auto` read
// from the scheduler that started it. Slurm job arrays set SLURM_ARRAY_TASK_ID with
// SLURM_ARRAY_TASK_MIN/_STEP/_COUNT (an array may start anywhere, e.g. --array=1-4);
// Kubernetes Indexed Jobs set JOB_COMPLETION_INDEX but not the count, which comes from
// --shard-count or TWINLIGHT_SHARD_COUNT (the Job's completions, set by its manifest).
#pragma once

#include "session/session.h"

#include <cstdint>
#include <functional>
#include <optional>
#include <string>

namespace tl::session {

// Bad shard input (the spec, --shard-count or the scheduler's variables): usage, exit 2.
struct ShardError : SessionError {
  using SessionError::SessionError;
};

// More shards than this is a typo or a broken environment (Slurm's default MaxArraySize is
// 1001, a Kubernetes Indexed Job allows 100,000 completions).
inline constexpr uint32_t kMaxShards = 100000;

struct Shard {
  uint32_t index = 0, count = 1;
  std::string source;  // where it came from, for the log: "--shard 1/4", "Slurm array task 7 (1 of 4)"
};

// Reads an environment variable: std::getenv, or a table in tests.
using Environment = std::function<std::optional<std::string>(const std::string& name)>;
std::optional<std::string> processEnvironment(const std::string& name);

// `spec` is "i/N" (0 <= i < N) or "auto"; `countOption` is --shard-count's text when given
// (only with auto). Throws ShardError naming what is wrong: malformed numbers, an index out
// of range, a count of 0 or above kMaxShards, a Slurm array whose task ids are not one
// contiguous range, a Kubernetes index without a count, or no scheduler at all.
Shard resolveShard(const std::string& spec, const std::optional<std::string>& countOption,
                   const Environment& env = processEnvironment);

// Contiguous blocks of `items` ordered things over `count` shards, sizes differing by at most
// one: item k belongs to shard floor(k * count / items).
uint32_t blockShardOf(size_t item, size_t items, uint32_t count);

}  // namespace tl::session
