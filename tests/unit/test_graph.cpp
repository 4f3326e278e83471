// Render-graph compile logic, without a GPU: ordering, culling, barriers, lifetimes,
// persistent history and the error messages (each names both sides).
#include "graph/graph.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace tl::graph {
namespace {

const ResourceDesc kImage = ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, 64, 64, "test image");

// A compute pass reading `reads` and creating `creates`.
PassId compute(RenderGraph& g, const std::string& name, std::vector<std::string> reads, std::vector<std::string> creates) {
  return g.addPass(name, PassKind::Compute, [&](PassBuilder& b) {
    for (auto& r : reads) b.read(r, Usage::Sampled);
    for (auto& c : creates) b.create(c, kImage, Usage::StorageWrite);
  }, nullptr);
}

std::vector<std::string> orderNames(const RenderGraph& g, const CompiledGraph& c) {
  std::vector<std::string> out;
  for (auto& p : c.order) out.push_back(g.passes()[p.pass].name);
  return out;
}

std::string errorOf(const RenderGraph& g) {
  try {
    g.compile();
  } catch (const GraphError& e) {
    return e.what();
  }
  return "";
}

TEST(Graph, OrdersByDependencyNotDeclaration) {
  RenderGraph g;
  compute(g, "consumer", {"a"}, {"b"});
  compute(g, "producer", {}, {"a"});
  g.markOutput("b");
  auto c = g.compile();
  EXPECT_EQ(orderNames(g, c), (std::vector<std::string>{"producer", "consumer"}));
}

TEST(Graph, CullsPassesWhoseOutputsNobodyReadsTransitively) {
  RenderGraph g;
  compute(g, "gbuffer", {}, {"gbuffer.normal"});
  compute(g, "debug.a", {"gbuffer.normal"}, {"debug.tmp"});
  compute(g, "debug.b", {"debug.tmp"}, {"debug.unused"});
  compute(g, "composite", {"gbuffer.normal"}, {"final"});
  g.markOutput("final");
  auto c = g.compile();
  EXPECT_EQ(orderNames(g, c), (std::vector<std::string>{"gbuffer", "composite"}));
  ASSERT_EQ(c.culled.size(), 2u);
  EXPECT_TRUE(c.resources[*g.find("debug.tmp")].culled);
  EXPECT_TRUE(c.resources[*g.find("debug.unused")].culled);
  EXPECT_FALSE(c.resources[*g.find("gbuffer.normal")].culled);
  EXPECT_NE(g.dump(c).find("culled:"), std::string::npos);
}

// The Graphviz form: every pass a box, every resource an ellipse, writer -> resource ->
// readers, culled passes grey; labels quoted so names with dots are one node.
TEST(Graph, DotListsPassesResourcesAndEdges) {
  RenderGraph g;
  compute(g, "producer", {}, {"a.b"});
  compute(g, "consumer", {"a.b"}, {"out"});
  compute(g, "unused", {"a.b"}, {"nobody \"reads\""});
  g.markOutput("out");
  const std::string d = g.dot(g.compile());
  EXPECT_EQ(d.rfind("digraph twinlight {", 0), 0u);
  EXPECT_EQ(d.back(), '\n');
  EXPECT_NE(d.find("\"pass:producer\" [shape=box"), std::string::npos) << d;
  EXPECT_NE(d.find("\"resource:a.b\" [shape=ellipse"), std::string::npos) << d;
  EXPECT_NE(d.find("\"pass:producer\" -> \"resource:a.b\""), std::string::npos) << d;
  EXPECT_NE(d.find("\"resource:a.b\" -> \"pass:consumer\""), std::string::npos) << d;
  EXPECT_NE(d.find("\"pass:unused\" [shape=box, style=dashed, color=grey"), std::string::npos) << "culled, grey";
  EXPECT_NE(d.find("resource:nobody \\\"reads\\\""), std::string::npos) << "quotes escaped: " << d;
  EXPECT_NE(d.find("label=\"[0] producer\\ncompute\""), std::string::npos) << "DOT's line break: " << d;
  // Every attribute list closed.
  EXPECT_EQ(std::count(d.begin(), d.end(), '['), std::count(d.begin(), d.end(), ']'));
}

TEST(Graph, SideEffectsPersistentAndImportedWritersSurvive) {
  RenderGraph g;
  g.declarePersistent("history", kImage);
  g.declareImported("swapchain", kImage);
  g.addPass("present", PassKind::Transfer, [](PassBuilder& b) { b.write("swapchain", Usage::TransferDst); }, nullptr);
  g.addPass("accumulate", PassKind::Compute, [](PassBuilder& b) { b.write("history", Usage::StorageWrite); }, nullptr);
  g.addPass("log", PassKind::Compute, [](PassBuilder& b) { b.sideEffect(); }, nullptr);
  auto c = g.compile();
  EXPECT_EQ(c.order.size(), 3u);
  EXPECT_TRUE(c.culled.empty());
}

