// The compute pass builder (lighting/common/pass_builders.h) on the device: one list of
// bindings drives the graph, the layout and the writes; an optional input that is absent
// needs no stand-in; a list that disagrees with itself or with its shader is one error
// naming both sides.
#include "gpu_fixture.h"

#include "graph/executor.h"
#include "lighting/common/pass_builders.h"
#include "shared/pass_builder_test.h"

namespace tl::test {
namespace {

using graph::PassKind;
using graph::Usage;
using lighting::ComputePass;

const auto kDesc = graph::ResourceDesc::image2D(VK_FORMAT_R32_SFLOAT, 8, 8, "test");
constexpr const char* kShader = "selftest/optional_input.comp";

// Runs the optional-input pass with or without a source cleared to `sourceValue`; returns
// the first texel of its result.
float runOptional(gpu::Device& device, bool withSource, float sourceValue) {
  graph::Executor ex(device);
  graph::RenderGraph g;
  if (withSource)
    g.addPass("source", PassKind::Transfer, [](graph::PassBuilder& b) { b.create("source", kDesc, Usage::TransferDst); },
              [sourceValue](graph::PassContext& ctx) {
                VkClearColorValue c{};
                c.float32[0] = sourceValue;
                VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
                vkCmdClearColorImage(ctx.cmd, ctx.image("source").handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &c, 1,
                                     &range);
              });
  ComputePass pass(device, "optional.input", kShader);
  pass.optionalSampled(shared::kOptionalInputSource, "source", g);
  shared::OptionalInputPush push{pass.present(shared::kOptionalInputSource) ? 1u : 0u, -7.0f};
  pass.storageOut(shared::kOptionalInputResult, "result", kDesc).push(push).dispatch(8, 8).add(g);
  g.markOutput("result");
  auto compiled = g.compile(ex.entryStates(g));
  ex.requestReadback("result");
  ex.execute(g, compiled);
  return ex.readback("result").texels()[0];
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const lighting::PassBuilderError& e) {
    return e.what();
  }
  return "(no error)";
}

}  // namespace

TEST_F(GpuTest, PassBuilderOptionalInputAbsentNeedsNoStandIn) {
  EXPECT_EQ(runOptional(session().device(), false, 0.0f), -7.0f);
  EXPECT_EQ(runOptional(session().device(), true, 3.5f), 3.5f);
}

TEST_F(GpuTest, PassBuilderBindingDeclaredTwiceNamesBoth) {
  graph::RenderGraph g;
  const std::string e = errorOf([&] {
    ComputePass(session().device(), "twice", kShader)
        .sampled(shared::kOptionalInputSource, "first")
        .storageOut(shared::kOptionalInputSource, "second", kDesc)
        .add(g);
  });
  EXPECT_NE(e.find("`twice`"), std::string::npos) << e;
  EXPECT_NE(e.find("`first`"), std::string::npos) << e;
  EXPECT_NE(e.find("`second`"), std::string::npos) << e;
  EXPECT_TRUE(g.passes().empty());
}

TEST_F(GpuTest, PassBuilderMissingBindingNamesShaderVariable) {
  graph::RenderGraph g;
  const std::string e = errorOf([&] {
    ComputePass(session().device(), "missing", kShader).storageOut(shared::kOptionalInputResult, "result", kDesc).add(g);
  });
  EXPECT_NE(e.find("`missing`"), std::string::npos) << e;
  EXPECT_NE(e.find("`source`"), std::string::npos) << e;  // the shader's name for the binding
  EXPECT_NE(e.find(kShader), std::string::npos) << e;
  EXPECT_TRUE(g.passes().empty());
}

TEST_F(GpuTest, PassBuilderBindingOfAnotherTypeNamesBoth) {
  graph::RenderGraph g;
  const std::string e = errorOf([&] {
    ComputePass(session().device(), "retyped", kShader)
        .storageIn(shared::kOptionalInputSource, "input")
        .storageOut(shared::kOptionalInputResult, "result", kDesc)
        .add(g);
  });
  EXPECT_NE(e.find("`input` as a storage image"), std::string::npos) << e;
  EXPECT_NE(e.find("`source` as a sampled image"), std::string::npos) << e;
}

// An absent optional storage image and a constant made outside the graph are bound (or not)
// without any graph access; a present optional storage image is one write.
TEST_F(GpuTest, PassBuilderOptionalStorageAndConstantsDeclareNoAccess) {
  gpu::Device& d = session().device();
  const gpu::Image constant(d, {VK_FORMAT_R32_SFLOAT, {8, 8, 1}, 1, VK_IMAGE_USAGE_SAMPLED_BIT}, "test.constant");
  for (const bool present : {false, true}) {
    graph::RenderGraph g;
    ComputePass pass(d, "optional.storage", kShader);
    pass.constantSampled(shared::kOptionalInputSource, constant, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL)
        .optionalStorageInOut(shared::kOptionalInputResult, "accum", present)
        .push(shared::OptionalInputPush{1u, 0.0f})
        .add(g);
    ASSERT_EQ(g.passes().size(), 1u);
    const graph::PassDecl& p = g.passes()[0];
    EXPECT_TRUE(p.readNames.empty()) << p.readNames.front();
    EXPECT_EQ(p.writeNames, present ? std::vector<std::string>{"accum"} : std::vector<std::string>{});
    for (const gpu::Binding& b : pass.layout()) EXPECT_EQ(b.optional, b.binding == shared::kOptionalInputResult);
  }
}

TEST_F(GpuTest, PassBuilderSharesSamplersAcrossPasses) {
  gpu::Device& d = session().device();
  EXPECT_EQ(d.sampler(lighting::samplers::point), d.sampler(lighting::samplers::point));
  EXPECT_NE(d.sampler(lighting::samplers::point), d.sampler(lighting::samplers::linear));
}

}  // namespace tl::test
