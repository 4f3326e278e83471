#include "session/gltf_lights_writer.h"

#include "scene/input_limits.h"
#include "session/image_io.h"
#include "session/session.h"

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/matrix_decompose.hpp>
#include <glm/gtx/quaternion.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <optional>
#include <set>

namespace tl::session {
namespace {

using json = nlohmann::ordered_json;  // keeps the exporter's order of keys
constexpr const char* kExtension = "KHR_lights_punctual";
constexpr uint32_t kGlbMagic = 0x46546C67;      // "glTF"
constexpr uint32_t kChunkJson = 0x4E4F534A;     // "JSON"

[[noreturn]] void fail(const std::filesystem::path& file, const std::string& why) {
  throw SessionError(fmt::format("{}: cannot save the lights into it: {}", file.string(), why));
}

uint32_t readU32(const std::vector<uint8_t>& bytes, size_t at) {
  uint32_t v = 0;
  std::memcpy(&v, bytes.data() + at, 4);
  return v;
}
void appendU32(std::string& out, uint32_t v) { out.append(reinterpret_cast<const char*>(&v), 4); }

// The file as JSON and, for a .glb, everything after its JSON chunk (the binary chunk).
struct GltfFile {
  json document;
  bool binary = false;
  std::string chunksAfterJson;
};

GltfFile readGltf(const std::filesystem::path& file) {
  std::vector<uint8_t> bytes;
  try {
    bytes = scene::readRegularFile(file, scene::InputLimits::kMaxFileBytes);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  }
  GltfFile g;
  std::string_view text(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  if (bytes.size() >= 4 && readU32(bytes, 0) == kGlbMagic) {
    if (bytes.size() < 20) fail(file, "a .glb shorter than its header");
    const uint64_t total = readU32(bytes, 8), jsonLength = readU32(bytes, 12);
    if (total != bytes.size()) fail(file, fmt::format("the .glb header says {} bytes, the file has {}", total, bytes.size()));
    if (readU32(bytes, 16) != kChunkJson || 20 + jsonLength > bytes.size()) fail(file, "its first chunk is not a whole JSON chunk");
    text = text.substr(20, jsonLength);
    g.binary = true;
    g.chunksAfterJson.assign(reinterpret_cast<const char*>(bytes.data()) + 20 + jsonLength, bytes.size() - 20 - jsonLength);
  }
  try {
    scene::requireJsonDepth(text, file.string());
    g.document = json::parse(text);
  } catch (const scene::InputFileError& e) {
    throw SessionError(e.what());
  } catch (const json::exception& e) {
    fail(file, fmt::format("not JSON: {}", e.what()));
  }
  if (!g.document.is_object()) fail(file, "its JSON is not an object");
  return g;
}

std::string serialise(const GltfFile& g) {
  if (!g.binary) return g.document.dump(2) + "\n";
  std::string jsonText = g.document.dump();
  while (jsonText.size() % 4) jsonText += ' ';  // chunks are 4-byte aligned, JSON padded with spaces
  std::string out;
  appendU32(out, kGlbMagic);
  appendU32(out, 2);
  appendU32(out, uint32_t(12 + 8 + jsonText.size() + g.chunksAfterJson.size()));
  appendU32(out, uint32_t(jsonText.size()));
  appendU32(out, kChunkJson);
  out += jsonText;
  out += g.chunksAfterJson;
  return out;
}

glm::dvec3 vec3Of(const json& v, glm::dvec3 fallback) {
  if (!v.is_array() || v.size() != 3) return fallback;
  for (const auto& x : v)
    if (!x.is_number()) return fallback;
  return {v[0].get<double>(), v[1].get<double>(), v[2].get<double>()};
}

// A node's transform relative to its parent, as glTF composes it: matrix, or T * R * S.
glm::dmat4 localMatrix(const json& node) {
  if (node.contains("matrix") && node["matrix"].is_array() && node["matrix"].size() == 16) {
    glm::dmat4 m(1.0);
    for (int i = 0; i < 16; ++i)
      if (node["matrix"][size_t(i)].is_number()) m[i / 4][i % 4] = node["matrix"][size_t(i)].get<double>();
    return m;
  }
  glm::dquat r(1.0, 0.0, 0.0, 0.0);
  if (node.contains("rotation") && node["rotation"].is_array() && node["rotation"].size() == 4) {
    const auto& q = node["rotation"];
    bool numbers = true;
    for (const auto& x : q) numbers = numbers && x.is_number();
    // Normalised as the importer does: exporters round quaternions to a few digits.
    if (numbers) r = glm::normalize(glm::dquat(q[3].get<double>(), q[0].get<double>(), q[1].get<double>(), q[2].get<double>()));
  }
  const glm::dvec3 t = node.contains("translation") ? vec3Of(node["translation"], glm::dvec3(0.0)) : glm::dvec3(0.0);
  const glm::dvec3 s = node.contains("scale") ? vec3Of(node["scale"], glm::dvec3(1.0)) : glm::dvec3(1.0);
  return glm::translate(glm::dmat4(1.0), t) * glm::mat4_cast(r) * glm::scale(glm::dmat4(1.0), s);
}

// The node placing a light at `position` looking along `direction` (lights shine down their -Z).
// A directional light's position lights nothing; it is where the artist put its icon (the
// importer reads it back from the node), so it is kept too.
glm::dmat4 lightWorld(const scene::Light& l) {
  const glm::dvec3 d = glm::normalize(l.direction);
  const glm::dquat q = glm::rotation(glm::dvec3(0.0, 0.0, -1.0), d);
  return glm::translate(glm::dmat4(1.0), l.position) * glm::mat4_cast(q);
}

json lightJson(const scene::Light& l) {
  json o = json::object();
  if (!l.name.empty()) o["name"] = l.name;
  o["type"] = scene::lightTypeName(l.type);  // directional, point or spot: area lights never come here
  o["color"] = json::array({double(l.color.r), double(l.color.g), double(l.color.b)});
  o["intensity"] = double(l.intensity);
  if (l.range && l.type != scene::LightType::Directional) o["range"] = double(*l.range);
  if (l.type == scene::LightType::Spot)
    o["spot"] = json{{"innerConeAngle", double(l.innerConeAngle)}, {"outerConeAngle", double(l.outerConeAngle)}};
  return o;
}

// Writes `local` into the node as translation, rotation and scale (a matrix when it does not
// decompose into them: a sheared parent).
void placeNode(json& node, const glm::dmat4& local) {
  glm::dvec3 scale, translation, skew;
  glm::dvec4 perspective;
  glm::dquat rotation;
  node.erase("matrix");
  node.erase("scale");
  const bool decomposed = glm::decompose(local, scale, rotation, translation, skew, perspective) &&
                          glm::length(skew) < 1e-9 && glm::length(perspective - glm::dvec4(0, 0, 0, 1)) < 1e-9;
  if (!decomposed) {
    node.erase("translation");
    node.erase("rotation");
    json m = json::array();
    for (int i = 0; i < 16; ++i) m.push_back(local[i / 4][i % 4]);
    node["matrix"] = std::move(m);
    return;
  }
  rotation = glm::normalize(rotation);
  node["translation"] = json::array({translation.x, translation.y, translation.z});
  node["rotation"] = json::array({rotation.x, rotation.y, rotation.z, rotation.w});
  if (glm::length(scale - glm::dvec3(1.0)) > 1e-9) node["scale"] = json::array({scale.x, scale.y, scale.z});
}

void eraseExtension(json& holder) {
  if (!holder.contains("extensions") || !holder["extensions"].is_object()) return;
  holder["extensions"].erase(kExtension);
  if (holder["extensions"].empty()) holder.erase("extensions");
}

void listExtension(json& doc, const char* list, bool used) {
  if (!used && !doc.contains(list)) return;
  json& names = doc[list];
  if (!names.is_array()) names = json::array();
  json kept = json::array();
  for (const auto& n : names)
    if (n != kExtension) kept.push_back(n);
  if (used) kept.push_back(kExtension);
  if (kept.empty()) doc.erase(list);
  else names = std::move(kept);
}

// Writes `lights` into the document: the lights array, their nodes, the extension lists.
std::vector<uint32_t> placeLights(json& doc, const std::vector<scene::Light>& lights, const std::filesystem::path& file) {
  if (!doc.contains("nodes")) doc["nodes"] = json::array();
  if (!doc["nodes"].is_array()) fail(file, "`nodes` is not an array");
  // Who is whose parent.
  const size_t nodeCount = doc["nodes"].size();
  std::vector<int64_t> parent(nodeCount, -1);
  for (size_t i = 0; i < nodeCount; ++i) {
    const json& node = doc["nodes"][i];
    if (node.contains("children") && node["children"].is_array())
      for (const auto& c : node["children"])
        if (c.is_number_unsigned() && c.get<uint64_t>() < nodeCount) parent[c.get<size_t>()] = int64_t(i);
  }
  // The scene the lights join: the file's default scene. A file without scenes gets one that
  // holds its roots, as the importer shows them.
  if (!doc.contains("scenes") || !doc["scenes"].is_array() || doc["scenes"].empty()) {
    json roots = json::array();
    for (size_t n = 0; n < nodeCount; ++n)
      if (parent[n] < 0) roots.push_back(n);
    doc["scenes"] = json::array({json{{"nodes", std::move(roots)}}});
    doc["scene"] = 0;
  }
  // No key is added to the document's top level from here until the lights table at the end: an
  // ordered JSON object keeps its members in a vector, so a new key would move `nodes` and
  // `sceneRoots` away under their references.
  json& nodes = doc["nodes"];
  // Which nodes an animation moves.
  std::set<size_t> animated;
  if (doc.contains("animations") && doc["animations"].is_array())
    for (const auto& a : doc["animations"])
      if (a.contains("channels") && a["channels"].is_array())
        for (const auto& c : a["channels"])
          if (c.contains("target") && c["target"].contains("node") && c["target"]["node"].is_number_unsigned())
            animated.insert(c["target"]["node"].get<size_t>());
  const auto parentWorld = [&](size_t n) {
    glm::dmat4 m(1.0);
    // Up the chain to the root; the chain is at most the node count long (a cycle is cut there).
    for (int64_t p = parent[n], steps = 0; p >= 0 && steps < int64_t(nodes.size()); p = parent[size_t(p)], ++steps)
      m = localMatrix(nodes[size_t(p)]) * m;
    return m;
  };
  const auto holdsOnlyALight = [&](size_t n) {
    const json& node = nodes[n];
    const bool hasLight = node.contains("extensions") && node["extensions"].is_object() && node["extensions"].contains(kExtension);
    const bool hasChildren = node.contains("children") && node["children"].is_array() && !node["children"].empty();
    return hasLight && !node.contains("mesh") && !node.contains("camera") && !node.contains("skin") && !hasChildren &&
           !animated.count(n);
  };
  // A node that holds nothing at all: the one an earlier save gave a light that has since been
  // deleted or hidden (it kept its place and lost the light). Placing a light there changes
  // nothing else of the file, and a light that comes back (an undo, a redo) takes its node again
  // instead of the file growing a node each time.
  const auto holdsNothing = [&](size_t n) {
    const json& node = nodes[n];
    const bool hasChildren = node.contains("children") && node["children"].is_array() && !node["children"].empty();
    return !node.contains("extensions") && !node.contains("mesh") && !node.contains("camera") && !node.contains("skin") &&
           !node.contains("extras") && !hasChildren && !animated.count(n);
  };
  std::vector<bool> reusable(nodes.size()), empty(nodes.size());
  for (size_t n = 0; n < nodes.size(); ++n) reusable[n] = holdsOnlyALight(n), empty[n] = holdsNothing(n);
  for (auto& node : nodes) eraseExtension(node);

  size_t sceneIndex = doc.contains("scene") && doc["scene"].is_number_unsigned() ? doc["scene"].get<size_t>() : 0;
  if (sceneIndex >= doc["scenes"].size()) sceneIndex = 0;
  json& scene = doc["scenes"][sceneIndex];
  if (!scene.contains("nodes") || !scene["nodes"].is_array()) scene["nodes"] = json::array();
  json& sceneRoots = scene["nodes"];
  // The importer takes the first directional light it meets (depth first from the roots, in
  // order) as the sun: the first directional light of `lights` has to be met before the others.
  const auto visitOrder = [&] {
    std::vector<size_t> order(nodes.size(), SIZE_MAX);
    size_t next = 0;
    std::vector<size_t> stack;
    for (auto it = sceneRoots.rbegin(); it != sceneRoots.rend(); ++it)
      if (it->is_number_unsigned() && it->get<size_t>() < nodes.size()) stack.push_back(it->get<size_t>());
    while (!stack.empty()) {
      const size_t n = stack.back();
      stack.pop_back();
      if (order[n] != SIZE_MAX) continue;
      order[n] = next++;
      const json& children = nodes[n].contains("children") ? nodes[n]["children"] : json::array();
      for (auto it = children.rbegin(); it != children.rend(); ++it)
        if (it->is_number_unsigned() && it->get<size_t>() < nodes.size()) stack.push_back(it->get<size_t>());
    }
    return order;
  };
  const auto newNode = [&](const scene::Light& l, size_t i, bool first) {
    const size_t n = nodes.size();
    json node = json::object();
    node["name"] = l.name.empty() ? fmt::format("light {}", i) : l.name;
    nodes.push_back(std::move(node));
    parent.push_back(-1);
    if (first) sceneRoots.insert(sceneRoots.begin(), n);
    else sceneRoots.push_back(n);
    return n;
  };

  json table = json::array();
  std::vector<uint32_t> placed;
  size_t sunIndex = SIZE_MAX;
  for (size_t i = 0; i < lights.size(); ++i) {
    const scene::Light& l = lights[i];
    table.push_back(lightJson(l));
    const bool sun = l.type == scene::LightType::Directional && sunIndex == SIZE_MAX;
    if (sun) sunIndex = i;
    // Its own node; else an empty root node of its name (a light saved before without a node of
    // its own now: undone and redone); else a new one.
    std::optional<size_t> own;
    if (l.node && *l.node < reusable.size() && (reusable[*l.node] || empty[*l.node])) own = *l.node;
    for (size_t r = 0; !own && !l.node && r < empty.size(); ++r)
      if (empty[r] && parent[r] < 0 && nodes[r].value("name", json()) == json(l.name) &&
          std::find(sceneRoots.begin(), sceneRoots.end(), json(r)) != sceneRoots.end())
        own = r;
    size_t n = 0;
    if (own) {
      n = *own;
      reusable[n] = empty[n] = false;  // two lights never share a node
    } else {
      n = newNode(l, i, sun);
    }
    placeNode(nodes[n], glm::inverse(parentWorld(n)) * lightWorld(l));
    nodes[n]["extensions"][kExtension] = json{{"light", i}};
    placed.push_back(uint32_t(n));
  }
  if (sunIndex != SIZE_MAX) {
    const std::vector<size_t> order = visitOrder();
    bool first = order[placed[sunIndex]] != SIZE_MAX;
    for (size_t i = 0; i < lights.size(); ++i)
      if (i != sunIndex && lights[i].type == scene::LightType::Directional) first = first && order[placed[sunIndex]] < order[placed[i]];
    if (!first) {  // its own node is met too late: the sun moves to a new first root
      eraseExtension(nodes[placed[sunIndex]]);
      const size_t n = newNode(lights[sunIndex], sunIndex, true);
      placeNode(nodes[n], lightWorld(lights[sunIndex]));
      nodes[n]["extensions"][kExtension] = json{{"light", sunIndex}};
      placed[sunIndex] = uint32_t(n);
    }
  }
  if (lights.empty()) {
    eraseExtension(doc);
  } else {
    doc["extensions"][kExtension]["lights"] = std::move(table);
  }
  listExtension(doc, "extensionsUsed", !lights.empty());
  if (lights.empty()) listExtension(doc, "extensionsRequired", false);
  return placed;
}

}  // namespace

std::vector<uint32_t> writeGltfLights(const std::filesystem::path& file, const std::vector<scene::Light>& lights) {
  for (const auto& l : lights)
    if (scene::isAreaLight(l.type)) fail(file, fmt::format("light `{}` is an area light (glTF has none: the lighting sidecar holds it)", l.name));
  GltfFile g = readGltf(file);
  std::vector<uint32_t> placed;
  try {
    placed = placeLights(g.document, lights, file);
  } catch (const json::exception& e) {  // a value of another type than glTF gives it ("extensions": 3)
    fail(file, fmt::format("its JSON is not shaped as glTF says: {}", e.what()));
  }
  const std::string bytes = serialise(g);
  writeFileAtomically(file, [&](const std::string& tmp) {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
    out.close();
    return bool(out);
  });
  return placed;
}

}  // namespace tl::session
