// Shards: --shard i/N and --shard auto from a Slurm array or a Kubernetes Indexed Job, every
// malformed value refused by name; views to shards in balanced contiguous blocks; and the
// merge of a compare sweep's shard folders, which must be the shards 0..N-1 of one sweep.
#include "session/provenance.h"
#include "session/shard.h"
#include "session/sweep.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>

namespace tl::session {
namespace {

Environment table(std::map<std::string, std::string> values) {
  return [values](const std::string& name) -> std::optional<std::string> {
    auto it = values.find(name);
    return it == values.end() ? std::nullopt : std::optional<std::string>(it->second);
  };
}

// The message of the ShardError resolveShard throws ("" when it throws none).
std::string refusal(const std::string& spec, std::optional<std::string> count, std::map<std::string, std::string> env) {
  try {
    resolveShard(spec, count, table(std::move(env)));
  } catch (const ShardError& e) {
    return e.what();
  }
  return "";
}

void expectRefused(const std::string& spec, std::optional<std::string> count, std::map<std::string, std::string> env,
                   const std::string& words) {
  const std::string message = refusal(spec, count, std::move(env));
  EXPECT_NE(message.find(words), std::string::npos) << "spec " << spec << ": `" << message << "` lacks `" << words << "`";
}

const std::map<std::string, std::string> kNone;

TEST(Shard, ExplicitIndexAndCount) {
  Shard s = resolveShard("2/5", std::nullopt, table(kNone));
  EXPECT_EQ(s.index, 2u);
  EXPECT_EQ(s.count, 5u);
  s = resolveShard("0/1", std::nullopt, table(kNone));
  EXPECT_EQ(s.index, 0u);
  EXPECT_EQ(s.count, 1u);
}

TEST(Shard, ExplicitValuesAreChecked) {
  expectRefused("3/3", std::nullopt, kNone, "shard index 3 is not below the shard count 3");
  expectRefused("0/0", std::nullopt, kNone, "is 0: a job has at least one shard");
  expectRefused("-1/3", std::nullopt, kNone, "`-1` is not a whole number");
  expectRefused("1/3x", std::nullopt, kNone, "`3x` is not a whole number");
  expectRefused(" 1/3", std::nullopt, kNone, "not a whole number");
  expectRefused("1/", std::nullopt, kNone, "`` is not a whole number");
  expectRefused("13", std::nullopt, kNone, "is not i/N");
  expectRefused("1/100001", std::nullopt, kNone, "above the limit of 100000");
  expectRefused("1/99999999999999999999", std::nullopt, kNone, "above the limit");
  expectRefused("1/4", "4", kNone, "--shard-count goes with --shard auto");
}

TEST(Shard, SlurmArrayFromZero) {
  const Shard s = resolveShard("auto", std::nullopt,
                               table({{"SLURM_ARRAY_TASK_ID", "3"}, {"SLURM_ARRAY_TASK_COUNT", "4"},
                                      {"SLURM_ARRAY_TASK_MIN", "0"}, {"SLURM_ARRAY_TASK_MAX", "3"}}));
  EXPECT_EQ(s.index, 3u);
  EXPECT_EQ(s.count, 4u);
  EXPECT_NE(s.source.find("Slurm array task 3"), std::string::npos) << s.source;
}

TEST(Shard, SlurmArrayNotStartingAtZeroOrWithASteps) {
  // --array=1-4: ids 1..4 are indices 0..3.
  Shard s = resolveShard("auto", std::nullopt,
                         table({{"SLURM_ARRAY_TASK_ID", "1"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "1"}}));
  EXPECT_EQ(s.index, 0u);
  EXPECT_EQ(s.count, 4u);
  // --array=10-16:3: ids 10, 13, 16 are indices 0..2.
  s = resolveShard("auto", std::nullopt,
                   table({{"SLURM_ARRAY_TASK_ID", "16"}, {"SLURM_ARRAY_TASK_COUNT", "3"}, {"SLURM_ARRAY_TASK_MIN", "10"},
                          {"SLURM_ARRAY_TASK_STEP", "3"}}));
  EXPECT_EQ(s.index, 2u);
  EXPECT_EQ(s.count, 3u);
  // A --shard-count that agrees is accepted.
  s = resolveShard("auto", "4",
                   table({{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "0"}}));
  EXPECT_EQ(s.index, 2u);
}

TEST(Shard, SlurmVariablesAreChecked) {
  expectRefused("auto", std::nullopt, {{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_MIN", "0"}},
                "SLURM_ARRAY_TASK_COUNT is not");
  expectRefused("auto", std::nullopt, {{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}},
                "SLURM_ARRAY_TASK_MIN is not");
  expectRefused("auto", std::nullopt,
                {{"SLURM_ARRAY_TASK_ID", "x2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "0"}},
                "SLURM_ARRAY_TASK_ID `x2` is not a whole number");
  expectRefused("auto", std::nullopt,
                {{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "0"}, {"SLURM_ARRAY_TASK_MIN", "0"}},
                "SLURM_ARRAY_TASK_COUNT is 0");
  // --array=1,3,7 (a list): id 7 is not within MIN + COUNT steps.
  expectRefused("auto", std::nullopt,
                {{"SLURM_ARRAY_TASK_ID", "7"}, {"SLURM_ARRAY_TASK_COUNT", "3"}, {"SLURM_ARRAY_TASK_MIN", "1"}},
                "not one range");
  // An id below MIN, or between steps.
  expectRefused("auto", std::nullopt,
                {{"SLURM_ARRAY_TASK_ID", "0"}, {"SLURM_ARRAY_TASK_COUNT", "3"}, {"SLURM_ARRAY_TASK_MIN", "1"}},
                "not one range");
  expectRefused("auto", std::nullopt,
                {{"SLURM_ARRAY_TASK_ID", "11"}, {"SLURM_ARRAY_TASK_COUNT", "3"}, {"SLURM_ARRAY_TASK_MIN", "10"},
                 {"SLURM_ARRAY_TASK_STEP", "3"}},
                "not one range");
  expectRefused("auto", "5", {{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "4"}, {"SLURM_ARRAY_TASK_MIN", "0"}},
                "--shard-count 5 disagrees with the Slurm array's 4 tasks");
  expectRefused("auto", std::nullopt,
                {{"SLURM_ARRAY_TASK_ID", "2"}, {"SLURM_ARRAY_TASK_COUNT", "200000"}, {"SLURM_ARRAY_TASK_MIN", "0"}},
                "above the limit");
}

TEST(Shard, KubernetesIndexWithItsCount) {
  Shard s = resolveShard("auto", "8", table({{"JOB_COMPLETION_INDEX", "5"}}));
  EXPECT_EQ(s.index, 5u);
  EXPECT_EQ(s.count, 8u);
  s = resolveShard("auto", std::nullopt, table({{"JOB_COMPLETION_INDEX", "0"}, {"TWINLIGHT_SHARD_COUNT", "3"}}));
  EXPECT_EQ(s.index, 0u);
  EXPECT_EQ(s.count, 3u);
  // The command line's count wins over the job's variable.
  s = resolveShard("auto", "6", table({{"JOB_COMPLETION_INDEX", "4"}, {"TWINLIGHT_SHARD_COUNT", "3"}}));
  EXPECT_EQ(s.count, 6u);
}

TEST(Shard, KubernetesVariablesAreChecked) {
  expectRefused("auto", std::nullopt, {{"JOB_COMPLETION_INDEX", "1"}}, "give --shard-count N or set TWINLIGHT_SHARD_COUNT");
  expectRefused("auto", "3", {{"JOB_COMPLETION_INDEX", "3"}}, "shard index 3 is not below the shard count 3");
  expectRefused("auto", std::nullopt, {{"JOB_COMPLETION_INDEX", "1"}, {"TWINLIGHT_SHARD_COUNT", "three"}},
                "TWINLIGHT_SHARD_COUNT `three` is not a whole number");
  expectRefused("auto", "0", {{"JOB_COMPLETION_INDEX", "0"}}, "--shard-count is 0");
}

TEST(Shard, AutoWithoutASchedulerSaysSo) {
  expectRefused("auto", std::nullopt, kNone, "neither SLURM_ARRAY_TASK_ID (a Slurm job array) nor JOB_COMPLETION_INDEX");
  // Empty variables count as unset.
  expectRefused("auto", std::nullopt, {{"SLURM_ARRAY_TASK_ID", ""}, {"JOB_COMPLETION_INDEX", ""}}, "neither");
}

TEST(Shard, BlocksAreContiguousAndBalanced) {
  for (size_t items : {1u, 2u, 3u, 7u, 100u, 1001u})
    for (uint32_t count : {1u, 2u, 3u, 4u, 16u}) {
      std::vector<size_t> sizes(count, 0);
      uint32_t previous = 0;
      for (size_t k = 0; k < items; ++k) {
        const uint32_t shard = blockShardOf(k, items, count);
        ASSERT_LT(shard, count);
        EXPECT_GE(shard, previous) << "not contiguous";
        previous = shard;
        ++sizes[shard];
      }
      const auto [lo, hi] = std::minmax_element(sizes.begin(), sizes.end());
      if (items >= count) EXPECT_LE(*hi - *lo, 1u) << items << " items over " << count;
      else EXPECT_LE(*hi, 1u);
    }
}

TEST(Sweep, PlanFoldersFollowTheGrid) {
  auto cameras = [](const std::string& file) {
    return file == "a/grove.gltf" ? std::vector<std::string>{"camera0", "camera1"} : std::vector<std::string>{"camera0"};
  };
  SweepPlan one = planSweep({"a/cornell.gltf"}, nullptr);
  ASSERT_EQ(one.views.size(), 1u);
  EXPECT_EQ(one.views[0].dir, "");
  SweepPlan oneWithCameras = planSweep({"a/grove.gltf"}, cameras);
  ASSERT_EQ(oneWithCameras.views.size(), 2u);
  EXPECT_EQ(oneWithCameras.views[1].dir, "camera1");
  SweepPlan grid = planSweep({"a/cornell.gltf", "a/grove.gltf"}, cameras);
  ASSERT_EQ(grid.views.size(), 3u);
  EXPECT_EQ(grid.views[0].dir, "cornell/camera0");
  EXPECT_EQ(grid.views[2].dir, "grove/camera1");
  EXPECT_EQ(grid.views[2].camera, "camera1");
  SweepPlan scenes = planSweep({"a/cornell.gltf", "a/grove.gltf"}, nullptr);
  EXPECT_EQ(scenes.views[1].dir, "grove");
  EXPECT_THROW(planSweep({"a/cornell.gltf", "b/cornell.gltf"}, nullptr), SessionError);
}

// A merge from fabricated shard folders (no GPU): what a real sweep's shards would hold.
class SweepMerge : public ::testing::Test {
 protected:
  std::filesystem::path root = std::filesystem::temp_directory_path() / "tl_test_sweep_merge";
  SweepPlan plan = planSweep({"s/cornell.gltf", "s/grove.gltf"}, [](const std::string& file) {
    return file == "s/grove.gltf" ? std::vector<std::string>{"camera0", "camera1"} : std::vector<std::string>{"camera0"};
  });
  CompareOptions options;

  void SetUp() override {
    std::filesystem::remove_all(root);
    options.paths = {"direct", "rt"};
  }
  void TearDown() override { std::filesystem::remove_all(root); }

  static void write(const std::filesystem::path& file, const nlohmann::json& j) {
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file) << j.dump(2);
  }
  // Shard `index` of `count`: its views' reports (FLIP of `direct` = 0.1 * (view + 1)) and its manifest.
  void shard(uint32_t index, uint32_t count, const nlohmann::json& grid,
             const nlohmann::json& build = twinlightJson()) {
    const std::filesystem::path dir = root / ("shard" + std::to_string(index));
    nlohmann::json held = nlohmann::json::array();
    for (size_t v = 0; v < plan.views.size(); ++v) {
      if (blockShardOf(v, plan.views.size(), count) != index) continue;
      held.push_back(v);
      nlohmann::json paths = nlohmann::json::array();
      paths.push_back({{"path", "direct"}, {"lightingPath", "direct"}, {"frameMs", 1.0}, {"FLIP", 0.1 * double(v + 1)}});
      paths.push_back({{"path", "rt"}, {"lightingPath", "rt"}, {"frameMs", 3.0}, {"FLIP", nullptr}});
      write(dir / plan.views[v].dir / "report.json",
            {{"scene", plan.views[v].sceneFile}, {"device", "test"}, {"reference", {{"spp", 16}}}, {"paths", paths},
             {"forms", nlohmann::json::object()}, {"metrics", nlohmann::json::object()}});
      std::ofstream(dir / plan.views[v].dir / "direct.png") << "image " << v;
    }
    write(dir / "shard.json", {{"kind", "twinlight compare shard"},
                               {"twinlight", build},
                               {"shard", {{"index", index}, {"count", count}, {"source", "test"}}},
                               {"views", held},
                               {"grid", grid}});
  }
  std::filesystem::path dir(uint32_t index) { return root / ("shard" + std::to_string(index)); }
  std::string mergeRefusal(const std::vector<std::filesystem::path>& dirs) {
    try {
      mergeSweep(dirs, root / "merged");
    } catch (const SessionError& e) {
      return e.what();
    }
    return "";
  }
};

TEST_F(SweepMerge, AssemblesEveryViewAndTheMeans) {
  const nlohmann::json grid = sweepGrid(plan, options);
  shard(0, 2, grid);
  shard(1, 2, grid);
  const nlohmann::json report = mergeSweep({dir(1), dir(0)}, root / "merged");
  EXPECT_EQ(report["kind"], "sweep");
  ASSERT_EQ(report["views"].size(), 3u);
  EXPECT_EQ(report["views"][2]["report"], "grove/camera1/report.json");
  for (const auto& v : plan.views) EXPECT_TRUE(std::filesystem::exists(root / "merged" / v.dir / "direct.png")) << v.dir;
  EXPECT_FALSE(std::filesystem::exists(root / "merged" / "shard.json"));
  EXPECT_TRUE(std::filesystem::exists(root / "merged" / "report.html"));
  ASSERT_EQ(report["configurations"].size(), 2u);
  EXPECT_DOUBLE_EQ(report["configurations"][0]["FLIP"].get<double>(), (0.1 + 0.2 + 0.3) / 3.0);
  EXPECT_TRUE(report["configurations"][1]["FLIP"].is_null()) << "a missing figure must not vanish into a mean";
  EXPECT_EQ(report["grid"], grid);
  EXPECT_EQ(report["twinlight"], twinlightJson()) << "the merged report names the build that merged it";
}

TEST_F(SweepMerge, RefusesIncompleteForeignAndDuplicateShards) {
  const nlohmann::json grid = sweepGrid(plan, options);
  shard(0, 3, grid);
  shard(1, 3, grid);
  EXPECT_NE(mergeRefusal({dir(0), dir(1)}).find("shard(s) 2 of 3 missing"), std::string::npos);
  EXPECT_NE(mergeRefusal({dir(0), dir(1), dir(1)}).find("are both shard 1/3"), std::string::npos);
  EXPECT_NE(mergeRefusal({dir(0), root / "nowhere"}).find("no shard.json"), std::string::npos);
  CompareOptions other = options;
  other.referenceSpp = 1024;
  shard(2, 3, sweepGrid(plan, other));
  EXPECT_NE(mergeRefusal({dir(0), dir(1), dir(2)}).find("is a shard of another sweep"), std::string::npos);
  nlohmann::json otherBuild = twinlightJson();
  otherBuild["commit"] = "0123456789abcdef0123456789abcdef01234567";
  otherBuild["modified"] = true;
  shard(2, 3, grid, otherBuild);
  const std::string mixed = mergeRefusal({dir(0), dir(1), dir(2)});
  EXPECT_NE(mixed.find("must come from one build"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("commit 0123456789ab, modified"), std::string::npos) << mixed;
  shard(2, 4, grid);
  EXPECT_NE(mergeRefusal({dir(0), dir(1), dir(2)}).find("is shard 2/4, but"), std::string::npos);
  EXPECT_NE(mergeRefusal({dir(0), dir(1), dir(0)}).find("are both shard 0/3"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(root / "merged" / "report.json")) << "a refused merge wrote a report";
}

}  // namespace
}  // namespace tl::session
