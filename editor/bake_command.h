// `twinlight bake`: the albedo database from the command line — bake a scene (or a shard of
// it), merge databases, list what one holds.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

struct BakeArgs {
  std::string scene;
  std::string db;
  std::string shard;                // "i/N"
  uint32_t batch = 0;               // combinations per submission, 0 = as many as fit
  uint32_t tileSize = 64;
  bool force = false;
  bool list = false;
  std::vector<std::string> merge;   // databases to merge into --db
  bool allowOutsideFiles = false;   // the scene may read files outside its folder
};

int runBake(const BakeArgs& args, const std::string& defaultScene);
