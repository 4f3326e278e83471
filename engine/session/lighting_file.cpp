#include "session/lighting_file.h"

#include "session/gltf_lights_writer.h"

#include "scene/color_temperature.h"
#include "scene/environment_map.h"
#include "scene/input_limits.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <initializer_list>

namespace tl::session {
namespace {

using nlohmann::json;
using scene::InputLimits;

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

// A direction as a unit vector; one that already is one is kept bit for bit, so a file read
// and written again is the same file.
glm::dvec3 unit(const glm::dvec3& d) {
  const double length = glm::length(d);
  return std::abs(length - 1.0) < 1e-12 ? d : d / length;
}

// Reads one document; every failure names the file and the key (`lights[2].intensity`).
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& why) const {
    throw SessionError(fmt::format("{}: {}: {}", file_, key, why));
  }

  const json& object(const json& parent, const std::string& key, const char* name) const {
    const json& v = parent.at(name);
    if (!v.is_object()) fail(key, "expected an object");
    return v;
  }

  // Only the keys the format has: a misspelt key is an error, not silently ignored.
  void onlyKeys(const json& obj, const std::string& where, std::initializer_list<const char*> known) const {
    for (const auto& [k, v] : obj.items()) {
      bool ok = false;
      for (const char* name : known) ok = ok || k == name;
      if (!ok) {
        std::string list;
        for (const char* name : known) list += fmt::format("{}{}", list.empty() ? "" : ", ", name);
        fail(where.empty() ? k : where + "." + k, fmt::format("unknown key (known: {})", list));
      }
    }
  }

  void required(const json& obj, const std::string& where, const char* name) const {
    if (!obj.contains(name)) fail(where + "." + name, "missing");
  }

  // A finite number within [lo, hi].
  double number(const json& v, const std::string& key, double lo, double hi, const char* unit = "") const {
    if (!v.is_number()) fail(key, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi) fail(key, fmt::format("{:g} is out of range: {:g} to {:g}{}", x, lo, hi, unit));
    return x;
  }

  glm::dvec3 vec3(const json& v, const std::string& key, double limit) const {
    if (!v.is_array() || v.size() != 3) fail(key, "expected three numbers [x, y, z]");
    return {number(v[0], key + "[0]", -limit, limit), number(v[1], key + "[1]", -limit, limit),
            number(v[2], key + "[2]", -limit, limit)};
  }

  // A unit direction (any non-zero length as written).
  glm::dvec3 direction(const json& v, const std::string& key) const {
    const glm::dvec3 d = vec3(v, key, InputLimits::kMaxCoordinate);
    if (!(glm::length(d) > 1e-9)) fail(key, "must not be zero");
    return unit(d);
  }

  // A colour: [r, g, b] (each >= 0) or one number (grey).
  glm::dvec3 color(const json& v, const std::string& key, double limit) const {
    if (v.is_number()) {
      const double x = number(v, key, 0.0, limit);
      return glm::dvec3(x);
    }
    if (!v.is_array() || v.size() != 3) fail(key, "expected [r, g, b] or one number");
    return {number(v[0], key + "[0]", 0.0, limit), number(v[1], key + "[1]", 0.0, limit), number(v[2], key + "[2]", 0.0, limit)};
  }

  // "color" [r, g, b] or "temperature_k" (black body, luminance 1), not both; white without either.
  glm::vec3 colorOrTemperature(const json& obj, const std::string& where) const {
    if (obj.contains("color") && obj.contains("temperature_k")) fail(where, "give `color` or `temperature_k`, not both");
    if (obj.contains("temperature_k"))
      return scene::colorTemperatureToRgb(number(obj.at("temperature_k"), where + ".temperature_k", scene::kMinColorTemperature,
                                                 scene::kMaxColorTemperature, " K"));
    if (obj.contains("color")) return glm::vec3(color(obj.at("color"), where + ".color", InputLimits::kMaxLight));
    return glm::vec3(1.0f);
  }

