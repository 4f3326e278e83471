// The render graph's barrier model, without a GPU, over mixed pass kinds (compute, ray
// tracing, raster, transfer, acceleration-structure builds): every read since the last write
// is waited for, layouts follow the usages, acceleration-structure builds are passes like any
// other, and history carries its state from one frame into the next.
#include "graph/graph.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace tl::graph {
namespace {

const ResourceDesc kImage = ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, 64, 64, "test image");
const ResourceDesc kBuffer = ResourceDesc::buffer(1024, "test buffer");

constexpr VkPipelineStageFlags2 kRaster = VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
constexpr VkPipelineStageFlags2 kCompute = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
constexpr VkPipelineStageFlags2 kRays = VK_PIPELINE_STAGE_2_RAY_TRACING_SHADER_BIT_KHR;
constexpr VkPipelineStageFlags2 kTransfer = VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT;
constexpr VkPipelineStageFlags2 kBuild = VK_PIPELINE_STAGE_2_ACCELERATION_STRUCTURE_BUILD_BIT_KHR;

bool has(VkFlags64 flags, VkFlags64 bits) { return (flags & bits) == bits; }

// A pass of `kind` that touches `resource` with `usage` and writes its own output (so it
// survives culling).
PassId pass(RenderGraph& g, const std::string& name, PassKind kind, const std::string& resource, Usage usage) {
  return g.addPass(name, kind, [&](PassBuilder& b) {
    if (isWrite(usage))
      b.write(resource, usage);
    else
      b.read(resource, usage);
    b.sideEffect();
  }, nullptr);
}

// The barrier on `resource` before the pass named `passName`, or nullptr.
const Barrier* barrierBefore(const RenderGraph& g, const CompiledGraph& c, const std::string& passName,
                             const std::string& resource) {
  for (const auto& cp : c.order) {
    if (g.passes()[cp.pass].name != passName) continue;
    for (const auto& b : cp.barriers)
      if (b.resource == *g.find(resource)) return &b;
  }
  return nullptr;
}

bool waitsFor(const RenderGraph& g, const Barrier& b, const std::string& passName) {
  return std::any_of(b.waitsFor.begin(), b.waitsFor.end(),
                     [&](PassId p) { return p != kNone && g.passes()[p].name == passName; });
}

// One frame's worth of the same shape, fed the states the previous frame left.
EntryStates exitStates(const RenderGraph& g, const CompiledGraph& c) {
  EntryStates out;
  for (ResourceId r = 0; r < g.resources().size(); ++r)
    if (g.resources()[r].persistent || g.resources()[r].imported) out[g.resources()[r].name] = c.exit[r];
  return out;
}

TEST(GraphBarriers, ReadersInDifferentStagesEachWaitForTheWrite) {
  for (const ResourceDesc& desc : {kImage, kBuffer}) {
    const bool image = desc.type == ResourceType::Image;
    RenderGraph g;
    g.addPass("write", PassKind::Compute, [&](PassBuilder& b) { b.create("x", desc, Usage::StorageWrite); }, nullptr);
    const Usage read = image ? Usage::Sampled : Usage::StorageRead;
    pass(g, "draw", PassKind::Raster, "x", read);
    pass(g, "trace", PassKind::RayTracing, "x", read);
    pass(g, "trace.again", PassKind::RayTracing, "x", read);  // same stage and access as `trace`
    pass(g, "dispatch", PassKind::Compute, "x", read);
    auto c = g.compile();

    const VkAccessFlags2 readAccess = image ? VK_ACCESS_2_SHADER_SAMPLED_READ_BIT : VK_ACCESS_2_SHADER_STORAGE_READ_BIT;
    for (auto [reader, stages] : {std::pair{"draw", kRaster}, std::pair{"trace", kRays}, std::pair{"dispatch", kCompute}}) {
      const Barrier* b = barrierBefore(g, c, reader, "x");
      ASSERT_NE(b, nullptr) << reader << " reads what `write` wrote and must wait for it ("
                            << (image ? "image" : "buffer") << ")";
      EXPECT_TRUE(has(b->src.stages, kCompute)) << reader;
      EXPECT_TRUE(has(b->src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT)) << reader;
      EXPECT_EQ(b->dst.stages, stages) << reader;
      EXPECT_TRUE(has(b->dst.access, readAccess)) << reader;
      EXPECT_TRUE(waitsFor(g, *b, "write")) << reader;
    }
    EXPECT_EQ(barrierBefore(g, c, "trace.again", "x"), nullptr) << "no redundant barrier: `trace` already waited";
    if (image) {
      EXPECT_EQ(barrierBefore(g, c, "draw", "x")->oldLayout, VK_IMAGE_LAYOUT_GENERAL);
      EXPECT_EQ(barrierBefore(g, c, "draw", "x")->newLayout, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL);
      // The later readers find the layout already right; they chain onto the transition.
      EXPECT_FALSE(barrierBefore(g, c, "trace", "x")->transition());
      EXPECT_TRUE(has(barrierBefore(g, c, "trace", "x")->src.stages, kRaster));
    }
  }
}

