// `twinlight render`: render a scene headless and save the image(s), a sequence for an animation.
#include "cli_command.h"
#include "render_options.h"

#include "cli_output.h"
#include "output_paths.h"
#include "metrics/statistics.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace tl::editor {
namespace {

using metrics::median;
using session::Session;
using session::SessionError;

// GPU milliseconds of every frame and pass, gathered over several renderFrames calls.
struct FrameTimes {
  std::vector<double> frames;
  std::vector<std::pair<std::string, std::vector<double>>> passes;

  void add(const Session& session) {
    frames.insert(frames.end(), session.frameGpuMs().begin(), session.frameGpuMs().end());
    for (const auto& [pass, ms] : session.passGpuMs()) {
      auto it = std::find_if(passes.begin(), passes.end(), [&](const auto& p) { return p.first == pass; });
      if (it == passes.end()) it = passes.insert(passes.end(), {pass, {}});
      it->second.insert(it->second.end(), ms.begin(), ms.end());
    }
  }
};

// The first frame compiles pipelines on first use: it is reported apart from the median.
void printFrameTimes(const FrameTimes& times) {
  const auto& frames = times.frames;
  if (frames.empty()) return;
  if (frames.size() == 1) {
    fmt::print("GPU frame time: {:.2f} ms (one frame, includes first-use pipeline compilation)\n", frames[0]);
    return;
  }
  std::vector<double> steady(frames.begin() + 1, frames.end());
  fmt::print("GPU frame time: median {:.2f} ms over {} frames (min {:.2f}, max {:.2f}); first frame {:.2f} ms\n",
             median(steady), steady.size(), *std::min_element(steady.begin(), steady.end()),
             *std::max_element(steady.begin(), steady.end()), frames[0]);
  for (const auto& [pass, ms] : times.passes) {
    std::vector<double> s(ms.begin() + (ms.size() > 1 ? 1 : 0), ms.end());
    fmt::print("  {:24} {:8.2f} ms\n", pass, median(s));
  }
}

class RenderCommand : public CliCommand {
 public:
  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand("render", "render a scene headless and save the image(s)");
    cmd->add_option("--scene", o_.scene, "glTF file (.gltf/.glb); default content/atrium.gltf");
    cmd->add_option("--path", o_.path, "lighting path (`twinlight info` lists them)");
    cmd->add_option("--frames", o_.frames, "frames to render (the last one is saved)")
        ->check(CLI::Range(1u, kMaxFrames))
        ->capture_default_str();
    cmd->add_option("--renderdoc", o_.renderDoc,
                    "then capture one more frame with RenderDoc into this path template (run under RenderDoc)");
    cmd->add_option("--out", o_.outputs,
                    "output image(s): .exr = scene-linear radiance before exposure, .png = tonemapped display")
        ->required();
    cmd->add_option("--dump-graph", o_.dumpGraph,
                    "write the compiled render graph as text (- for stdout), or Graphviz DOT for a .dot file");
    cmd->add_option("--spp", o_.spp,
                    "reference path: samples per pixel to accumulate (sets the frames); with --until-noise, the cap")
        ->check(CLI::Range(1u, kMaxSpp));
    cmd->add_option("--until-noise", o_.untilNoise,
                    fmt::format("reference path: accumulate until the image's relative standard error (the root of the "
                                "mean variance of the pixels' estimates over their mean) is at most this, e.g. 0.01, or "
                                "until --spp samples (default {}) a pixel",
                                session::NoiseTarget::kDefaultMaxSamples));
    cmd->add_option("--bounces", o_.bounces,
                    "reference path: scattering events per path (1 = direct light only, 2 = one indirect bounce)")
        ->check(CLI::Range(1u, kMaxBounces))
        ->capture_default_str();
    addViewAndLightOptions(*cmd, o_);
    return cmd;
  }
  int run() override { return runRender(o_); }

 private:
  RenderOptions o_;
};

}  // namespace