  // A light-like quantity after conversion: colour times a scalar, every channel finite and
  // within InputLimits::kMaxLight.
  glm::vec3 checkedLight(const glm::dvec3& value, const std::string& key) const {
    for (int c = 0; c < 3; ++c)
      if (!(value[c] >= 0.0 && value[c] <= InputLimits::kMaxLight))
        fail(key, fmt::format("{:g} after conversion is out of range: 0 to {:g}", value[c], double(InputLimits::kMaxLight)));
    return glm::vec3(value);
  }

 private:
  std::string file_;
};

// "irradiance"/"radiance": [r, g, b] as is, or one number times the colour (`color` or
// `temperature_k`).
glm::vec3 readScaledColor(const Reader& r, const json& obj, const std::string& where, const char* name) {
  r.required(obj, where, name);
  const json& v = obj.at(name);
  const std::string key = where + "." + name;
  if (v.is_array()) {
    if (obj.contains("color") || obj.contains("temperature_k"))
      r.fail(key, "an [r, g, b] value takes no `color` or `temperature_k`: give one number with them");
    return r.checkedLight(r.color(v, key, InputLimits::kMaxLight), key);
  }
  const double scale = r.number(v, key, 0.0, InputLimits::kMaxLight);
  return r.checkedLight(glm::dvec3(r.colorOrTemperature(obj, where)) * scale, key);
}

// A size in metres: more than 0, at most the largest coordinate, and still more than 0 as the
// float the light table holds.
float readSize(const Reader& r, const json& j, const std::string& where, const char* name) {
  r.required(j, where, name);
  const std::string key = where + "." + name;
  const float x = float(r.number(j.at(name), key, 0.0, InputLimits::kMaxCoordinate, " m"));
  if (!(x > 0.0f)) r.fail(key, "must be more than 0 m");
  return x;
}

// The shape of an area light: a rectangle's width and height (and the way its width runs), a
// disk's radius, a tube's length and radius; which faces emit.
void readAreaShape(const Reader& r, const json& j, const std::string& where, scene::Light& l) {
  const auto refuse = [&](const char* name, const char* why) {
    if (j.contains(name)) r.fail(where + "." + name, why);
  };
  if (l.type == scene::LightType::Rect) {
    l.width = readSize(r, j, where, "width");
    l.height = readSize(r, j, where, "height");
  } else {
    refuse("width", "only a rect has a width");
    refuse("height", "only a rect has a height");
  }
  if (l.type == scene::LightType::Disk || l.type == scene::LightType::Tube) l.radius = readSize(r, j, where, "radius");
  else refuse("radius", "a rect has width and height, not a radius");
  if (l.type == scene::LightType::Tube) l.length = readSize(r, j, where, "length");
  else refuse("length", "only a tube has a length");
  if (l.type == scene::LightType::Tube) {
    refuse("two_sided", "a tube emits all round");
    refuse("width_axis", "a tube has no width axis");
    return;
  }
  if (j.contains("two_sided")) {
    if (!j.at("two_sided").is_boolean()) r.fail(where + ".two_sided", "expected true or false");
    l.twoSided = j.at("two_sided").get<bool>();
  }
  if (j.contains("width_axis")) {
    l.widthAxis = r.direction(j.at("width_axis"), where + ".width_axis");
    if (glm::length(glm::cross(l.widthAxis, l.direction)) < 1e-3)
      r.fail(where + ".width_axis", "must not be parallel to direction (the light's normal)");
  }
}

// The glTF node a light was saved to (bookkeeping for the next save: gltf_lights_writer.h).
uint32_t readNode(const Reader& r, const json& v, const std::string& key) {
  const double n = r.number(v, key, 0.0, double(INT32_MAX));
  if (n != std::floor(n)) r.fail(key, "expected a node index (a whole number)");
  return uint32_t(n);
}