// A progressive sum behind an optional output runs only in frames that read the output.
TEST(Graph, OnDemandHistoryWritersRunOnlyWhenTheirOutputIsRead) {
  auto frame = [](bool readIrradiance) {
    RenderGraph g;
    g.declareOnDemandHistory("irradiance.sum", kImage);
    g.addPass("irradiance", PassKind::Compute, [](PassBuilder& b) {
      b.read("irradiance.sum", Usage::StorageRead);
      b.write("irradiance.sum", Usage::StorageWrite);
      b.create("irradiance", kImage, Usage::StorageWrite);
    }, nullptr);
    compute(g, "final", {}, {"final"});
    g.markOutput("final");
    if (readIrradiance) g.markOutput("irradiance");
    auto c = g.compile();
    return orderNames(g, c);
  };
  EXPECT_EQ(frame(false), (std::vector<std::string>{"final"}));
  auto withIt = frame(true);
  EXPECT_NE(std::find(withIt.begin(), withIt.end(), "irradiance"), withIt.end());
}

TEST(Graph, LifetimesWriterAndReaders) {
  RenderGraph g;
  PassId a = compute(g, "a", {}, {"x"});
  compute(g, "b", {}, {"y"});
  PassId c1 = compute(g, "c", {"x", "y"}, {"z"});
  g.markOutput("z");
  auto c = g.compile();
  const auto& x = c.resources[*g.find("x")];
  EXPECT_EQ(x.writer, a);
  EXPECT_EQ(x.readers, std::vector<PassId>{c1});
  EXPECT_EQ(x.firstUse, 0u);
  EXPECT_EQ(x.lastUse, 2u);
  const auto& z = c.resources[*g.find("z")];
  EXPECT_EQ(z.firstUse, 2u);
  EXPECT_EQ(z.lastUse, 2u);
}

