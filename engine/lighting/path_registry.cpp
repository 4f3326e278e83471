#include "lighting/lighting_path.h"

#include <algorithm>
#include <stdexcept>

namespace tl::lighting {
namespace {

struct Entry {
  LightingPathFactory make;
  std::string name;
  bool plugin;
};

// Function-local statics: plugins register from static initialisers, in whatever order the
// linker runs them, so the table must exist before the first of them.
std::vector<Entry>& entries() {
  static std::vector<Entry> table = [] {
    std::vector<Entry> t;
    for (LightingPathFactory f : {makeDirectPath, makeLegacyPath, makeRtPath, makeReferencePath})
      t.push_back({f, f()->name(), false});
    return t;
  }();
  return table;
}

std::vector<LightingPathFactory>& factories() {
  static std::vector<LightingPathFactory> list;
  return list;
}

void rebuildFactories() {
  factories().clear();
  for (const Entry& e : entries()) factories().push_back(e.make);
}

}  // namespace

std::optional<std::string> LightingPath::unavailableReason(const gpu::Device& device) const {
  if (capabilities().needsRayTracing && !device.rayTracing().pipeline)
    return "needs hardware or lavapipe ray tracing: " + device.rayTracing().unavailableReason;
  return std::nullopt;
}

const std::vector<LightingPathFactory>& lightingPathRegistry() {
  if (factories().size() != entries().size()) rebuildFactories();
  return factories();
}

void registerLightingPath(LightingPathFactory factory) {
  auto& table = entries();
  for (const Entry& e : table)
    if (e.make == factory) return;
  std::string name = factory()->name();
  for (const Entry& e : table)
    if (e.name == name) throw std::logic_error("two lighting paths are named `" + name + "`");
  // Plugins after the built-ins, by name: the same order whatever order the linker chose.
  auto at = std::find_if(table.begin(), table.end(), [&](const Entry& e) { return e.plugin && e.name > name; });
  table.insert(at, {factory, std::move(name), true});
  rebuildFactories();
}

std::vector<std::string> lightingPathNames() {
  std::vector<std::string> names;
  for (const Entry& e : entries()) names.push_back(e.name);
  return names;
}

bool isPluginPath(std::string_view name) {
  for (const Entry& e : entries())
    if (e.name == name) return e.plugin;
  return false;
}

}  // namespace tl::lighting