scene::Light readLight(const Reader& r, const json& j, const std::string& where) {
  if (!j.is_object()) r.fail(where, "expected an object");
  r.onlyKeys(j, where, {"name", "type", "position", "direction", "color", "temperature_k", "intensity", "range",
                        "inner_cone_deg", "outer_cone_deg", "width", "height", "radius", "length", "two_sided", "width_axis",
                        "hidden", "gltf_node"});
  scene::Light l;
  if (j.contains("name")) {
    if (!j.at("name").is_string()) r.fail(where + ".name", "expected a string");
    l.name = j.at("name").get<std::string>();
  }
  if (j.contains("gltf_node")) l.node = readNode(r, j.at("gltf_node"), where + ".gltf_node");
  if (j.contains("hidden")) {
    if (!j.at("hidden").is_boolean()) r.fail(where + ".hidden", "expected true or false");
    l.hidden = j.at("hidden").get<bool>();
  }
  r.required(j, where, "type");
  const json& type = j.at("type");
  const std::string t = type.is_string() ? type.get<std::string>() : "";
  if (t == "point") l.type = scene::LightType::Point;
  else if (t == "spot") l.type = scene::LightType::Spot;
  else if (t == "directional") l.type = scene::LightType::Directional;
  else if (t == "rect") l.type = scene::LightType::Rect;
  else if (t == "disk") l.type = scene::LightType::Disk;
  else if (t == "tube") l.type = scene::LightType::Tube;
  else r.fail(where + ".type", "expected \"point\", \"spot\", \"directional\", \"rect\", \"disk\" or \"tube\"");
  const bool positioned = l.type != scene::LightType::Directional, aimed = l.type != scene::LightType::Point;
  if (positioned) {
    r.required(j, where, "position");
    l.position = r.vec3(j.at("position"), where + ".position", InputLimits::kMaxCoordinate);
  } else if (j.contains("position")) {
    r.fail(where + ".position", "a directional light has no position");
  }
  if (aimed) {
    r.required(j, where, "direction");
    l.direction = r.direction(j.at("direction"), where + ".direction");
  } else if (j.contains("direction")) {
    r.fail(where + ".direction", "a point light has no direction");
  }
  l.color = r.colorOrTemperature(j, where);
  r.required(j, where, "intensity");
  const bool area = scene::isAreaLight(l.type);
  l.intensity = float(r.number(j.at("intensity"), where + ".intensity", 0.0, InputLimits::kMaxLight,
                               l.type == scene::LightType::Directional ? " lux" : area ? " nits" : " cd"));
  r.checkedLight(glm::dvec3(l.color) * double(l.intensity), where + ".intensity");
  if (area) readAreaShape(r, j, where, l);
  else if (j.contains("width") || j.contains("height") || j.contains("radius") || j.contains("length") || j.contains("two_sided") ||
           j.contains("width_axis"))
    r.fail(where, "only an area light (rect, disk, tube) has a shape");
  if (j.contains("range") && !j.at("range").is_null()) {
    if (!positioned) r.fail(where + ".range", "a directional light has no range");
    if (area) r.fail(where + ".range", "an area light has no range");
    const double range = r.number(j.at("range"), where + ".range", 0.0, InputLimits::kMaxCoordinate, " m");
    if (!(range > 0.0)) r.fail(where + ".range", "must be more than 0 (null: unlimited)");
    l.range = float(range);
  }
  if (l.type == scene::LightType::Spot) {
    if (j.contains("inner_cone_deg"))
      l.innerConeAngle = float(r.number(j.at("inner_cone_deg"), where + ".inner_cone_deg", 0.0, 90.0, " degrees") / kDegrees);
    if (j.contains("outer_cone_deg"))
      l.outerConeAngle = float(r.number(j.at("outer_cone_deg"), where + ".outer_cone_deg", 0.0, 90.0, " degrees") / kDegrees);
    // As KHR_lights_punctual: 0 <= inner < outer <= pi/2, checked in radians as they will be used.
    if (!(l.innerConeAngle >= 0.0f && l.innerConeAngle < l.outerConeAngle && l.outerConeAngle <= 0.5f * 3.14159265f + 1e-6f))
      r.fail(where, fmt::format("cones must satisfy 0 <= inner_cone_deg < outer_cone_deg <= 90 (inner {:g}, outer {:g})",
                                l.innerConeAngle * kDegrees, l.outerConeAngle * kDegrees));
  } else if (j.contains("inner_cone_deg") || j.contains("outer_cone_deg")) {
    r.fail(where, "only a spot light has cones");
  }
  return l;
}