int runRender(const RenderOptions& o) {
  // Usage and outputs first, before a device or a scene is touched: a typo costs no render.
  bool sequence = false;
  for (const auto& out : o.outputs) {
    checkImageOutput(out);
    sequence = sequence || isFrameSequence(out);
  }
  if (!o.dumpGraph.empty()) checkGraphOutput(o.dumpGraph);
  if (sequence && !o.animateFps)
    throw UsageError("--out with # writes one image per frame of an animation: add --animate FPS (and --frames N)");
  if (sequence && o.spp) throw UsageError("--spp accumulates one image: it cannot write a --out sequence");
  if (sequence && o.untilNoise) throw UsageError("--until-noise accumulates one image: it cannot write a --out sequence");
  if (o.untilNoise && !(*o.untilNoise > 0.0 && std::isfinite(*o.untilNoise)))
    throw SessionError(fmt::format("--until-noise must be a number > 0 (a relative standard error, e.g. 0.01), not {}",
                                   *o.untilNoise));
  if (o.frames == 0) throw SessionError("--frames must be at least 1");
  if (o.bounces == 0) throw SessionError("--bounces must be at least 1");
  uint32_t frames = o.frames;
  if (o.spp) {
    if (*o.spp == 0) throw SessionError("--spp must be at least 1");
    if (*o.spp > 16 && *o.spp % 16) throw SessionError("--spp must be a multiple of 16, or at most 16");
    frames = (*o.spp + 15) / 16;
  }

  Session session;
  prepareSession(session, o);
  const uint32_t w = session.settings().width, h = session.settings().height;
  if (o.spp && o.path != session.referencePath())
    throw SessionError(fmt::format("--spp applies to --path {}", session.referencePath()));
  if (o.untilNoise && o.path != session.referencePath())
    throw SessionError(fmt::format("--until-noise applies to --path {}", session.referencePath()));
  if (o.bounces) session.settings().referenceBounces = *o.bounces;
  // Up to 16 samples a frame: fewer submissions, and each frame stays short.
  if (o.spp) session.settings().referenceSamplesPerFrame = std::min(*o.spp, 16u);

  FrameTimes times;
  // What each image write said, printed after the progress: the file and, for an EXR beyond
  // the half-float range, that it was written as 32-bit float.
  std::vector<std::string> written;
  auto save = [&](const std::filesystem::path& file) {
    const auto result = session.saveImage(file);
    std::string note;
    if (result.float32)
      note = fmt::format(" (32-bit float: {} of {} pixels exceed the half-float range, 65504, and would have clipped)",
                         result.beyondHalf, result.pixels);
    written.push_back(fmt::format("wrote {}{}", std::filesystem::absolute(file).string(), note));
    if (result.nonFinite > 0)
      throw SessionError(fmt::format("{}: {} of {} pixels are not finite", file.string(), result.nonFinite, result.pixels));
  };
  auto start = std::chrono::steady_clock::now();
  std::optional<session::ReferenceConvergence> converged;
  {
    Progress progress("render");
    auto report = [&](uint32_t done) {
      progress.update(double(done) / frames,
                      o.spp ? fmt::format("{}/{} spp", done * session.settings().referenceSamplesPerFrame, *o.spp)
                            : fmt::format("frame {}/{}", done, frames));
    };
    if (o.untilNoise) {
      session::NoiseTarget target;
      target.relativeStdError = *o.untilNoise;
      if (o.spp) target.maxSamples = *o.spp;
      target.samplesPerFrame = std::min(target.samplesPerFrame, target.maxSamples);
      converged = session.renderReferenceUntilNoise(target, [&](const session::ReferenceConvergence& sofar) {
        if (sofar.frames > 0) times.add(session);
        if (!sofar.noise) return;
        // Progress by the noise: samples needed scale as 1 / noise^2.
        const double needed = double(sofar.noise->samplesPerPixel()) * std::pow(sofar.noise->relativeStdError / target.relativeStdError, 2.0);
        progress.update(std::min(1.0, double(sofar.noise->samplesPerPixel()) / std::min(needed, double(target.maxSamples))),
                        fmt::format("{} spp, noise {:.4f} (target {})", sofar.noise->samplesPerPixel(),
                                    sofar.noise->relativeStdError, target.relativeStdError));
      });
      times.add(session);
      frames = converged->frames;
    } else if (!sequence) {
      session.renderFrames(frames, report);
      times.add(session);
    } else {
      // One frame at a time, each read back and written as it is done: frame_0001 is the first.
      for (uint32_t f = 1; f <= frames; ++f) {
        session.renderFrames(1);
        times.add(session);
        for (const auto& out : o.outputs)
          if (isFrameSequence(out)) save(sequenceFrame(out, f));
        report(f);
      }
    }
  }
  double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (const auto& out : o.outputs) {
    if (isFrameSequence(out)) continue;
    save(out);
  }
  for (const auto& line : written) fmt::print("{}\n", line);
  if (!o.renderDoc.empty()) renderDocFrame(session, o.renderDoc);
  fmt::print("rendered {} frame(s) of {} with `{}` at {}x{} on {} in {:.2f} s\n", frames, session.scene().name,
             session.path(), w, h, session.device().name(), seconds);
  printFrameTimes(times);
  if (const auto noise = session.referenceNoise()) {
    // The reference's own noise (session/reference_noise.h), and whether the target was met.
    std::string target;
    if (converged)
      target = converged->reached ? fmt::format(" (target {}: reached)", *o.untilNoise)
                                  : fmt::format(" (target {}: not reached; the cap of {} samples stopped it)", *o.untilNoise,
                                                o.spp.value_or(session::NoiseTarget::kDefaultMaxSamples));
    fmt::print("reference noise: relative standard error {:.5f} after {} samples per pixel{}\n", noise->relativeStdError,
               noise->samplesPerPixel(), target);
  }
  if (!o.dumpGraph.empty()) {
    if (o.dumpGraph == "-") {
      fmt::print("{}", session.graphDump());
    } else {
      session.writeGraph(o.dumpGraph);  // .dot / .gv: Graphviz
      fmt::print("wrote {}\n", o.dumpGraph);
    }
  }
  return exitStatus(session);
}

std::unique_ptr<CliCommand> makeRenderCommand() { return std::make_unique<RenderCommand>(); }

}  // namespace tl::editor
