// `twinlight capture`: every buffer of a frame (EXR + manifest.json) into a folder.
#include "cli_command.h"
#include "render_options.h"

#include "cli_output.h"
#include "session/capture.h"
#include "session/image_io.h"

#include <fmt/format.h>

namespace tl::editor {
namespace {

class CaptureCommand : public CliCommand {
 public:
  CaptureCommand() { render_.frames = 4; }

  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand("capture", "write every buffer of a frame (EXR + manifest.json) into a folder");
    cmd->add_option("--scene", render_.scene, "glTF file; default content/atrium.gltf");
    cmd->add_option("--path", render_.path, "lighting path")->capture_default_str();
    cmd->add_option("--frames", render_.frames, "frames rendered first (the last is captured)")
        ->check(CLI::Range(1u, kMaxFrames))
        ->capture_default_str();
    cmd->add_option("--out", out_, "folder to write into")->required();
    cmd->add_flag("--renderdoc", renderDoc_,
                  "also capture one frame with RenderDoc (run under `renderdoccmd capture` or qrenderdoc)");
    addViewAndLightOptions(*cmd, render_);
    return cmd;
  }

  int run() override {
    session::checkOutputFolder(out_);
    if (render_.frames == 0) throw session::SessionError("--frames must be at least 1");
    session::Session session;
    prepareSession(session, render_);
    session.requestAllBuffers();
    {
      Progress progress("capture");
      session.renderFrames(render_.frames, [&](uint32_t done) {
        progress.update(double(done) / render_.frames, fmt::format("frame {}/{}", done, render_.frames));
      });
    }
    auto manifest = session::writeCapture(session, out_);
    size_t files = 0;
    for (const auto& r : manifest["resources"]) files += !r["file"].is_null();
    fmt::print("captured {} of {} resources of {} / {} (frame {}) into {}\n", files, manifest["resources"].size(),
               manifest["scene"].get<std::string>(), manifest["lightingPath"].get<std::string>(),
               manifest["frame"].get<uint64_t>(), out_);
    if (renderDoc_) renderDocFrame(session, std::filesystem::path(out_) / "renderdoc");
    return exitStatus(session);
  }

 private:
  RenderOptions render_;
  std::string out_;
  bool renderDoc_ = false;
};

}  // namespace

std::unique_ptr<CliCommand> makeCaptureCommand() { return std::make_unique<CaptureCommand>(); }

}  // namespace tl::editor