// Written in the format's own order (format and version first), read in any order.
using ordered = nlohmann::ordered_json;
ordered colorJson(const glm::vec3& c) { return ordered::array({double(c.r), double(c.g), double(c.b)}); }
ordered vecJson(const glm::dvec3& v) { return ordered::array({v.x, v.y, v.z}); }

}  // namespace

std::filesystem::path lightingSidecarPath(const std::filesystem::path& scene) {
  std::filesystem::path p = scene;
  p.replace_extension(".lighting.json");
  return p;
}

Lighting readLightingFile(const std::filesystem::path& file, const Lighting& base) {
  const Reader r(file.string());
  std::vector<uint8_t> bytes;
  try {
    bytes = scene::readRegularFile(file, InputLimits::kMaxSettingsBytes);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  }
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  json j;
  try {
    scene::requireJsonDepth(text, file.string());
    j = json::parse(text);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  } catch (const json::exception& e) {
    throw SessionError(fmt::format("{}: not JSON: {}", file.string(), e.what()));
  }
  if (!j.is_object()) r.fail("(document)", "expected a JSON object");
  if (!j.contains("format") || j.at("format") != kLightingFormat)
    r.fail("format", fmt::format("expected \"{}\" (a Twinlight lighting file)", kLightingFormat));
  if (!j.contains("version") || j.at("version") != kLightingFormatVersion)
    r.fail("version", fmt::format("expected {} (this Twinlight reads version {})", kLightingFormatVersion, kLightingFormatVersion));
  r.onlyKeys(j, "", {"format", "version", "sun", "sky", "exposure_ev", "environment", "lights"});

  Lighting l = base;
  if (j.contains("sun")) {
    const json& s = r.object(j, "sun", "sun");
    r.onlyKeys(s, "sun", {"direction", "irradiance", "color", "temperature_k", "angular_radius_deg", "gltf_node"});
    if (s.contains("gltf_node")) l.sunNode = readNode(r, s.at("gltf_node"), "sun.gltf_node");
    r.required(s, "sun", "direction");
    l.sunDirection = r.direction(s.at("direction"), "sun.direction");
    l.sunIrradiance = readScaledColor(r, s, "sun", "irradiance");
    if (s.contains("angular_radius_deg"))
      l.sunAngularRadius = float(r.number(s.at("angular_radius_deg"), "sun.angular_radius_deg", 0.0, 10.0, " degrees") / kDegrees);
  }
  if (j.contains("sky")) {
    const json& s = r.object(j, "sky", "sky");
    r.onlyKeys(s, "sky", {"radiance", "color", "temperature_k"});
    l.skyRadiance = readScaledColor(r, s, "sky", "radiance");
  }
  if (j.contains("exposure_ev")) {
    const json& e = j.at("exposure_ev");
    const double most = InputLimits::kMaxExposureEv;
    l.exposureEv = e.is_null() ? std::nullopt : std::optional<float>(float(r.number(e, "exposure_ev", -most, most, " EV")));
  }
  if (j.contains("environment")) {
    const json& e = j.at("environment");
    if (e.is_null()) {
      l.environmentMap.reset();
      l.environmentRotation = 0.0f;
      l.environmentIntensity = 1.0f;
    } else {
      if (!e.is_object()) r.fail("environment", "expected an object or null (the uniform sky)");
      r.onlyKeys(e, "environment", {"file", "rotation_deg", "intensity"});
      r.required(e, "environment", "file");
      if (!e.at("file").is_string() || e.at("file").get<std::string>().empty())
        r.fail("environment.file", "expected the path of an EXR or HDR image");
      std::filesystem::path map = e.at("file").get<std::string>();
      if (map.is_relative()) map = file.parent_path() / map;
      const float rotation =
          e.contains("rotation_deg") ? float(r.number(e.at("rotation_deg"), "environment.rotation_deg", -360.0, 360.0, " degrees") / kDegrees)
                                     : 0.0f;
      const float intensity = e.contains("intensity") ? float(r.number(e.at("intensity"), "environment.intensity", 0.0, 1e6)) : 1.0f;
      // The map last: a bad value above fails before an image is read.
      try {
        l.environmentMap = std::make_shared<const scene::EnvironmentMap>(scene::loadEnvironmentMap(map));
      } catch (const scene::SceneError& err) {
        throw SessionError(fmt::format("{}: environment.file: {}", file.string(), err.what()));
      }
      l.environmentRotation = rotation;
      l.environmentIntensity = intensity;
    }
  }
  if (j.contains("lights")) {
    const json& a = j.at("lights");
    if (!a.is_array()) r.fail("lights", "expected an array of lights");
    std::vector<scene::Light> lights;
    for (size_t i = 0; i < a.size(); ++i) lights.push_back(readLight(r, a[i], fmt::format("lights[{}]", i)));
    l.lights = std::move(lights);
  }
  return l;
}

