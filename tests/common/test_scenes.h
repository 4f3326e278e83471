// Small scenes built in memory for tests that need exact, known content.
#pragma once

#include "scene/scene.h"

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace tl::test {

// The instance called `name` (the node's name); throws when there is none.
inline const scene::Instance& instanceNamed(const scene::Scene& s, const std::string& name) {
  for (const auto& i : s.instances)
    if (i.name == name) return i;
  throw std::runtime_error("no instance " + name);
}

// Its id in the G-buffer (gbuffer.instanceId: index + 1).
inline uint32_t instanceIdOf(const scene::Scene& s, const std::string& name) {
  return uint32_t(&instanceNamed(s, name) - s.instances.data()) + 1;
}

// An axis-aligned cube of side `size` centred at `centre`, every face UV-mapped 0..1, one
// instance, with material `material`.
inline std::unique_ptr<scene::Scene> makeCubeScene(const scene::Material& material, float size = 1.0f,
                                                    glm::vec3 centre = glm::vec3(0.0f)) {
  auto s = std::make_unique<scene::Scene>();
  s->name = "cube";
  s->materials.push_back(material);
  scene::Mesh mesh;
  mesh.name = "cube";
  const float h = 0.5f * size;
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2) {
      glm::vec3 n(0.0f), u(0.0f), v(0.0f);
      n[axis] = float(sign);
      u[(axis + 1) % 3] = h;
      v[(axis + 2) % 3] = h;
      const uint32_t base = uint32_t(mesh.vertices.size());
      for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        scene::Vertex vtx;
        vtx.position = centre + n * h + u * c.x + v * c.y;
        vtx.normal = n;
        vtx.uv = c * 0.5f + 0.5f;
        mesh.vertices.push_back(vtx);
      }
      mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    }
  for (auto& vtx : mesh.vertices) mesh.bounds.extend(glm::dvec3(vtx.position));
  s->meshes.push_back(mesh);
  scene::Instance inst;
  inst.name = "cube";
  inst.worldBounds = mesh.bounds;
  s->instances.push_back(inst);
  s->bounds = mesh.bounds;
  return s;
}

// Axis-aligned solid boxes (each one mesh and one instance, faces pointing out), all with
// `material`: walls with a thickness, for rooms whose walls are thicker than a voxel.
struct SolidBox {
  glm::vec3 min, max;
};
inline std::unique_ptr<scene::Scene> makeBoxesScene(const scene::Material& material, const std::vector<SolidBox>& boxes) {
  auto s = std::make_unique<scene::Scene>();
  s->name = "boxes";
  s->materials.push_back(material);
  for (size_t b = 0; b < boxes.size(); ++b) {
    const glm::vec3 centre = 0.5f * (boxes[b].min + boxes[b].max), half = 0.5f * (boxes[b].max - boxes[b].min);
    scene::Mesh mesh;
    mesh.name = "box" + std::to_string(b);
    for (int axis = 0; axis < 3; ++axis)
      for (int sign = -1; sign <= 1; sign += 2) {
        glm::vec3 n(0.0f), u(0.0f), v(0.0f);
        n[axis] = float(sign);
        // u x v = n, so the triangles wind counter-clockwise seen from outside.
        u[(axis + 1) % 3] = half[(axis + 1) % 3] * float(sign);
        v[(axis + 2) % 3] = half[(axis + 2) % 3];
        const uint32_t base = uint32_t(mesh.vertices.size());
        for (glm::vec2 c : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
          scene::Vertex vtx;
          vtx.position = centre + n * half + u * c.x + v * c.y;
          vtx.normal = n;
          vtx.uv = c * 0.5f + 0.5f;
          mesh.vertices.push_back(vtx);
        }
        mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
      }
    for (auto& vtx : mesh.vertices) mesh.bounds.extend(glm::dvec3(vtx.position));
    scene::Instance inst;
    inst.name = mesh.name;
    inst.mesh = uint32_t(b);
    inst.worldBounds = mesh.bounds;
    s->bounds.extend(mesh.bounds.min);
    s->bounds.extend(mesh.bounds.max);
    s->meshes.push_back(std::move(mesh));
    s->instances.push_back(inst);
  }
  return s;
}

// A `cells` x `cells` checkerboard of two sRGB-encoded colours, `texels` per side.
inline scene::Texture makeCheckerTexture(uint32_t texels, uint32_t cells, glm::u8vec3 a, glm::u8vec3 b) {
  scene::Texture t;
  t.name = "checker";
  t.width = t.height = texels;
  t.rgba8.resize(size_t(texels) * texels * 4);
  for (uint32_t y = 0; y < texels; ++y)
    for (uint32_t x = 0; x < texels; ++x) {
      const bool odd = ((x * cells / texels) + (y * cells / texels)) % 2;
      const glm::u8vec3 c = odd ? b : a;
      uint8_t* p = &t.rgba8[(size_t(y) * texels + x) * 4];
      p[0] = c.r, p[1] = c.g, p[2] = c.b, p[3] = 255;
    }
  t.contentHash = scene::hashBytes(t.rgba8.data(), t.rgba8.size(), texels);
  return t;
}

}  // namespace tl::test
