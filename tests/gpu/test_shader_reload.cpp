// Hot shader reload: a syntax error is reported with its file and line while the last good
// pipeline keeps rendering; a fix takes effect at the next frame.
#include "gpu/shader_reload.h"
#include "gpu_fixture.h"

#include <fstream>
#include <regex>
#include <sstream>
#include <thread>

namespace tl::test {
namespace {

namespace fs = std::filesystem;

std::string readText(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Rewrites a file so that its modification time moves on even on coarse clocks.
void rewrite(const fs::path& p, const std::string& text) {
  const auto before = fs::last_write_time(p);
  std::ofstream(p, std::ios::trunc) << text;
  if (fs::last_write_time(p) == before) fs::last_write_time(p, before + std::chrono::seconds(1));
}

TEST_F(GpuTest, ABrokenShaderReportsFileAndLineAndKeepsRendering) {
  const fs::path root = fs::temp_directory_path() / "twinlight-reload-test";
  fs::remove_all(root);
  fs::create_directories(root);
  fs::copy(fs::path(TWINLIGHT_SOURCE_ROOT) / "shaders", root / "shaders", fs::copy_options::recursive);
  const fs::path tonemap = root / "shaders" / "common" / "tonemap.comp";
  const std::string original = readText(tonemap);

  auto& s = session();
  s.loadScene(contentFile("cornell.gltf"));
  s.setSize(32, 32);
  auto frame = [&] {
    s.requestBuffer("tonemap.ldr");
    s.renderFrames(1);
    return s.buffer("tonemap.ldr").bytes;
  };
  const auto good = frame();
  {
    gpu::ShaderReloader reloader(root / "shaders", root / "spv");
    EXPECT_TRUE(reloader.poll().recompiled.empty()) << "the first poll only records";

    // Line 14 gets a syntax error.
    std::string broken = std::regex_replace(original, std::regex("void main\\(\\) \\{"), "void main() {\n  this is not glsl;");
    rewrite(tonemap, broken);
    gpu::ShaderReloadResult r = reloader.poll();
    ASSERT_EQ(r.errors.size(), 1u);
    EXPECT_NE(r.errors[0].find("tonemap.comp:14:"), std::string::npos) << r.errors[0];
    EXPECT_EQ(reloader.errors().size(), 1u) << "the error stands until fixed";
    EXPECT_EQ(frame(), good) << "the last good pipeline keeps running";

    // A fix that shows: the tonemapper writes its input inverted.
    std::string inverted = std::regex_replace(original, std::regex("vec4\\(tlLinearToSrgb\\(display\\), 1.0\\)"),
                                              "vec4(1.0 - tlLinearToSrgb(display), 1.0)");
    ASSERT_NE(inverted, original);
    rewrite(tonemap, inverted);
    r = reloader.poll();
    EXPECT_TRUE(r.errors.empty());
    ASSERT_EQ(r.recompiled.size(), 1u);
    EXPECT_EQ(r.recompiled[0], "common/tonemap.comp");
    EXPECT_TRUE(reloader.errors().empty());
    const auto reloaded = frame();
    ASSERT_EQ(reloaded.size(), good.size());
    size_t inverse = 0;
    for (size_t i = 0; i < good.size(); i += 4) inverse += std::abs(int(reloaded[i]) - (255 - int(good[i]))) <= 1;
    EXPECT_GT(inverse, good.size() / 4 * 99 / 100) << "the next frame uses the edited shader";
  }
  EXPECT_EQ(frame(), good) << "without the reloader, the build's shaders again";
  fs::remove_all(root);
}

// A plugin's shaders are the second source root: an edited one is recompiled to the shader
// path its pipeline loads (plugins/<name>/shaders/<file>), with shaders/ on its include path.
TEST(ShaderReload, PluginShadersAreASecondSourceRoot) {
  const fs::path root = fs::temp_directory_path() / "twinlight-reload-plugin-test";
  fs::remove_all(root);
  fs::create_directories(root);
  fs::copy(fs::path(TWINLIGHT_SOURCE_ROOT) / "plugins", root / "plugins", fs::copy_options::recursive);
  const fs::path trace = root / "plugins" / "ao_debug" / "shaders" / "ao_trace.comp";
  {
    gpu::ShaderReloader reloader(fs::path(TWINLIGHT_SOURCE_ROOT) / "shaders", root / "spv", root / "plugins");
    EXPECT_TRUE(reloader.poll().recompiled.empty()) << "the first poll only records";
    rewrite(trace, readText(trace) + "\n// edited\n");
    gpu::ShaderReloadResult r = reloader.poll();
    EXPECT_TRUE(r.errors.empty()) << (r.errors.empty() ? "" : r.errors[0]);
    EXPECT_EQ(r.recompiled, std::vector<std::string>{"plugins/ao_debug/shaders/ao_trace.comp"});
    EXPECT_TRUE(fs::exists(root / "spv" / "plugins" / "ao_debug" / "shaders" / "ao_trace.comp.spv"));
  }
  fs::remove_all(root);
}

}  // namespace
}  // namespace tl::test
