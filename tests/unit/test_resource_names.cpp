// Frame resources are bound by typed names (graph/resource_name.h): the kind is checked when
// the pass is compiled, the name is what the graph and the inspector see.
#include "graph/resource_name.h"
#include "lighting/common/composite_pass.h"
#include "lighting/common/frame_inputs.h"
#include "lighting/common/gbuffer_pass.h"
#include "lighting/common/pass_builders.h"

#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <type_traits>

namespace tl {
namespace {

using graph::BufferName;
using graph::ImageName;
using lighting::ComputePass;

// An image call takes an image's name, a buffer call a buffer's: the other kind, or a bare
// string, is refused by the compiler.
template <class Name>
concept SampledTakes = requires(ComputePass& p, Name n) { p.sampled(0u, n); };
template <class Name>
concept BufferInTakes = requires(ComputePass& p, Name n) { p.bufferIn(0u, n); };
template <class Name>
concept UniformTakes = requires(ComputePass& p, Name n) { p.uniform(0u, n); };

static_assert(SampledTakes<ImageName>);
static_assert(!SampledTakes<BufferName>);
static_assert(!SampledTakes<const char*>);
static_assert(!SampledTakes<std::string>);
static_assert(BufferInTakes<BufferName>);
static_assert(!BufferInTakes<ImageName>);
static_assert(UniformTakes<BufferName>);
static_assert(!UniformTakes<ImageName>);
static_assert(!std::is_convertible_v<BufferName, ImageName>);
static_assert(!std::is_convertible_v<ImageName, BufferName>);
static_assert(!std::is_convertible_v<const char*, ImageName>);
// The frame's own resources carry their kind.
static_assert(std::is_same_v<decltype(lighting::kCompositeHdr), const ImageName>);
static_assert(std::is_same_v<decltype(lighting::kFrameConstants), const BufferName>);
static_assert(std::is_same_v<decltype(lighting::gbuffer::kDepth), const ImageName>);

TEST(ResourceNames, ConvertToTheNameTheGraphAndTheInspectorUse) {
  constexpr ImageName hdr{"composite.hdr"};
  const std::string_view view = hdr;
  const std::string text = hdr;
  EXPECT_EQ(view, "composite.hdr");
  EXPECT_EQ(text, "composite.hdr");
  EXPECT_TRUE(hdr == std::string("composite.hdr"));
  EXPECT_FALSE(hdr == std::string_view("composite.ldr"));
  std::ostringstream out;
  out << hdr;
  EXPECT_EQ(out.str(), "composite.hdr");
}

// The G-buffer's channels are its named resources, each once, in attachment order.
TEST(ResourceNames, GbufferChannelsAreTheGbufferResources) {
  const ImageName expected[] = {lighting::gbuffer::kBaseColor, lighting::gbuffer::kNormal,   lighting::gbuffer::kMaterial,
                                lighting::gbuffer::kEmissive,  lighting::gbuffer::kMotion, lighting::gbuffer::kInstanceId};
  ASSERT_EQ(std::size(lighting::kGbufferChannels), std::size(expected));
  std::set<std::string_view> names;
  for (size_t i = 0; i < std::size(expected); ++i) {
    EXPECT_EQ(lighting::kGbufferChannels[i].name, expected[i]) << i;
    EXPECT_EQ(lighting::kGbufferChannels[i].location, i) << lighting::kGbufferChannels[i].name;
    EXPECT_TRUE(lighting::kGbufferChannels[i].name.name().starts_with("gbuffer.")) << lighting::kGbufferChannels[i].name;
    names.insert(lighting::kGbufferChannels[i].name);
  }
  names.insert(lighting::gbuffer::kDepth);
  EXPECT_EQ(names.size(), std::size(expected) + 1);
}

}  // namespace
}  // namespace tl
