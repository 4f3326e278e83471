// The pass builders (lighting/common/pass_builders.h) on the device: one list of bindings
// drives the graph, the layout and the writes; an optional input that is absent needs no
// stand-in; a list that disagrees with itself or with its shader (for a ray-tracing pass, any
// of its stages) is one error naming both sides.
#include "gpu_fixture.h"

#include "shared/gbuffer.h"

#include "gpu/acceleration_structure.h"
#include "graph/executor.h"
#include "lighting/common/pass_builders.h"
#include "shared/frame.h"
#include "shared/lights.h"
#include "shared/pass_builder_test.h"
#include "shared/reference.h"
#include "shared/selftest.h"

#include <algorithm>

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
  pass.optionalSampled(shared::kOptionalInputSource, graph::ImageName{"source"}, g);
  shared::OptionalInputPush push{pass.present(shared::kOptionalInputSource) ? 1u : 0u, -7.0f};
  pass.storageOut(shared::kOptionalInputResult, graph::ImageName{"result"}, kDesc).push(push).dispatch(8, 8).add(g);
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
        .sampled(shared::kOptionalInputSource, graph::ImageName{"first"})
        .storageOut(shared::kOptionalInputSource, graph::ImageName{"second"}, kDesc)
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
    ComputePass(session().device(), "missing", kShader).storageOut(shared::kOptionalInputResult, graph::ImageName{"result"}, kDesc).add(g);
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
        .storageIn(shared::kOptionalInputSource, graph::ImageName{"input"})
        .storageOut(shared::kOptionalInputResult, graph::ImageName{"result"}, kDesc)
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
        .optionalStorageInOut(shared::kOptionalInputResult, graph::ImageName{"accum"}, present)
        .push(shared::OptionalInputPush{1u, 0.0f})
        .add(g);
    ASSERT_EQ(g.passes().size(), 1u);
    const graph::PassDecl& p = g.passes()[0];
    EXPECT_TRUE(p.readNames.empty()) << p.readNames.front();
    EXPECT_EQ(p.writeNames, present ? std::vector<std::string>{"accum"} : std::vector<std::string>{});
    for (const gpu::Binding& b : pass.layout()) EXPECT_EQ(b.optional, b.binding == shared::kOptionalInputResult);
  }
}