std::string lightingJson(const Lighting& lighting, const std::filesystem::path& folder) {
  ordered j = ordered::object();
  j["format"] = kLightingFormat;
  j["version"] = kLightingFormatVersion;
  ordered& sun = j["sun"] = ordered::object();
  sun["direction"] = vecJson(unit(lighting.sunDirection));
  sun["irradiance"] = colorJson(lighting.sunIrradiance);
  sun["angular_radius_deg"] = double(lighting.sunAngularRadius) * kDegrees;
  if (lighting.sunNode) sun["gltf_node"] = *lighting.sunNode;
  j["sky"] = ordered::object();
  j["sky"]["radiance"] = colorJson(lighting.skyRadiance);
  j["exposure_ev"] = lighting.exposureEv ? ordered(double(*lighting.exposureEv)) : ordered(nullptr);
  if (lighting.environmentMap) {
    std::filesystem::path map = lighting.environmentMap->path;
    if (!folder.empty() && scene::isInsideFolder(folder, map))
      map = std::filesystem::relative(std::filesystem::weakly_canonical(map), std::filesystem::weakly_canonical(folder));
    else
      map = std::filesystem::absolute(map);
    ordered& env = j["environment"] = ordered::object();
    env["file"] = map.generic_string();
    env["rotation_deg"] = double(lighting.environmentRotation) * kDegrees;
    env["intensity"] = double(lighting.environmentIntensity);
  } else {
    j["environment"] = nullptr;
  }
  ordered lights = ordered::array();
  for (const auto& l : lighting.lights) {
    ordered o = ordered::object();
    o["name"] = l.name;
    o["type"] = scene::lightTypeName(l.type);
    if (l.type != scene::LightType::Directional) o["position"] = vecJson(l.position);
    if (l.type != scene::LightType::Point) o["direction"] = vecJson(unit(l.direction));
    o["color"] = colorJson(l.color);
    o["intensity"] = double(l.intensity);
    if (l.type != scene::LightType::Directional && !scene::isAreaLight(l.type))
      o["range"] = l.range ? ordered(double(*l.range)) : ordered(nullptr);
    if (l.type == scene::LightType::Rect) {
      o["width"] = double(l.width);
      o["height"] = double(l.height);
    }
    if (l.type == scene::LightType::Disk || l.type == scene::LightType::Tube) o["radius"] = double(l.radius);
    if (l.type == scene::LightType::Tube) o["length"] = double(l.length);
    if (l.type == scene::LightType::Rect || l.type == scene::LightType::Disk) {
      o["two_sided"] = l.twoSided;
      // A width axis along the normal means "any": left out, as a file that gave none.
      if (glm::length(glm::cross(l.widthAxis, l.direction)) >= 1e-3 * glm::length(l.widthAxis) * glm::length(l.direction))
        o["width_axis"] = vecJson(unit(l.widthAxis));
    }
    if (l.type == scene::LightType::Spot) {
      o["inner_cone_deg"] = double(l.innerConeAngle) * kDegrees;
      o["outer_cone_deg"] = double(l.outerConeAngle) * kDegrees;
    }
    if (l.hidden) o["hidden"] = true;  // written only when set: a file without it shows every light
    if (l.node) o["gltf_node"] = *l.node;
    lights.push_back(std::move(o));
  }
  j["lights"] = std::move(lights);
  return j.dump(2) + "\n";
}

