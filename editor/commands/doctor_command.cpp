// `twinlight doctor`: a stability report of every lighting path on a scene (session/doctor.h).
#include "cli_command.h"
#include "render_options.h"

#include "output_paths.h"
#include "session/doctor.h"
#include "session/image_io.h"

#include <fmt/format.h>

namespace tl::editor {
namespace {

class DoctorCommand : public CliCommand {
 public:
  DoctorCommand() { render_.size = "128x72"; }

  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand(
        "doctor",
        "stability report: every lighting path on SCENE, NaN/Inf/negative counts per buffer, energy against the "
        "reference, flicker over a short camera orbit, the frames the reflections take to settle after it, messages "
        "from the Vulkan layers; exit status 1 when not healthy");
    cmd->add_option("scene", render_.scene, "glTF file")->required();
    cmd->add_option("--frames", doctor_.frames, "frames each real-time path renders before its buffers are read")
        ->check(CLI::Range(1u, kMaxFrames))
        ->capture_default_str();
    cmd->add_option("--spp", doctor_.referenceSpp, "the reference's samples per pixel")
        ->check(CLI::Range(1u, kMaxSpp))
        ->capture_default_str();
    cmd->add_option("--orbit-frames", doctor_.orbitFrames, "frames of the camera orbit that measures flicker (0: none)")
        ->check(CLI::Range(0u, kMaxFrames))
        ->capture_default_str();
    cmd->add_option("--orbit-degrees", doctor_.orbitDegrees,
                    "the orbit's step per frame in degrees, about the point looked at (larger: a faster camera)")
        ->check(CLI::Range(0.0, 45.0))
        ->capture_default_str();
    cmd->add_option("--settle-frames", doctor_.settleFrames,
                    "frames the view is held after the orbit, to measure how many the reflections take to settle "
                    "(0: none; needs --orbit-frames 2 or more)")
        ->check(CLI::Range(0u, kMaxFrames))
        ->capture_default_str();
    cmd->add_option("--json", json_, "also write the report as JSON to FILE (- for stdout)");
    addViewAndLightOptions(*cmd, render_);
    return cmd;
  }

  int run() override {
    checkJsonOutput(json_);
    // The validation layers are part of the report: they are always on here.
    gpu::DeviceOptions device;
    device.validation = true;
    session::Session session(device);
    prepareSession(session, render_);
    const auto report = session::runDoctor(session, doctor_);
    // With the JSON on stdout, stdout is that one document: the text report goes to stderr.
    fmt::print(json_ == "-" ? stderr : stdout, "{}", report.toText());
    if (json_ == "-") {
      fmt::print("{}\n", report.toJson().dump(2));
    } else if (!json_.empty()) {
      session::writeTextFile(json_, report.toJson().dump(2) + "\n");
      fmt::print("wrote {}\n", json_);
    }
    if (!report.healthy())
      throw session::SessionError(fmt::format("{} is not healthy: non-finite or negative values or validation "
                                              "messages (the report above names them)",
                                              render_.scene));
    return 0;
  }

 private:
  RenderOptions render_;
  session::DoctorOptions doctor_;
  std::string json_;
};

}  // namespace

std::unique_ptr<CliCommand> makeDoctorCommand() { return std::make_unique<DoctorCommand>(); }

}  // namespace tl::editor
