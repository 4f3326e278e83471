// `twinlight bake`: the albedo database from the command line — bake scenes (or a shard of
// their keys: by hand, or from a Slurm array / Kubernetes Indexed Job), merge databases,
// list what one holds.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

struct BakeArgs {
  std::vector<std::string> scenes;  // baked in order; a key two scenes share is baked once
  std::string db;
  std::string shard;                // "i/N" or "auto"
  std::optional<std::string> shardCount;  // with auto, where the scheduler gives no count
  uint32_t batch = 0;               // combinations per submission, 0 = as many as fit
  uint32_t tileSize = 64;
  bool force = false;
  bool list = false;
  std::vector<std::string> merge;   // databases to merge into --db
  bool allowOutsideFiles = false;   // the scene may read files outside its folder
};

int runBake(const BakeArgs& args, const std::string& defaultScene);