void writeLightingFile(const std::filesystem::path& file, const Lighting& lighting) {
  const std::string text = lightingJson(lighting, file.parent_path().empty() ? std::filesystem::current_path() : file.parent_path());
  // Like an image written with --out: the folder is made when it does not exist yet.
  std::error_code dirError;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), dirError);
  if (dirError)
    throw SessionError(fmt::format("{}: cannot make its folder for the lighting file: {}", file.string(), dirError.message()));
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.close();
    if (!out) throw SessionError(fmt::format("{}: cannot write the lighting file", file.string()));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw SessionError(fmt::format("{}: cannot write the lighting file", file.string()));
  }
}

SavedLighting saveSceneLighting(const std::filesystem::path& scene, Lighting& lighting) {
  // The glTF's lights: the sun first (the importer takes the first directional light as the
  // sun), then every punctual light that shows; on glTF's scale (lux, candela).
  std::vector<scene::Light> punctual;
  std::vector<scene::Light*> owners;  // the lighting's light each entry came from (null: the sun)
  const float sunE = std::max({lighting.sunIrradiance.r, lighting.sunIrradiance.g, lighting.sunIrradiance.b});
  if (sunE > 0.0f) {
    scene::Light sun;
    sun.name = lighting.sunName.empty() ? "Sun" : lighting.sunName;
    sun.type = scene::LightType::Directional;
    sun.color = lighting.sunIrradiance / sunE;
    sun.intensity = float(double(sunE) * scene::kLumensPerWatt);
    sun.direction = lighting.sunDirection;
    sun.node = lighting.sunNode;
    punctual.push_back(sun);
    owners.push_back(nullptr);
  }
  for (auto& l : lighting.lights)
    if (!l.hidden && !scene::isAreaLight(l.type)) punctual.push_back(l), owners.push_back(&l);
  const std::vector<uint32_t> nodes = writeGltfLights(scene, punctual);
  for (size_t i = 0; i < nodes.size(); ++i) (owners[i] ? owners[i]->node : lighting.sunNode) = nodes[i];
  if (sunE <= 0.0f) lighting.sunNode.reset();
  for (auto& l : lighting.lights)  // not in the glTF: no node of it holds them now
    if (l.hidden || scene::isAreaLight(l.type)) l.node.reset();
  SavedLighting saved;
  saved.sidecar = lightingSidecarPath(scene);
  saved.gltfLights = punctual.size();
  writeLightingFile(saved.sidecar, lighting);
  return saved;
}

OpeningLighting openingLighting(const scene::Scene& scene, const std::optional<std::filesystem::path>& lightingFile,
                                bool defaultSun) {
  OpeningLighting opened;
  opened.lighting = sceneLighting(scene, Lighting{});
  bool emissive = false;
  for (const auto& m : scene.materials) emissive |= m.emissiveStrength * glm::length(m.emissiveFactor) > 0.0f;
  if (defaultSun && !scene.environment.sunFromFile && !emissive && scene.lights.empty()) {
    opened.lighting.sunIrradiance = scene::Environment{}.sunIrradiance;
    opened.defaultSun = true;
  }
  const std::filesystem::path file = lightingFile.value_or(lightingSidecarPath(scene.path));
  std::error_code ec;
  // A --lighting file that is not there is an error; a scene without a sidecar is the usual case.
  if (!lightingFile && !std::filesystem::exists(file, ec)) return opened;
  try {
    opened.lighting = readLightingFile(file, opened.lighting);
    opened.readFrom = file;
  } catch (const SessionError& e) {
    opened.error = e.what();
  }
  return opened;
}

}  // namespace tl::session
