// The viewport's selection mark (shaders/common/display_outline.glsl): the selected instance is
// outlined and keeps its own colour inside, so the colour an artist edits (the inspector's
// albedo override) is the colour the viewport shows. It used to be tinted orange all over.
#include "gpu_fixture.h"

#include "lighting/common/display_pass.h"

#include <cstring>
#include <map>

namespace tl::test {
namespace {

class DisplaySelectionTest : public GpuTest {
 protected:
  void TearDown() override {
    restoreBaseline(session());
    GpuTest::TearDown();
  }
};

TEST_F(DisplaySelectionTest, TheSelectedInstanceKeepsItsColourAndOnlyItsOutlineIsMarked) {
  auto& s = session();
  s.setSize(96, 96);
  s.setFrameIndex(0);
  s.resetHistory();
  s.setDisplay(lighting::DisplayRequest{});
  s.requestBuffer(lighting::kDisplayLdr);
  s.requestBuffer("gbuffer.instanceId");
  s.renderFrames(1);
  const std::vector<uint8_t> plain = s.buffer(lighting::kDisplayLdr).bytes;
  const graph::Readback ids = s.buffer("gbuffer.instanceId");
  const uint32_t w = ids.extent.width, h = ids.extent.height;
  const auto id = [&](int x, int y) {
    uint32_t v = 0;
    std::memcpy(&v, &ids.bytes[(size_t(y) * w + size_t(x)) * 4], 4);
    return v;
  };
  // The instance covering most of the image (ids are instance + 1, 0 the sky).
  std::map<uint32_t, size_t> area;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) ++area[id(int(x), int(y))];
  area.erase(0);
  ASSERT_FALSE(area.empty());
  const uint32_t selected = std::max_element(area.begin(), area.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;

  lighting::DisplayRequest outlined;
  outlined.selectedInstance = selected;
  s.setFrameIndex(0);
  s.resetHistory();
  s.setDisplay(outlined);
  s.requestBuffer(lighting::kDisplayLdr);
  s.renderFrames(1);
  const std::vector<uint8_t>& marked = s.buffer(lighting::kDisplayLdr).bytes;
  ASSERT_EQ(marked.size(), plain.size());
  size_t inside = 0, insideChanged = 0, edgeChanged = 0;
  for (int y = 0; y < int(h); ++y)
    for (int x = 0; x < int(w); ++x) {
      const bool in = id(x, y) == selected;
      bool edge = false;
      for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
        const int nx = std::clamp(x + dx, 0, int(w) - 1), ny = std::clamp(y + dy, 0, int(h) - 1);
        edge = edge || ((id(nx, ny) == selected) != in);
      }
      const size_t at = (size_t(y) * w + size_t(x)) * 4;
      bool changed = false;
      for (int c = 0; c < 3; ++c) changed = changed || marked[at + c] != plain[at + c];
      if (edge) edgeChanged += changed;
      else if (in) ++inside, insideChanged += changed;
    }
  EXPECT_GT(inside, 200u) << "the instance is large enough to tell";
  EXPECT_EQ(insideChanged, 0u) << "of " << inside << " pixels inside the selection, away from its outline";
  EXPECT_GT(edgeChanged, 20u) << "the outline is drawn";
}

}  // namespace
}  // namespace tl::test