TEST(Graph, BarriersFollowHazards) {
  RenderGraph g;
  g.addPass("raster", PassKind::Raster, [](PassBuilder& b) { b.create("color", kImage, Usage::ColorAttachment); }, nullptr);
  compute(g, "read1", {"color"}, {"o1"});
  compute(g, "read2", {"color"}, {"o2"});  // same usage and layout as read1: no barrier
  g.markOutput("o1");
  g.markOutput("o2");
  auto c = g.compile();
  auto barrierFor = [&](size_t pass, const char* name) -> const Barrier* {
    for (auto& b : c.order[pass].barriers)
      if (b.resource == *g.find(name)) return &b;
    return nullptr;
  };
  const Barrier* first = barrierFor(0, "color");
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->oldLayout, VK_IMAGE_LAYOUT_UNDEFINED);  // transient's first use: contents undefined
  EXPECT_EQ(first->newLayout, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  const Barrier* raw = barrierFor(1, "color");
  ASSERT_NE(raw, nullptr);
  EXPECT_EQ(raw->src.stages, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT);
  EXPECT_EQ(raw->dst.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(raw->newLayout, VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL);
  EXPECT_EQ(barrierFor(2, "color"), nullptr);
}

TEST(Graph, WriteAfterReadGetsABarrier) {
  RenderGraph g;
  g.declarePersistent("history", kImage);
  compute(g, "reader", {"history"}, {"out"});
  g.addPass("writer", PassKind::Compute, [](PassBuilder& b) { b.write("history", Usage::StorageWrite); }, nullptr);
  g.markOutput("out");
  auto c = g.compile();
  ASSERT_EQ(orderNames(g, c), (std::vector<std::string>{"reader", "writer"}));
  bool found = false;
  for (auto& b : c.order[1].barriers)
    if (b.resource == *g.find("history"))
      found = b.src.stages == VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT && b.oldLayout == VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL &&
              b.newLayout == VK_IMAGE_LAYOUT_GENERAL;
  EXPECT_TRUE(found);
}

TEST(Graph, ACacheIsWrittenBeforeItsReadersInFramesThatRebuildIt) {
  for (bool rebuild : {true, false}) {
    RenderGraph g;
    g.declareCache("voxels", kImage);
    compute(g, "cones", {"voxels"}, {"gi"});  // declared first, still runs after a rebuild
    if (rebuild)
      g.addPass("voxelize", PassKind::Compute, [](PassBuilder& b) { b.write("voxels", Usage::StorageWrite); }, nullptr);
    g.markOutput("gi");
    auto c = g.compile();
    if (rebuild) {
      EXPECT_EQ(orderNames(g, c), (std::vector<std::string>{"voxelize", "cones"}));
    } else {
      EXPECT_EQ(orderNames(g, c), (std::vector<std::string>{"cones"})) << "no writer: last contents are read";
    }
  }
}

TEST(Graph, PersistentHistoryIsReadBeforeItsWriterEvenIfDeclaredAfter) {
  RenderGraph g;
  g.declarePersistent("taa.history", kImage);
  g.addPass("taa.resolve", PassKind::Compute, [](PassBuilder& b) {
    b.read("taa.history", Usage::StorageRead);
    b.write("taa.history", Usage::StorageWrite);
  }, nullptr);
  compute(g, "debug.view", {"taa.history"}, {"debug.out"});  // wants last frame's history
  g.markOutput("debug.out");
  auto c = g.compile();
  EXPECT_EQ(orderNames(g, c), (std::vector<std::string>{"debug.view", "taa.resolve"}));
}

TEST(Graph, ReadModifyWriteIsOneBarrierWithTheWriteUsage) {
  RenderGraph h;
  h.declarePersistent("acc", kImage);
  h.addPass("accumulate", PassKind::Compute, [](PassBuilder& b) {
    b.read("acc", Usage::StorageRead);
    b.write("acc", Usage::StorageWrite);
  }, nullptr);
  auto c = h.compile();
  ASSERT_EQ(c.order[0].barriers.size(), 1u);
  EXPECT_EQ(c.order[0].barriers[0].newLayout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(c.order[0].barriers[0].dst.access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

// Work split over passes (the legacy voxels: a clear, voxelization rounds, then their mips):
// the steps run as declared, each fenced from the last, and readers see the last step.
TEST(Graph, StepsOfOneWriteRunInOrderAndReadersSeeTheLast) {
  RenderGraph g;
  g.declareCache("voxels", kImage);
  compute(g, "cones", {"voxels"}, {"gi"});  // declared first, runs after every step
  g.addPass("clear", PassKind::Compute, [](PassBuilder& b) { b.write("voxels", Usage::StorageWrite); }, nullptr);
  g.addPass("voxelize", PassKind::Raster, [](PassBuilder& b) {
    b.read("shadow.map", Usage::Sampled);
    b.update("voxels", Usage::StorageWrite);
  }, nullptr);
  g.addPass("emitters", PassKind::Raster, [](PassBuilder& b) { b.update("voxels", Usage::StorageWrite); }, nullptr);
  compute(g, "shadow", {}, {"shadow.map"});  // declared last: the emitters still wait for voxelize
  g.markOutput("gi");
  auto c = g.compile();
  ASSERT_EQ(orderNames(g, c), (std::vector<std::string>{"clear", "shadow", "voxelize", "emitters", "cones"}));
  auto barrier = [&](size_t pass) -> const Barrier* {
    for (auto& b : c.order[pass].barriers)
      if (b.resource == *g.find("voxels")) return &b;
    return nullptr;
  };
  const Barrier* afterClear = barrier(2);
  ASSERT_NE(afterClear, nullptr);
  EXPECT_EQ(afterClear->src.stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_NE(afterClear->dst.stages & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, 0u);
  EXPECT_NE(afterClear->dst.access & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, 0u);
  const Barrier* betweenRounds = barrier(3);
  ASSERT_NE(betweenRounds, nullptr);
  EXPECT_NE(betweenRounds->src.stages & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, 0u);
  EXPECT_NE(betweenRounds->dst.stages & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, 0u);
  const ResourceInfo& info = c.resources[*g.find("voxels")];
  EXPECT_EQ(g.passes()[info.writer].name, "emitters");
  EXPECT_NE(g.dump(c).find("written by emitters (after clear, voxelize)"), std::string::npos) << g.dump(c);
}

TEST(Graph, StepsOfOneWriteAreKeptOrCulledTogether) {
  for (bool read : {true, false}) {
    RenderGraph g;
    compute(g, "make", {}, {"x"});
    g.addPass("refine", PassKind::Compute, [](PassBuilder& b) {
      b.read("x", Usage::StorageRead);
      b.update("x", Usage::StorageWrite);
    }, nullptr);
    if (read) {
      compute(g, "use", {"x"}, {"out"});
      g.markOutput("out");
    }
    auto c = g.compile();
    if (read)
      EXPECT_EQ(orderNames(g, c), (std::vector<std::string>{"make", "refine", "use"}));
    else
      EXPECT_EQ(c.culled.size(), 2u) << "nobody reads x: both steps go";
  }
}

TEST(GraphErrors, UpdateWithoutAnEarlierWriterNamesThePass) {
  RenderGraph g;
  g.declareCache("voxels", kImage);
  g.addPass("voxelize", PassKind::Raster, [](PassBuilder& b) { b.update("voxels", Usage::StorageWrite); }, nullptr);
  g.addPass("clear", PassKind::Compute, [](PassBuilder& b) { b.write("voxels", Usage::StorageWrite); }, nullptr);
  std::string e = errorOf(g);
  EXPECT_NE(e.find("pass `voxelize` updates `voxels`, which no pass declared before it writes"), std::string::npos) << e;
}

TEST(GraphErrors, ReadOfUnwrittenResourceNamesBoth) {
  // A transient is declared by the pass that creates (writes) it, so the reachable misuse
  // is a read of a name no pass writes.
  RenderGraph h;
  compute(h, "rt.denoise.1", {"rt.gi.temporal"}, {"rt.gi.denoised"});
  h.markOutput("rt.gi.denoised");
  std::string e = errorOf(h);
  EXPECT_NE(e.find("pass `rt.denoise.1` reads `rt.gi.temporal`"), std::string::npos) << e;
  EXPECT_NE(e.find("no pass writes"), std::string::npos) << e;
}

TEST(GraphErrors, TypoSuggestsTheClosestName) {
  RenderGraph g;
  compute(g, "gbuffer", {}, {"gbuffer.normal"});
  compute(g, "composite", {"gbufer.normal"}, {"out"});
  g.markOutput("out");
  std::string e = errorOf(g);
  EXPECT_NE(e.find("pass `composite` reads `gbufer.normal`"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean `gbuffer.normal`?"), std::string::npos) << e;
}

TEST(GraphErrors, TwoWritersNamesBothPasses) {
  RenderGraph g;
  g.declarePersistent("accum", kImage);
  g.addPass("first", PassKind::Compute, [](PassBuilder& b) { b.write("accum", Usage::StorageWrite); }, nullptr);
  g.addPass("second", PassKind::Compute, [](PassBuilder& b) { b.write("accum", Usage::StorageWrite); }, nullptr);
  std::string e = errorOf(g);
  EXPECT_NE(e.find("resource `accum` is written by both `first` and `second`"), std::string::npos) << e;
}

TEST(GraphErrors, DuplicateCreateNamesBothPasses) {
  RenderGraph g;
  compute(g, "a", {}, {"x"});
  compute(g, "b", {}, {"x"});
  std::string e = errorOf(g);
  EXPECT_NE(e.find("resource `x` is declared twice: by pass `a` and by pass `b`"), std::string::npos) << e;
}

TEST(GraphErrors, CycleNamesThePasses) {
  RenderGraph g;
  g.declareImported("seed", kImage);
  g.addPass("p", PassKind::Compute, [](PassBuilder& b) {
    b.read("y", Usage::Sampled);
    b.create("x", kImage, Usage::StorageWrite);
  }, nullptr);
  g.addPass("q", PassKind::Compute, [](PassBuilder& b) {
    b.read("x", Usage::Sampled);
    b.create("y", kImage, Usage::StorageWrite);
  }, nullptr);
  g.markOutput("x");
  std::string e = errorOf(g);
  EXPECT_NE(e.find("`p`"), std::string::npos) << e;
  EXPECT_NE(e.find("`q`"), std::string::npos) << e;
  EXPECT_NE(e.find("cycle"), std::string::npos) << e;
}

TEST(GraphErrors, UnknownOutput) {
  RenderGraph g;
  compute(g, "a", {}, {"x"});
  g.markOutput("y");
  EXPECT_NE(errorOf(g).find("frame output `y`"), std::string::npos);
}

TEST(GraphDump, ListsEveryResourceWithItsWriterFormatAndSize) {
  RenderGraph g;
  compute(g, "producer", {}, {"a.image"});
  compute(g, "consumer", {"a.image"}, {"b.image"});
  g.markOutput("b.image");
  std::string d = g.dump(g.compile());
  EXPECT_NE(d.find("a.image"), std::string::npos);
  EXPECT_NE(d.find("written by producer"), std::string::npos);
  EXPECT_NE(d.find("written by consumer"), std::string::npos);
  EXPECT_NE(d.find("RGBA16F 64x64"), std::string::npos);
  EXPECT_NE(d.find("test image"), std::string::npos);
}

TEST(GraphFormats, SizesAndNames) {
  EXPECT_EQ(formatName(VK_FORMAT_R16G16B16A16_SFLOAT), "RGBA16F");
  EXPECT_EQ(formatBytesPerTexel(VK_FORMAT_D32_SFLOAT), 4u);
  // 64^2 * 8 bytes, plus mips 32^2 .. 1^2.
  auto d = ResourceDesc::image2D(VK_FORMAT_R16G16B16A16_SFLOAT, 64, 64, "", 7);
  VkDeviceSize expected = 0;
  for (uint32_t s = 64; s >= 1; s /= 2) expected += VkDeviceSize(s) * s * 8;
  EXPECT_EQ(approximateBytes(d), expected);
  EXPECT_EQ(approximateBytes(ResourceDesc::image3D(VK_FORMAT_R8_UNORM, 4, 4, 4)), 64u);
}

}  // namespace
}  // namespace tl::graph