TEST(GraphBarriers, AWriteAfterSeveralReadsWaitsForAllOfThem) {
  // History: last frame's contents are read in three stages, then rewritten.
  for (const ResourceDesc& desc : {kImage, kBuffer}) {
    const bool image = desc.type == ResourceType::Image;
    RenderGraph g;
    g.declarePersistent("history", desc);
    const Usage read = image ? Usage::Sampled : Usage::StorageRead;
    pass(g, "draw", PassKind::Raster, "history", read);
    pass(g, "trace", PassKind::RayTracing, "history", read);
    pass(g, "dispatch", PassKind::Compute, "history", read);
    pass(g, "copy", PassKind::Transfer, "history", Usage::TransferDst);
    ResourceState entry;  // written last frame by a compute pass
    entry.layout = image ? VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_UNDEFINED;
    entry.write = PastAccess{{kCompute, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT}, kNone};
    auto c = g.compile({{"history", entry}});
    const Barrier* b = barrierBefore(g, c, "copy", "history");
    ASSERT_NE(b, nullptr);
    EXPECT_TRUE(has(b->src.stages, kRaster | kRays | kCompute)) << "stages waited for: " << stageNames(b->src.stages);
    for (const char* reader : {"draw", "trace", "dispatch"}) EXPECT_TRUE(waitsFor(g, *b, reader)) << reader;
    EXPECT_EQ(b->dst.stages, kTransfer);
    EXPECT_EQ(b->dst.access, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    if (image) {
      EXPECT_EQ(b->newLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
    }
  }
}

TEST(GraphBarriers, LayoutsFollowTheUsages) {
  RenderGraph g;
  g.addPass("raster", PassKind::Raster, [](PassBuilder& b) { b.create("color", kImage, Usage::ColorAttachment); }, nullptr);
  pass(g, "sample", PassKind::Compute, "color", Usage::Sampled);
  pass(g, "load", PassKind::RayTracing, "color", Usage::StorageRead);
  pass(g, "copy", PassKind::Transfer, "color", Usage::TransferSrc);
  g.addPass("both", PassKind::Compute, [](PassBuilder& b) {  // one pass, two ways: GENERAL
    b.read("color", Usage::Sampled);
    b.read("color", Usage::StorageRead);
    b.sideEffect();
  }, nullptr);
  auto c = g.compile();

  const Barrier* first = barrierBefore(g, c, "raster", "color");
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED) << "a transient's first use discards";
  EXPECT_EQ(first->newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);

  const Barrier* sample = barrierBefore(g, c, "sample", "color");
  ASSERT_NE(sample, nullptr);
  EXPECT_EQ(sample->oldLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  EXPECT_EQ(sample->newLayout, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL);
  EXPECT_EQ(sample->src, (StageAccess{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT}));

  // A reader that needs another layout transitions the image, which rewrites it: it waits for
  // the reader before (in compute) as well as for the colour write.
  const Barrier* load = barrierBefore(g, c, "load", "color");
  ASSERT_NE(load, nullptr);
  EXPECT_EQ(load->oldLayout, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL);
  EXPECT_EQ(load->newLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_TRUE(has(load->src.stages, kCompute | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT));
  EXPECT_TRUE(waitsFor(g, *load, "sample"));
  EXPECT_TRUE(waitsFor(g, *load, "raster"));

  const Barrier* copy = barrierBefore(g, c, "copy", "color");
  ASSERT_NE(copy, nullptr);
  EXPECT_EQ(copy->newLayout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  EXPECT_TRUE(has(copy->src.stages, kRays)) << "the transition waits for the ray-tracing reader";

  const Barrier* both = barrierBefore(g, c, "both", "color");
  ASSERT_NE(both, nullptr);
  EXPECT_EQ(both->newLayout, VK_IMAGE_LAYOUT_GENERAL) << "sampled and storage in one pass share GENERAL";
  EXPECT_TRUE(has(both->dst.access, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT));
}

TEST(GraphBarriers, AReadOnlyPassUsingDepthTwoWaysKeepsItReadOnly) {
  RenderGraph g;
  g.addPass("depth", PassKind::Raster, [](PassBuilder& b) {
    b.create("z", ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, 8, 8), Usage::DepthAttachment);
  }, nullptr);
  g.addPass("test.and.sample", PassKind::Raster, [](PassBuilder& b) {
    b.read("z", Usage::DepthRead);
    b.read("z", Usage::Sampled);
    b.sideEffect();
  }, nullptr);
  auto c = g.compile();
  const Barrier* b = barrierBefore(g, c, "test.and.sample", "z");
  ASSERT_NE(b, nullptr);
  EXPECT_EQ(b->newLayout, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL);
  EXPECT_TRUE(has(b->dst.stages, VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT));
}

// The RT path's shape: refit the bottom levels, build the top level over them, trace it with
// the ray-tracing pipeline and with ray queries; next frame the builds wait for the traces.
TEST(GraphBarriers, AccelerationStructureBuildsAreGraphPasses) {
  auto frame = [](const EntryStates& entry, RenderGraph& g) {
    g.declareImported("vertices", kBuffer);
    g.declareImported("instances", kBuffer);
    g.declareImported("blas", kBuffer);
    g.declareImported("tlas", kBuffer);
    g.addPass("refit", PassKind::AccelerationStructureBuild, [](PassBuilder& b) {
      b.read("vertices", Usage::BuildInput);
      b.read("blas", Usage::AccelerationStructureRead);
      b.write("blas", Usage::AccelerationStructureWrite);
      b.create("refit.scratch", kBuffer, Usage::BuildScratch);
    }, nullptr);
    g.addPass("build", PassKind::AccelerationStructureBuild, [](PassBuilder& b) {
      b.read("instances", Usage::BuildInput);
      b.read("blas", Usage::AccelerationStructureRead);
      b.write("tlas", Usage::AccelerationStructureWrite);
      b.create("build.scratch", kBuffer, Usage::BuildScratch);
    }, nullptr);
    for (auto [name, kind] : {std::pair{"trace", PassKind::RayTracing}, std::pair{"query", PassKind::Compute}}) {
      g.addPass(name, kind, [](PassBuilder& b) {
        b.read("tlas", Usage::AccelerationStructureRead);
        b.read("blas", Usage::AccelerationStructureRead);
        b.sideEffect();
      }, nullptr);
    }
    return g.compile(entry);
  };
  RenderGraph first;
  auto c1 = frame({}, first);

  const Barrier* build = barrierBefore(first, c1, "build", "blas");
  ASSERT_NE(build, nullptr) << "the top level reads the refitted bottom levels";
  EXPECT_EQ(build->src, (StageAccess{kBuild, VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR}));
  EXPECT_EQ(build->dst, (StageAccess{kBuild, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR}));
  for (auto [reader, stages] : {std::pair{"trace", kRays}, std::pair{"query", kCompute}}) {
    const Barrier* t = barrierBefore(first, c1, reader, "tlas");
    ASSERT_NE(t, nullptr) << reader;
    EXPECT_EQ(t->src, (StageAccess{kBuild, VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR})) << reader;
    EXPECT_EQ(t->dst, (StageAccess{stages, VK_ACCESS_2_ACCELERATION_STRUCTURE_READ_BIT_KHR})) << reader;
    EXPECT_NE(barrierBefore(first, c1, reader, "blas"), nullptr) << reader << " reads the refitted levels through the top";
  }
  EXPECT_EQ(barrierBefore(first, c1, "refit", "vertices"), nullptr) << "host-written input: visible at submission";

  // Next frame: the refit rewrites what last frame's build and traces read, the build
  // rewrites what they traced.
  RenderGraph second;
  auto c2 = frame(exitStates(first, c1), second);
  const Barrier* refit = barrierBefore(second, c2, "refit", "blas");
  ASSERT_NE(refit, nullptr);
  EXPECT_TRUE(has(refit->src.stages, kBuild | kRays | kCompute)) << stageNames(refit->src.stages);
  const Barrier* rebuild = barrierBefore(second, c2, "build", "tlas");
  ASSERT_NE(rebuild, nullptr);
  EXPECT_TRUE(has(rebuild->src.stages, kRays | kCompute)) << stageNames(rebuild->src.stages);
  EXPECT_EQ(std::count(rebuild->waitsFor.begin(), rebuild->waitsFor.end(), kNone), 1) << "the previous frame's";
}

TEST(GraphBarriers, HistoryCarriesItsStateIntoTheNextFrame) {
  // rt.temporal's shape: history read in ray tracing and compute, then copied over.
  auto frame = [](const EntryStates& entry, RenderGraph& g) {
    g.declarePersistent("history", kImage);
    pass(g, "lighting", PassKind::RayTracing, "history", Usage::Sampled);
    pass(g, "temporal", PassKind::Compute, "history", Usage::Sampled);
    pass(g, "store", PassKind::Transfer, "history", Usage::TransferDst);
    return g.compile(entry);
  };
  RenderGraph first;
  auto c1 = frame({}, first);
  const Barrier* start = barrierBefore(first, c1, "lighting", "history");
  ASSERT_NE(start, nullptr);
  EXPECT_EQ(start->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED) << "nothing written yet";
  EXPECT_EQ(c1.exit[*first.find("history")].layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);

  RenderGraph second;
  auto c2 = frame(exitStates(first, c1), second);
  for (auto [reader, stages] : {std::pair{"lighting", kRays}, std::pair{"temporal", kCompute}}) {
    const Barrier* b = barrierBefore(second, c2, reader, "history");
    ASSERT_NE(b, nullptr) << reader << " reads what the previous frame's `store` wrote";
    EXPECT_TRUE(has(b->src.stages, kTransfer)) << reader;
    EXPECT_TRUE(has(b->src.access, VK_ACCESS_2_TRANSFER_WRITE_BIT)) << reader;
    EXPECT_TRUE(has(b->dst.stages, stages)) << reader;
    EXPECT_NE(std::find(b->waitsFor.begin(), b->waitsFor.end(), kNone), b->waitsFor.end()) << reader;
  }
  EXPECT_EQ(barrierBefore(second, c2, "lighting", "history")->oldLayout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL)
      << "the layout the previous frame left, not UNDEFINED: the contents are kept";
  const Barrier* store = barrierBefore(second, c2, "store", "history");
  ASSERT_NE(store, nullptr);
  EXPECT_TRUE(has(store->src.stages, kRays | kCompute));
}

TEST(GraphBarriers, TheDumpShowsStagesAccessesLayoutsAndWhoIsWaitedFor) {
  RenderGraph g;
  g.addPass("writer", PassKind::Compute, [](PassBuilder& b) { b.create("x", kImage, Usage::StorageWrite); }, nullptr);
  pass(g, "reader", PassKind::RayTracing, "x", Usage::Sampled);
  std::string d = g.dump(g.compile());
  EXPECT_NE(d.find("barrier x: compute [storage write] -> ray tracing [sampled read], GENERAL -> READ_ONLY; after `writer`"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("barrier x: none -> compute [storage read+storage write], UNDEFINED -> GENERAL (discard)"),
            std::string::npos)
      << d;
}

TEST(GraphBarriers, MisuseOfAKindOfPassNamesBoth) {
  auto error = [](PassKind kind, Usage usage, const ResourceDesc& desc) -> std::string {
    RenderGraph g;
    g.declareImported("thing", desc);
    pass(g, "p", kind, "thing", usage);
    try {
      g.compile();
    } catch (const GraphError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error(PassKind::Transfer, Usage::Sampled, kImage).find("pass `p` (transfer) cannot use `thing` as Sampled"),
            std::string::npos);
  EXPECT_NE(error(PassKind::Compute, Usage::BuildInput, kBuffer).find("cannot use `thing` as BuildInput"),
            std::string::npos);
  EXPECT_NE(error(PassKind::AccelerationStructureBuild, Usage::StorageRead, kBuffer).find("cannot use"),
            std::string::npos);
  EXPECT_NE(error(PassKind::RayTracing, Usage::AccelerationStructureRead, kImage).find("needs a buffer"),
            std::string::npos);
  EXPECT_NE(error(PassKind::Raster, Usage::ColorAttachment, kBuffer).find("needs an image"), std::string::npos);
  EXPECT_EQ(error(PassKind::Compute, Usage::AccelerationStructureRead, kBuffer), "") << "ray queries";
}

}  // namespace
}  // namespace tl::graph