// Work split over passes (the legacy voxels' clear and rounds, their mips a level per pass):
// storageUpdate declares the next step of an earlier pass's write, which the graph orders
// after it with a barrier between; a mip entry binds that level's view. An update with no
// earlier writer is the graph's error, naming the pass.
TEST_F(GpuTest, PassBuilderStepsOfOneWriteAreGraphUpdates) {
  gpu::Device& d = session().device();
  const gpu::Image constant(d, {VK_FORMAT_R32_SFLOAT, {8, 8, 1}, 1, VK_IMAGE_USAGE_SAMPLED_BIT}, "test.constant");
  auto step = [&](graph::RenderGraph& g, const char* name, uint32_t mip, bool update) {
    ComputePass pass(d, name, kShader);
    pass.constantSampled(shared::kOptionalInputSource, constant, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    if (update)
      pass.storageUpdate(shared::kOptionalInputResult, graph::ImageName{"chain"}, mip);
    else
      pass.storageOut(shared::kOptionalInputResult, graph::ImageName{"chain"}, mip);
    pass.pipelineName("optional.chain").push(shared::OptionalInputPush{1u, 0.0f}).add(g);
  };
  const auto chainDesc = graph::ResourceDesc::image2D(VK_FORMAT_R32_SFLOAT, 8, 8, "test chain", 2);
  graph::RenderGraph g;
  g.declareCache("chain", chainDesc);
  step(g, "level0", 0, false);
  step(g, "level1", 1, true);
  const graph::CompiledGraph c = g.compile();
  ASSERT_EQ(c.order.size(), 2u);
  EXPECT_EQ(g.passes()[c.order[1].pass].name, "level1");
  EXPECT_EQ(g.passes()[1].writeUpdates, std::vector<bool>{true});
  ASSERT_EQ(c.order[1].barriers.size(), 1u);
  EXPECT_EQ(c.order[1].barriers[0].src.access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  graph::RenderGraph alone;
  alone.declareCache("chain", chainDesc);
  step(alone, "level1", 1, true);
  std::string e;
  try {
    alone.compile();
  } catch (const graph::GraphError& x) {
    e = x.what();
  }
  EXPECT_NE(e.find("pass `level1` updates `chain`, which no pass declared before it writes"), std::string::npos) << e;
}

TEST_F(GpuTest, PassBuilderSharesSamplersAcrossPasses) {
  gpu::Device& d = session().device();
  EXPECT_EQ(d.sampler(lighting::samplers::point), d.sampler(lighting::samplers::point));
  EXPECT_NE(d.sampler(lighting::samplers::point), d.sampler(lighting::samplers::linear));
}

// ---- RayTracingPass ---------------------------------------------------------------------

const lighting::RayShaders kSelfTestShaders{"builder.selftest", "selftest/trace.rgen", {"selftest/trace.rmiss"},
                                            {{"selftest/trace.rchit", ""}}};
const auto kSelfTestDesc = graph::ResourceDesc::image2D(VK_FORMAT_R32_SFLOAT, shared::kSelfTestSize, shared::kSelfTestSize,
                                                        "hit distance");

// The ray-tracing self-test's scene (gpu/self_test.cpp: one triangle) traced through the
// builder: the pass's list alone gives the layout, the graph's access and the descriptors.
class RayTracingPassTest : public RayTracingTest {
 protected:
  void SetUp() override {
    RayTracingTest::SetUp();
    if (IsSkipped()) return;
    gpu::Device& d = session().device();
    const float vertices[9] = {-1.0f, -1.0f, 0.0f, 1.01f, -1.0f, 0.0f, -1.0f, 1.01f, 0.0f};
    const uint32_t indices[3] = {0, 1, 2};
    const VkBufferUsageFlags input = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR;
    vb_ = gpu::Buffer(d, sizeof vertices, input, gpu::MemoryUsage::Upload, "test.vertices");
    ib_ = gpu::Buffer(d, sizeof indices, input, gpu::MemoryUsage::Upload, "test.indices");
    vb_.write(vertices, sizeof vertices);
    ib_.write(indices, sizeof indices);
    blas_ = gpu::buildBottomLevel(d, {vb_.address(), 12, 3, ib_.address(), 1, true}, "test.blas");
    tlas_ = gpu::buildTopLevel(d, {{glm::mat4(1.0f), 0, 0xFF, blas_.address()}}, "test.tlas");
  }
  gpu::Buffer vb_, ib_;
  gpu::AccelerationStructure blas_, tlas_;
};

TEST_F(RayTracingPassTest, TracesFromItsBindingList) {
  gpu::Device& d = session().device();
  graph::Executor ex(d);
  graph::RenderGraph g;
  lighting::RayTracingPass(d, "builder.trace", kSelfTestShaders)
      .accelerationStructure(shared::kSelfTestBindingScene, tlas_.handle(), {})
      .storageOut(shared::kSelfTestBindingOutput, graph::ImageName{"result"}, kSelfTestDesc)
      .trace(shared::kSelfTestSize, shared::kSelfTestSize)
      .add(g);
  ASSERT_EQ(g.passes().size(), 1u);
  EXPECT_EQ(g.passes()[0].kind, PassKind::RayTracing);
  EXPECT_EQ(g.passes()[0].writeNames, std::vector<std::string>{"result"});
  g.markOutput("result");
  auto compiled = g.compile(ex.entryStates(g));
  ex.requestReadback("result");
  ex.execute(g, compiled);
  const std::vector<float> got = ex.readback("result").texels();
  ASSERT_EQ(got.size(), size_t(shared::kSelfTestSize * shared::kSelfTestSize));
  size_t hits = 0;
  for (uint32_t y = 0; y < shared::kSelfTestSize; ++y)
    for (uint32_t x = 0; x < shared::kSelfTestSize; ++x) {
      const shared::vec2 xy = shared::tlSelfTestRayXY(x, y);
      const float want = xy.x + xy.y < 0.01f ? 1.0f : shared::kSelfTestMiss;
      EXPECT_NEAR(got[y * shared::kSelfTestSize + x], want, 1e-4f) << x << "," << y;
      hits += want > 0.0f;
    }
  EXPECT_GT(hits, 0u);  // the scene is hit somewhere, missed elsewhere
  EXPECT_LT(hits, got.size());
}

// The same shaders and list in two passes are one pipeline of the device's cache.
TEST_F(RayTracingPassTest, PassesOfTheSameShadersShareOnePipeline) {
  gpu::Device& d = session().device();
  graph::RenderGraph g;
  auto add = [&](const char* name, graph::ImageName output) {
    lighting::RayTracingPass(d, name, kSelfTestShaders)
        .accelerationStructure(shared::kSelfTestBindingScene, tlas_.handle(), {})
        .storageOut(shared::kSelfTestBindingOutput, output, kSelfTestDesc)
        .trace(shared::kSelfTestSize, shared::kSelfTestSize)
        .add(g);
  };
  add("builder.first", graph::ImageName{"first"});
  const size_t pipelines = d.pipelines().size();
  add("builder.second", graph::ImageName{"second"});
  EXPECT_EQ(d.pipelines().size(), pipelines);
  EXPECT_EQ(g.passes().size(), 2u);
}

// Misuse: the raygen shader's output is missing from the list. One error, before any pipeline
// is made, names the pass, the shader that declares the binding and its variable there.
TEST_F(RayTracingPassTest, MissingBindingNamesTheStage) {
  gpu::Device& d = session().device();
  graph::RenderGraph g;
  const size_t pipelines = d.pipelines().size();
  const std::string e = errorOf([&] {
    lighting::RayTracingPass(d, "builder.missing", {"builder.missing", "selftest/trace.rgen", {"selftest/trace.rmiss"},
                                                    {{"selftest/trace.rchit", ""}}})
        .accelerationStructure(shared::kSelfTestBindingScene, tlas_.handle(), {})
        .trace(shared::kSelfTestSize, shared::kSelfTestSize)
        .add(g);
  });
  EXPECT_NE(e.find("`builder.missing`"), std::string::npos) << e;
  EXPECT_NE(e.find("selftest/trace.rgen"), std::string::npos) << e;
  EXPECT_NE(e.find("`result`"), std::string::npos) << e;  // the shader's name for the binding
  EXPECT_TRUE(g.passes().empty());
  EXPECT_EQ(d.pipelines().size(), pipelines);
}

// A binding only a hit shader declares is part of what the pipeline's list is checked against:
// the union of its stages, each binding once, each named after the first stage declaring it.
TEST_F(GpuTest, ReflectStagesIsTheUnionOfTheStages) {
  // The RT path's trace: its closest-hit shader reads the scene's geometry, its ray generation
  // only the pre-trace's records and the hits it writes.
  const std::vector<std::string> stages = {"rt/trace.rgen", "rt/trace.rmiss", "rt/trace.rchit", "rt/alpha.rahit"};
  auto has = [](const std::vector<gpu::ReflectedBinding>& v, uint32_t binding) {
    return std::any_of(v.begin(), v.end(), [&](const gpu::ReflectedBinding& r) { return r.binding == binding; });
  };
  const std::vector<gpu::ReflectedBinding> rayGen = gpu::reflectSet0(gpu::loadSpirv(stages[0]));
  const std::vector<gpu::ReflectedBinding> hit = gpu::reflectSet0(gpu::loadSpirv(stages[2]));
  std::vector<uint32_t> hitOnly;
  for (const gpu::ReflectedBinding& b : hit)
    if (!has(rayGen, b.binding)) hitOnly.push_back(b.binding);
  ASSERT_FALSE(hitOnly.empty()) << "the closest-hit shader declares no binding of its own: the test needs one";
  std::vector<std::string> from;
  const std::vector<gpu::ReflectedBinding> all = lighting::reflectStages(stages, &from);
  ASSERT_EQ(all.size(), from.size());
  for (size_t i = 0; i < all.size(); ++i) {
    for (size_t j = i + 1; j < all.size(); ++j) EXPECT_NE(all[i].binding, all[j].binding);
    if (std::find(hitOnly.begin(), hitOnly.end(), all[i].binding) != hitOnly.end()) {
      EXPECT_EQ(from[i], "rt/trace.rchit");
    }
    if (has(rayGen, all[i].binding)) {
      EXPECT_EQ(from[i], "rt/trace.rgen");
    }
  }
  for (uint32_t b : hitOnly) EXPECT_TRUE(has(all, b));
  for (const gpu::ReflectedBinding& b : rayGen) EXPECT_TRUE(has(all, b.binding));
}

// ---- RasterPass -------------------------------------------------------------------------

// The G-buffer's shaders: the frame's block is declared by both stages; the vertex stage also
// reads deforming meshes' previous positions (an optional binding), nothing else in set 0.
gpu::GraphicsPipelineDesc gbufferShaders(const char* name) {
  gpu::GraphicsPipelineDesc d;
  d.name = name;
  d.vertexShader = "common/gbuffer.vert";
  d.fragmentShader = "common/gbuffer.frag";
  return d;
}

const auto kDepthDesc = graph::ResourceDesc::image2D(VK_FORMAT_D32_SFLOAT, 8, 8, "test depth");

// A raster pass's list is checked against the union of its vertex and fragment bindings.
TEST_F(GpuTest, RasterPassListMatchesBothStages) {
  lighting::RasterPass pass(session().device(), "raster.ok", gbufferShaders("raster.ok"));
  pass.uniform(shared::kBindingFrame, lighting::kFrameConstants);
  pass.optionalBufferIn(shared::kGbufferPreviousPositions, graph::BufferName{"previous"}, false);
  EXPECT_NO_THROW(pass.check(lighting::reflectStages({"common/gbuffer.vert", "common/gbuffer.frag"})));
}

// Misuse: the frame's block missing from the list. One error, before any pipeline is made,
// names the pass and the first stage that declares the binding; no pass is added.
TEST_F(GpuTest, RasterPassMissingBindingFailsBeforeThePipeline) {
  gpu::Device& d = session().device();
  graph::RenderGraph g;
  const size_t pipelines = d.pipelines().size();
  const std::string e = errorOf([&] {
    lighting::RasterPass(d, "raster.missing", gbufferShaders("raster.missing")).depthOut(graph::ImageName{"depth"}, kDepthDesc, 0.0f).add(g);
  });
  EXPECT_NE(e.find("`raster.missing`"), std::string::npos) << e;
  EXPECT_NE(e.find("common/gbuffer.vert"), std::string::npos) << e;
  EXPECT_NE(e.find("which the pass does not declare"), std::string::npos) << e;
  EXPECT_TRUE(g.passes().empty());
  EXPECT_EQ(d.pipelines().size(), pipelines);
}

// Misuse: a binding neither stage declares (the lights' shadow views, which the G-buffer
// does not read) names both stages.
TEST_F(GpuTest, RasterPassExtraBindingNamesBothStages) {
  graph::RenderGraph g;
  const std::string e = errorOf([&] {
    lighting::RasterPass(session().device(), "raster.extra", gbufferShaders("raster.extra"))
        .uniform(shared::kBindingFrame, lighting::kFrameConstants)
        .optionalBufferIn(shared::kGbufferPreviousPositions, graph::BufferName{"previous"}, false)
        .bufferIn(shared::kBindingLightShadowViews, graph::BufferName{"views"})
        .depthOut(graph::ImageName{"depth"}, kDepthDesc, 0.0f)
        .add(g);
  });
  EXPECT_NE(e.find("`views`"), std::string::npos) << e;
  EXPECT_NE(e.find("common/gbuffer.vert, common/gbuffer.frag"), std::string::npos) << e;
  EXPECT_TRUE(g.passes().empty());
}

}  // namespace tl::test
