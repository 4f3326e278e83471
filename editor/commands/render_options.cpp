#include "render_options.h"

#include "gpu/install_paths.h"
#include "gpu/renderdoc.h"
#include "session/lighting_file.h"
#include "session/settings_json.h"

#include <fmt/format.h>
#include <glm/trigonometric.hpp>

namespace tl::editor {

using session::Session;
using session::SessionError;

std::filesystem::path defaultScene() { return gpu::contentDirectory() / "atrium.gltf"; }

void addViewAndLightOptions(CLI::App& cmd, RenderOptions& o) {
  o.sizeOption = cmd.add_option("--size", o.size, "image size WxH (wins over --settings)")->capture_default_str();
  cmd.add_option("--set", o.sets,
                 "change a render setting, NAME=VALUE (repeatable; `twinlight settings` lists them), e.g. "
                 "--set shadowMapSize=4096 --set materials=clay; a JSON object is taken too")
      ->allow_extra_args(false);
  cmd.add_option("--settings", o.settingsFile,
                 o.settingsMayListVariants
                     ? "JSON file: settings for every path (an object, or a capture manifest, bench JSON or report "
                       "holding one), or a list of configurations [{\"name\": N, \"path\": P, \"settings\": {...}}, ...] "
                       "measured after --paths"
                     : "JSON file of settings to start from: an object, or a capture manifest, bench JSON or compare "
                       "report (its \"settings\"); --size, --set and the other options win over it");
  addSettingAliases(cmd, o.aliases);
  cmd.add_option("--camera", o.view.camera, "use the scene's glTF camera N (0-based)");
  cmd.add_option("--albedo-db", o.albedoDb, "albedo database whose baked values and overrides the RT path's hits use");
  cmd.add_flag("--allow-outside-files", o.allowOutsideFiles,
               "let the scene read buffers and images outside its own folder (../, absolute paths, links out)");
  cmd.add_option("--look-from", o.view.lookFrom, "camera position x,y,z (metres, y up)");
  cmd.add_option("--look-at", o.view.lookAt, "point the camera looks at, x,y,z");
  cmd.add_option("--fov", o.view.fovDegrees, "vertical field of view in degrees");
  cmd.add_option("--lighting", o.light.lighting,
                 "lighting file (SCENE.lighting.json: sun, sky, environment, exposure, punctual and area lights) in place of the "
                 "scene's own; the light options below win over it");
  cmd.add_option("--save-lighting", o.light.saveLighting,
                 "write the lighting this command renders with (the scene's lights, --lighting and every light option) "
                 "to a lighting file");
  cmd.add_option("--sun-dir", o.light.sunDir, "direction sunlight travels, x,y,z");
  cmd.add_option("--sun", o.light.sun, "sun irradiance E (W/m^2-like; white Lambertian facing it shows E/pi), E or r,g,b");
  cmd.add_option("--sky", o.light.sky, "uniform sky radiance L, L or r,g,b");
  cmd.add_option("--environment", o.light.environment,
                 "equirectangular environment map (EXR, HDR: radiance on the sky's scale) in place of the uniform sky");
  cmd.add_option("--environment-rotation", o.light.environmentRotation,
                 "turn the environment map about +Y, degrees (counter-clockwise seen from above)");
  cmd.add_option("--environment-intensity", o.light.environmentIntensity, "multiply the environment map's radiance");
  cmd.add_option("--exposure", o.light.exposureEv, "exposure in EV (default: from the sun and sky)");
  cmd.add_option("--sun-size", o.sunSizeDegrees, "angular radius of the sun in degrees (0.27 = the real sun): soft shadows")
      ->check(CLI::Range(0.01f, 10.0f));
  cmd.add_option("--time", o.time, "animation time in seconds (morph targets, node animation) of the first frame")->capture_default_str();
  cmd.add_option("--animate", o.animateFps, "play the animations: each frame advances 1/FPS seconds")
      ->check(CLI::Range(1.0, 1000.0));
}

void prepareSession(Session& session, const RenderOptions& o) {
  applySettingAliases(lighting::RenderSettings{}, o.aliases);  // a bad value fails before the scene loads
  session.loadScene(o.scene.empty() ? defaultScene() : std::filesystem::path(o.scene),
                    scene::LoadOptions{o.allowOutsideFiles});
  session.setPath(o.path);
  auto [w, h] = parseSize(o.size);
  session.setSize(w, h);
  if (!o.settingsFile.empty()) {
    session.settings() = session::applySettingsJson(session.settings(), session::readSettingsFile(o.settingsFile));
    if (o.sizeOption && o.sizeOption->count() > 0) session.setSize(w, h);
  }
  session.settings() = applySettingAliases(session.settings(), o.aliases);
  for (const std::string& assignment : o.sets) {
    if (!assignment.empty() && assignment.front() == '{') {  // the JSON form bench --set took first
      nlohmann::json overrides;
      try {
        overrides = session::parseSettingsText(assignment, "--set");
      } catch (const nlohmann::json::exception& e) {
        throw SessionError(fmt::format("--set is not JSON: {}", e.what()));
      }
      session.settings() = session::applySettingsJson(session.settings(), overrides);
    } else {
      session.settings() = session::applySettingText(session.settings(), assignment);
    }
  }
  applyView(session, o.view);
  applyLight(session, o.light);
  if (!o.albedoDb.empty()) session.openAlbedoDatabase(o.albedoDb, false);
  if (o.sunSizeDegrees) {
    auto light = session.lighting();
    light.sunAngularRadius = glm::radians(*o.sunSizeDegrees);
    session.setLighting(light);
  }
  if (!o.light.saveLighting.empty()) session::writeLightingFile(o.light.saveLighting, session.lighting());
  session.setAnimationTime(o.time);
  session.setAnimationStep(o.animateFps ? 1.0 / *o.animateFps : 0.0);
}

nlohmann::json renderOptionsJson(const RenderOptions& o) {
  auto opt = [](const auto& v) { return v ? nlohmann::json(*v) : nlohmann::json(nullptr); };
  nlohmann::json aliases = nlohmann::json::object();
  for (size_t i = 0; i < o.aliases.size(); ++i) aliases[settingAliases()[i].option] = opt(o.aliases[i]);
  return {{"size", o.size},
          {"camera", opt(o.view.camera)},
          {"lookFrom", o.view.lookFrom},
          {"lookAt", o.view.lookAt},
          {"fov", opt(o.view.fovDegrees)},
          {"sunDir", o.light.sunDir},
          {"sun", o.light.sun},
          {"sky", o.light.sky},
          {"exposure", opt(o.light.exposureEv)},
          {"settingAliases", aliases},
          {"set", o.sets},
          {"settingsFile", o.settingsFile},
          {"albedoDb", o.albedoDb},
          {"sunSize", opt(o.sunSizeDegrees)},
          {"time", o.time},
          {"animate", opt(o.animateFps)}};
}

void renderDocFrame(Session& session, const std::filesystem::path& pathTemplate) {
  auto& rd = gpu::RenderDoc::get();
  if (!rd.attached()) throw SessionError("RenderDoc capture unavailable: " + rd.unavailableReason());
  rd.setCaptureTemplate(std::filesystem::absolute(pathTemplate).string());
  rd.startFrame(session.device().instance());
  session.renderFrames(1);
  if (!rd.endFrame(session.device().instance()) || rd.captureCount() == 0)
    throw SessionError("RenderDoc captured nothing");
  fmt::print("RenderDoc capture: {}\n", rd.capturePath(rd.captureCount() - 1).value_or("?"));
}

}  // namespace tl::editor
