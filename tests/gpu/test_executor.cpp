// The executor on the device, without a scene: persistent history carries last frame's
// contents, transients that share aliased memory still read back their own values, and
// the timestamps name every pass.
#include "gpu_fixture.h"

#include "gpu/self_test.h"
#include "graph/executor.h"

namespace tl::test {
namespace {

using graph::PassKind;
using graph::Usage;

const auto kDesc = graph::ResourceDesc::image2D(VK_FORMAT_R32_SFLOAT, 8, 8, "test");

void clear(graph::PassContext& ctx, const char* name, float value) {
  VkClearColorValue c{};
  c.float32[0] = value;
  VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vkCmdClearColorImage(ctx.cmd, ctx.image(name).handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &c, 1, &range);
}

void copy(graph::PassContext& ctx, const char* from, const char* to) {
  VkImageCopy region{};
  region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.extent = {8, 8, 1};
  vkCmdCopyImage(ctx.cmd, ctx.image(from).handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, ctx.image(to).handle(),
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
}

}  // namespace

TEST_F(GpuTest, PersistentHistoryHoldsLastFramesContents) {
  graph::Executor ex(session().device());
  for (int frame = 1; frame <= 3; ++frame) {
    graph::RenderGraph g;
    g.declarePersistent("history", kDesc);
    // Declared after its reader: the graph must still run the reader first.
    g.addPass("write.history", PassKind::Transfer, [](graph::PassBuilder& b) { b.write("history", Usage::TransferDst); },
              [frame](graph::PassContext& ctx) { clear(ctx, "history", float(frame)); });
    g.addPass("read.history", PassKind::Transfer,
              [](graph::PassBuilder& b) {
                b.read("history", Usage::TransferSrc);
                b.create("seen", kDesc, Usage::TransferDst);
              },
              [](graph::PassContext& ctx) { copy(ctx, "history", "seen"); });
    g.markOutput("seen");
    auto compiled = g.compile(ex.entryStates(g));
    ex.requestReadback("seen");
    ex.execute(g, compiled);
    float seen = ex.readback("seen").texels()[0];
    if (frame > 1) {
      EXPECT_EQ(seen, float(frame - 1)) << "frame " << frame;
    }
  }
}

// History is valid only where a pass wrote it: after a reset, a frame that declares an
// on-demand history but culls its writer leaves it invalid; the frame that runs the writer
// makes it valid.
TEST_F(GpuTest, HistoryIsValidOnlyWhereAPassWroteIt) {
  graph::Executor ex(session().device());
  auto frame = [&](bool readSum) {
    graph::RenderGraph g;
    g.declareOnDemandHistory("sum", kDesc);
    g.addPass("accumulate", PassKind::Transfer,
              [](graph::PassBuilder& b) {
                b.write("sum", Usage::TransferDst);
                b.create("result", kDesc, Usage::TransferDst);
              },
              [](graph::PassContext& ctx) {
                clear(ctx, "sum", 1.0f);
                clear(ctx, "result", 1.0f);
              });
    g.addPass("final", PassKind::Transfer, [](graph::PassBuilder& b) { b.create("final", kDesc, Usage::TransferDst); },
              [](graph::PassContext& ctx) { clear(ctx, "final", 0.0f); });
    g.markOutput("final");
    if (readSum) g.markOutput("result");
    auto compiled = g.compile(ex.entryStates(g));
    ex.execute(g, compiled);
  };
  frame(true);
  EXPECT_TRUE(ex.historyValid("sum"));
  ex.resetHistory();
  frame(false);  // the writer is culled: nothing new in "sum"
  EXPECT_FALSE(ex.historyValid("sum")) << "a frame that did not write it must not make it valid";
  frame(true);
  EXPECT_TRUE(ex.historyValid("sum"));
}

TEST_F(GpuTest, AliasedTransientsReadBackTheirOwnValues) {
  graph::Executor ex(session().device());
  graph::RenderGraph g;
  // a -> a.out, then b -> b.out: a and b have disjoint lifetimes and may share memory.
  g.addPass("make.a", PassKind::Transfer, [](graph::PassBuilder& b) { b.create("a", kDesc, Usage::TransferDst); },
            [](graph::PassContext& ctx) { clear(ctx, "a", 11.0f); });
  g.addPass("use.a", PassKind::Transfer,
            [](graph::PassBuilder& b) {
              b.read("a", Usage::TransferSrc);
              b.create("a.out", kDesc, Usage::TransferDst);
            },
            [](graph::PassContext& ctx) { copy(ctx, "a", "a.out"); });
  g.addPass("make.b", PassKind::Transfer,
            [](graph::PassBuilder& b) {
              b.read("a.out", Usage::TransferSrc);  // orders b after a's last use
              b.create("b", kDesc, Usage::TransferDst);
            },
            [](graph::PassContext& ctx) { clear(ctx, "b", 22.0f); });
  g.addPass("use.b", PassKind::Transfer,
            [](graph::PassBuilder& b) {
              b.read("b", Usage::TransferSrc);
              b.create("b.out", kDesc, Usage::TransferDst);
            },
            [](graph::PassContext& ctx) { copy(ctx, "b", "b.out"); });
  g.markOutput("b.out");
  auto compiled = g.compile(ex.entryStates(g));
  ex.requestReadbackAll();
  ex.execute(g, compiled);

  bool shared = false;
  const auto& res = ex.resources();
  auto info = [&](const std::string& n) {
    return *std::find_if(res.begin(), res.end(), [&](auto& r) { return r.name == n; });
  };
  shared = info("a").aliased && info("b").aliased && info("a").offset == info("b").offset;
  EXPECT_TRUE(shared) << "a and b have disjoint lifetimes and should share memory";
  EXPECT_EQ(ex.readback("a").texels()[0], 11.0f);
  EXPECT_EQ(ex.readback("b").texels()[0], 22.0f);
  EXPECT_EQ(ex.readback("a.out").texels()[0], 11.0f);
  EXPECT_EQ(ex.readback("b.out").texels()[63], 22.0f);

  ASSERT_EQ(ex.timings().size(), 4u);
  EXPECT_EQ(ex.timings()[0].pass, "make.a");
  for (auto& t : ex.timings()) EXPECT_GE(t.gpuMs, 0.0);
}

}  // namespace tl::test

namespace tl::test {

TEST_F(GpuTest, RayTracingPipelineTracesTheSelfTestTriangle) {
  auto& d = session().device();
  if (!d.rayTracing().pipeline) GTEST_SKIP() << d.rayTracing().unavailableReason;
  auto failure = gpu::rayTracingSelfTest(d);
  EXPECT_FALSE(failure.has_value()) << *failure;
}

}  // namespace tl::test

namespace tl::test {

// Two frames in flight: the executor refuses a third, each frame's read-back is its own
// (frame 2 reuses frame 1's transient image while frame 1 may still be running), and a
// steady frame allocates nothing: each slot's staging serves its later frames.
TEST_F(GpuTest, TwoFramesInFlightKeepTheirOwnReadBacksAndAllocateNothingOnceWarm) {
  graph::Executor ex(session().device());
  auto submitFrame = [&](float value) {
    graph::RenderGraph g;
    g.addPass("make.value", PassKind::Transfer, [](graph::PassBuilder& b) { b.create("value", kDesc, Usage::TransferDst); },
              [value](graph::PassContext& ctx) { clear(ctx, "value", value); });
    g.markOutput("value");
    auto compiled = g.compile(ex.entryStates(g));
    ex.requestReadback("value");
    ex.submit(g, compiled);
  };
  submitFrame(1.0f);
  submitFrame(2.0f);
  EXPECT_EQ(ex.framesInFlight(), 2u);
  EXPECT_THROW(submitFrame(3.0f), gpu::Error) << "a third frame in flight would reuse the first one's slot";
  EXPECT_EQ(ex.framesInFlight(), 2u);
  ex.finish();
  EXPECT_EQ(ex.readback("value").texels()[0], 1.0f);
  ex.finish();
  EXPECT_EQ(ex.readback("value").texels()[63], 2.0f);

  const uint64_t allocationsBefore = session().device().allocationsMade();
  for (int frame = 3; frame <= 8; ++frame) {
    submitFrame(float(frame));
    if (ex.framesInFlight() == 2) {
      ex.finish();
      EXPECT_EQ(ex.readback("value").texels()[0], float(frame - 1)) << "frame " << frame - 1;
    }
  }
  ex.finishAll();
  EXPECT_EQ(ex.readback("value").texels()[0], 8.0f);
  EXPECT_EQ(session().device().allocationsMade(), allocationsBefore) << "a steady frame allocated memory";
}

}  // namespace tl::test
