#include "session/recovery.h"

#include "albedo/albedo_database.h"
#include "scene/input_limits.h"
#include "session/image_io.h"
#include "session/lighting_file.h"
#include "session/settings_json.h"

#include <fmt/format.h>

#include <cmath>

namespace tl::session {
namespace {

constexpr const char* kFormat = "twinlight.recovery";
constexpr int kVersion = 1;

std::filesystem::path lightingFileOf(const std::filesystem::path& file) {
  std::string name = file.filename().string();
  const std::string suffix = ".recovery.json";
  if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
    name.resize(name.size() - suffix.size());
  return file.parent_path() / (name + ".recovery.lighting.json");
}

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& why) {
  throw SessionError(fmt::format("{}: {}", file.string(), why));
}

float channel(const std::filesystem::path& file, const nlohmann::json& v, const std::string& key) {
  if (!v.is_number()) fail(file, key + ": expected a number");
  const double d = v.get<double>();
  if (!std::isfinite(d) || d < 0.0 || d > 1e6) fail(file, fmt::format("{}: {} is not an albedo", key, d));
  return float(d);
}

}  // namespace

std::filesystem::path recoveryFile(const std::filesystem::path& folder, const std::filesystem::path& scene) {
  const std::string key = std::filesystem::absolute(scene).lexically_normal().string();
  const uint64_t hash = scene::hashBytes(key.data(), key.size());
  return folder / fmt::format("{}-{:08x}.recovery.json", scene.stem().string(), uint32_t(hash));
}

void writeRecovery(const std::filesystem::path& file, const RecoveredWork& work) {
  std::error_code ec;
  std::filesystem::create_directories(file.parent_path(), ec);
  if (ec) fail(file, fmt::format("cannot make its folder: {}", ec.message()));
  const std::filesystem::path lighting = lightingFileOf(file);
  if (work.lighting) writeLightingFile(lighting, *work.lighting);
  nlohmann::json j;
  j["format"] = kFormat;
  j["version"] = kVersion;
  j["scene"] = std::filesystem::absolute(work.scene).lexically_normal().string();
  j["savedAt"] = work.savedAt.empty() ? albedo::utcNow() : work.savedAt;
  j["lighting"] = work.lighting ? nlohmann::json(lighting.filename().string()) : nlohmann::json(nullptr);
  j["settings"] = work.settings ? *work.settings : nlohmann::json(nullptr);
  nlohmann::json overrides = nlohmann::json::array();
  for (const RecoveredOverride& o : work.overrides) {
    nlohmann::json e;
    e["key"] = albedo::keyToHex(o.key);
    e["rgb"] = o.rgb ? nlohmann::json::array({o.rgb->r, o.rgb->g, o.rgb->b}) : nlohmann::json(nullptr);
    e["label"] = o.label;
    overrides.push_back(std::move(e));
  }
  j["overrides"] = std::move(overrides);
  writeTextFile(file, j.dump(2) + "\n");
}

RecoveredWork readRecovery(const std::filesystem::path& file) {
  std::vector<uint8_t> bytes;
  try {
    bytes = scene::readRegularFile(file, scene::InputLimits::kMaxSettingsBytes);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  }
  const std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  nlohmann::json j;
  try {
    scene::requireJsonDepth(text, file.string());
    j = nlohmann::json::parse(text);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  } catch (const nlohmann::json::exception& e) {
    fail(file, fmt::format("not JSON: {}", e.what()));
  }
  if (!j.is_object() || j.value("format", "") != kFormat) fail(file, fmt::format("not a recovery file (format \"{}\")", kFormat));
  if (j.value("version", 0) != kVersion) fail(file, fmt::format("version {} expected", kVersion));
  RecoveredWork work;
  if (!j.contains("scene") || !j["scene"].is_string()) fail(file, "scene: expected the scene's path");
  work.scene = j["scene"].get<std::string>();
  if (j.contains("savedAt") && j["savedAt"].is_string()) work.savedAt = j["savedAt"].get<std::string>();
  if (j.contains("lighting") && !j["lighting"].is_null()) {
    if (!j["lighting"].is_string()) fail(file, "lighting: expected the lighting file's name or null");
    try {
      work.lighting = readLightingFile(file.parent_path() / j["lighting"].get<std::string>(), Lighting{});
    } catch (const SessionError& e) {
      fail(file, fmt::format("lighting: {}", e.what()));
    }
  }
  if (j.contains("settings") && !j["settings"].is_null()) {
    if (!j["settings"].is_object()) fail(file, "settings: expected an object or null");
    try {
      applySettingsJson(lighting::RenderSettings{}, j["settings"]);  // checked here: a bad value is this file's error
    } catch (const SessionError& e) {
      fail(file, fmt::format("settings: {}", e.what()));
    }
    work.settings = j["settings"];
  }
  if (j.contains("overrides")) {
    if (!j["overrides"].is_array()) fail(file, "overrides: expected an array");
    for (size_t i = 0; i < j["overrides"].size(); ++i) {
      const nlohmann::json& e = j["overrides"][i];
      const std::string where = fmt::format("overrides[{}]", i);
      if (!e.is_object()) fail(file, where + ": expected an object");
      RecoveredOverride o;
      const auto key = e.contains("key") && e["key"].is_string() ? albedo::keyFromHex(e["key"].get<std::string>()) : std::nullopt;
      if (!key) fail(file, where + ".key: expected 16 hex digits");
      o.key = *key;
      if (e.contains("rgb") && !e["rgb"].is_null()) {
        if (!e["rgb"].is_array() || e["rgb"].size() != 3) fail(file, where + ".rgb: expected [r, g, b] or null");
        o.rgb = glm::vec3(channel(file, e["rgb"][0], where + ".rgb"), channel(file, e["rgb"][1], where + ".rgb"),
                          channel(file, e["rgb"][2], where + ".rgb"));
      }
      if (e.contains("label") && e["label"].is_string()) o.label = e["label"].get<std::string>();
      work.overrides.push_back(std::move(o));
    }
  }
  return work;
}

void removeRecovery(const std::filesystem::path& file) {
  std::error_code ec;
  std::filesystem::remove(lightingFileOf(file), ec);
  std::filesystem::remove(file, ec);
}

}  // namespace tl::session
