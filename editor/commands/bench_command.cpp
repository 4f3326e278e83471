// `twinlight bench`: per-pass GPU milliseconds (median and spread) as a table and JSON (bench.h).
#include "cli_command.h"
#include "render_options.h"

#include "bench.h"
#include "cli_output.h"
#include "output_paths.h"
#include "session/image_io.h"

#include <fmt/format.h>

namespace tl::editor {
namespace {

class BenchCommand : public CliCommand {
 public:
  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand("bench", "per-pass GPU milliseconds (median and spread) as a table and JSON");
    cmd->add_option("--scene", render_.scene, "glTF file; default content/atrium.gltf");
    cmd->add_option("--path", render_.path, "lighting path")->capture_default_str();
    cmd->add_option("--frames", bench_.frames, "frames measured")->check(CLI::Range(1u, kMaxFrames))->capture_default_str();
    cmd->add_option("--warmup", bench_.warmup, "frames rendered first and left out")
        ->check(CLI::Range(0u, kMaxWarmupFrames))
        ->capture_default_str();
    cmd->add_flag("--rays", bench_.rays,
                  "rt path: the device's raw ray rate on the scene's TLAS (trivial kernel) against rt.trace's; "
                  "reference: its paths per second against that rate on its own");
    cmd->add_flag("--cut-every-frame", bench_.cutEveryFrame,
                  "forget the history before every measured frame, as on a camera cut (what rejection costs at worst)");
    cmd->add_option("--frames-in-flight", bench_.framesInFlight,
                    "frames the host may record ahead of the device: 1 waits for each frame, 2 records the next meanwhile")
        ->check(CLI::Range(1u, gpu::kMaxFramesInFlight))
        ->capture_default_str();
    cmd->add_flag("--against-one-in-flight", bench_.againstOneInFlight,
                  "also time frames with one in flight against --frames-in-flight, in turns: the wall-clock ratio");
    cmd->add_option("--json", json_, "write the figures as JSON to FILE (- for stdout)");
    addViewAndLightOptions(*cmd, render_);
    return cmd;
  }

  int run() override {
    checkJsonOutput(json_);
    if (bench_.frames == 0) throw session::SessionError("--frames must be at least 1");
    session::Session session;
    prepareSession(session, render_);
    nlohmann::json report;
    {
      Progress progress("bench");
      report = runBench(session, bench_, [&](const std::string& what, double f) { progress.update(f, what); });
    }
    // With the JSON on stdout, stdout is that one document: the table goes to stderr.
    if (json_ == "-") {
      if (verbosity() != Verbosity::Quiet) fmt::print(stderr, "{}", benchTable(report));
      fmt::print("{}\n", report.dump(2));
    } else {
      fmt::print("{}", benchTable(report));
    }
    if (!json_.empty() && json_ != "-") {
      session::writeTextFile(json_, report.dump(2) + "\n");
      fmt::print("wrote {}\n", json_);
    }
    return exitStatus(session);
  }

 private:
  RenderOptions render_;
  BenchOptions bench_;
  std::string json_;
};

}  // namespace

std::unique_ptr<CliCommand> makeBenchCommand() { return std::make_unique<BenchCommand>(); }

}  // namespace tl::editor
