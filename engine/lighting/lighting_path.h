// A lighting path is an interface, not an if-statement: given the G-buffer and the sun
// shadow map in the graph, it adds its own passes and names the resources the shared
// composite consumes. Direct, legacy, RT and reference implement it; plugins may too.
#pragma once

#include "graph/graph.h"
#include "lighting/common/frame_inputs.h"
#include "shared/sh.h"

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace tl::lighting {

// Names of graph resources a path produced; empty means "not produced" and the composite
// uses the neutral value (AO = 1, unoccluded sky irradiance, no indirect specular).
// The GI fade beyond LightingOutputs::giBlendDistance spans this fraction of it (it starts at
// (1 - fraction) x the distance).
inline constexpr float kGiBlendWidthFraction = 0.2f;

struct LightingOutputs {
  std::string ambientOcclusion;  // R8/R16F, 1 = unoccluded
  std::string diffuseShY;        // RGBA16F, L1 SH of luma (shared/sh.h)
  std::string diffuseCoCg;       // RG16F, chroma
  std::string specular;          // RGBA16F, traced reflections: demodulated radiance (rgb), weight (a) (shared/rt_specular.h)
  std::string radiance;          // a path that computes the whole image (the reference):
                                 // the composite passes it through unchanged
  // Beyond this view distance (m) the path's diffuse GI fades out over 20% of it (Metro: RT
  // GI to 250 m, then the legacy pipeline): towards the far field below when given, else the
  // unoccluded sky. 0: no fade.
  float giBlendDistance = 0.0f;
  // The far field: another path's diffuse GI (SH + chroma, times its AO), e.g. legacy's.
  std::string farShY, farCoCg, farAo;
  // The directionality of a uniform sky in the SH (shared/sh.h): what "no direction" looks
  // like in how the path gathers, for the specular (shared/sh_specular.h) and for filters
  // across normals. The RT path's cosine samples: kShOpenSkyDirectionality; legacy's cones:
  // tlLegacyOpenSkyDirectionality(). farOpenSkyDirectionality: the far field's.
  float openSkyDirectionality = shared::kShOpenSkyDirectionality;
  float farOpenSkyDirectionality = shared::kShOpenSkyDirectionality;
  // The AO also darkens the diffuse GI (legacy: coarse voxel GI needs SSAO's contact detail).
  // Off for ray-traced GI, whose rays already saw the occluders.
  bool aoOnGi = false;
  // A top level the light table's shadow rays at the pixels trace (lights.direct): the rt
  // path's, then any bottom levels a frame rewrites. Empty: the lights are unshadowed (direct, legacy).
  std::vector<std::string> shadowStructures;
  VkAccelerationStructureKHR shadowTlasHandle = VK_NULL_HANDLE;
  // Set by the session, not the path: the lights.direct image the composite adds ("" if none).
  std::string lightsRadiance;
};

// Graph resources a path makes for those who measure it, beyond what the composite takes
// (empty: not made). Compare, the Compare panel and the noise figures read a path through these
// names, never its own headers.
struct PathReadouts {
  std::string image;             // a path that computes the whole image: that image (else composite.hdr)
  std::string ambientOcclusion;  // its AO (1 = unoccluded)
  std::string irradiance;        // irradiance at the pixels, without the sun
  std::string noise;             // per-pixel standard error of its estimate (rgba32f: rgb, a the pixel's samples)
  std::string noiseTotals;       // a buffer of one shared::RefNoiseTotals: the image's noise, read back every frame
  std::vector<std::string> byDepth;  // its radiance split by path depth (what --bounces caps), in depth order
  // Its radiance split by the first surface's lobe: what it reflects through its diffuse layer,
  // and through its specular lobes (rgb each; what the camera sees directly is in neither).
  std::vector<std::string> byLobe;
  std::vector<std::string> shaders;  // the shaders its estimate comes from: a cache of its images keys on their SPIR-V
};

// What a path is, for everything that must treat paths differently without knowing their
// names: the session, compare, bench and the editor ask these.
struct PathCapabilities {
  bool needsRayTracing = false;  // runs only on a device with ray-tracing pipelines (unavailableReason says why not)
  bool isReference = false;      // the ground truth: compare and the Compare panel measure the other paths against it
  bool accumulates = false;      // holds history: its image converges over still frames
  bool rasterizes = true;        // shades the G-buffer the rasterizer drew, so TAA's jitter applies; the reference
                                 // path tracer computes every pixel itself, jittering its own rays
  bool halfResolution = false;   // can trace at reduced resolution (its settings say how)
  // A debug view, not lighting: its image holds values to look at (AO as grey), shown as they
  // are (no exposure, no tonemap curve: the same grey in every scene) and left out of compare
  // and the Compare panel unless asked for by name (an error against the reference means nothing).
  bool debugView = false;
  PathReadouts readouts;
};

// What `bench --rays` gives a path to make its ray figures from: the last frame's settings
// and index, its read-backs (those the path asked for with rayProbeReadbacks) and the median
// GPU time of a pass by name (0 when it did not run).
struct RayProbeFrame {
  const RenderSettings& settings;
  uint32_t frameIndex = 0;
  std::function<const graph::Readback&(std::string_view name)> readback;
  std::function<double(std::string_view pass)> medianMs;
  // `count` things done in `ms` milliseconds, per second (0 for a pass that did not run).
  static double perSecond(double count, double ms) { return ms > 0.0 ? count / (ms * 1e-3) : 0.0; }
};

class LightingPath {
 public:
  virtual ~LightingPath() = default;
  virtual std::string name() const = 0;         // "direct", "legacy", "rt", "reference"
  virtual std::string description() const = 0;  // one line for --help and tooltips
  // Why this device cannot run the path (shown verbatim), or nothing when it can: by default,
  // what the capabilities need (ray tracing).
  virtual std::optional<std::string> unavailableReason(const gpu::Device& device) const;
  virtual LightingOutputs addPasses(graph::RenderGraph& graph, FrameInputs& in) = 0;
  // Figures about the last frame beyond pass timings (acceleration-structure sizes, culled
  // instances, ...), name -> value, for the benchmark and the tests.
  virtual std::vector<std::pair<std::string, double>> figures() const { return {}; }
  // `bench --rays`: a path with a trivial benchmark kernel turns it on in `settings` (false:
  // it has none), names the buffers its figures read back, and makes them from a frame: its
  // rate of rays or paths against the trivial kernel's on the same structures.
  virtual bool enableRayProbe(RenderSettings&) const { return false; }
  virtual std::vector<std::string> rayProbeReadbacks() const { return {}; }
  virtual std::vector<std::pair<std::string, double>> rayFigures(const RayProbeFrame&) const { return {}; }
  virtual PathCapabilities capabilities() const = 0;
};

// The lighting paths this build knows, in the order they are listed (the editor, `twinlight
// info`, compare): the built-in ones, then the plugins' (plugins/, registered with
// registerLightingPath) in the order of their names. The session makes one of each; nothing
// else names them.
using LightingPathFactory = std::unique_ptr<LightingPath> (*)();
const std::vector<LightingPathFactory>& lightingPathRegistry();
// Adds a plugin's path (once per factory); its name must not be taken (std::logic_error).
// Cheap to call before main(): the factory's path is made once, for its name, and dropped.
void registerLightingPath(LightingPathFactory factory);
// Whether the path of this name came from registerLightingPath (a plugin), not the engine.
bool isPluginPath(std::string_view name);
// The registered paths' names, in the registry's order.
std::vector<std::string> lightingPathNames();

// A plugin registers its path from a static object in its own .cpp:
//   static const LightingPathRegistrar registrar(makeMyPath);
// (plugins/CMakeLists.txt links plugins WHOLE_ARCHIVE so that object file is kept.)
struct LightingPathRegistrar {
  explicit LightingPathRegistrar(LightingPathFactory factory) { registerLightingPath(factory); }
};

// Sun + sky without indirect light: the baseline every other path adds to.
std::unique_ptr<LightingPath> makeDirectPath();
// Progressive path tracer on the ray-tracing pipeline: the ground truth.
std::unique_ptr<LightingPath> makeReferencePath();
// RTX OFF: GTAO + voxel-clipmap cone-traced GI and voxel AO.
std::unique_ptr<LightingPath> makeLegacyPath();
// Metro Exodus' hybrid RT GI + RTAO: one ray per pixel, SH irradiance, accumulation.
std::unique_ptr<LightingPath> makeRtPath();

}  // namespace tl::lighting
