#define TINYGLTF_IMPLEMENTATION
#include "gltf_writer.h"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <cstring>
#include <stdexcept>

namespace tl::content {

void Shape::append(const Shape& o) {
  uint32_t base = uint32_t(positions.size());
  positions.insert(positions.end(), o.positions.begin(), o.positions.end());
  normals.insert(normals.end(), o.normals.begin(), o.normals.end());
  uvs.insert(uvs.end(), o.uvs.begin(), o.uvs.end());
  tangents.insert(tangents.end(), o.tangents.begin(), o.tangents.end());
  joints.insert(joints.end(), o.joints.begin(), o.joints.end());
  weights.insert(weights.end(), o.weights.begin(), o.weights.end());
  for (uint32_t i : o.indices) indices.push_back(base + i);
}

Shape& Shape::boundTo(uint32_t joint) {
  joints.assign(positions.size(), glm::uvec4(joint, 0, 0, 0));
  weights.assign(positions.size(), glm::vec4(1.0f, 0.0f, 0.0f, 0.0f));
  return *this;
}

namespace {

// One planar face: origin corner, two edge vectors (u, v), normal = u x v.
void face(Shape& s, glm::vec3 origin, glm::vec3 u, glm::vec3 v, glm::vec2 uvSize) {
  uint32_t base = uint32_t(s.positions.size());
  glm::vec3 n = glm::normalize(glm::cross(u, v));
  const glm::vec2 corners[4] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  for (auto c : corners) {
    s.positions.push_back(origin + u * c.x + v * c.y);
    s.normals.push_back(n);
    s.uvs.push_back(c * uvSize);
  }
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) s.indices.push_back(base + i);
}

}  // namespace

Shape box(glm::vec3 size, float uvScale) {
  Shape s;
  glm::vec3 h = size * 0.5f;
  glm::vec3 X(size.x, 0, 0), Y(0, size.y, 0), Z(0, 0, size.z);
  auto uv = [&](float a, float b) { return glm::vec2(a, b) * uvScale; };
  face(s, {-h.x, -h.y, h.z}, X, Y, uv(size.x, size.y));    // +Z
  face(s, {h.x, -h.y, -h.z}, -X, Y, uv(size.x, size.y));   // -Z
  face(s, {h.x, -h.y, h.z}, -Z, Y, uv(size.z, size.y));    // +X
  face(s, {-h.x, -h.y, -h.z}, Z, Y, uv(size.z, size.y));   // -X
  face(s, {-h.x, h.y, h.z}, X, -Z, uv(size.x, size.z));    // +Y
  face(s, {-h.x, -h.y, -h.z}, X, Z, uv(size.x, size.z));   // -Y
  return s;
}

Shape quad(float width, float depth, float uvScale) {
  Shape s;
  face(s, {-width / 2, 0, depth / 2}, {width, 0, 0}, {0, 0, -depth}, glm::vec2(width, depth) * uvScale);
  return s;
}

Shape cylinder(float radius, float height, int segments) {
  Shape s;
  const float twoPi = 6.28318530718f;
  for (int i = 0; i <= segments; ++i) {
    float a = twoPi * float(i) / float(segments);
    glm::vec3 n(std::cos(a), 0.0f, -std::sin(a));
    for (int k = 0; k < 2; ++k) {
      s.positions.push_back(n * radius + glm::vec3(0, k * height, 0));
      s.normals.push_back(n);
      s.uvs.push_back({float(i) / float(segments) * 2.0f, float(k) * height});
    }
  }
  for (int i = 0; i < segments; ++i) {
    uint32_t a = uint32_t(2 * i), b = a + 2;
    for (uint32_t idx : {a, b, b + 1, a, b + 1, a + 1}) s.indices.push_back(idx);
  }
  // Caps.
  for (int k = 0; k < 2; ++k) {
    uint32_t center = uint32_t(s.positions.size());
    glm::vec3 n(0, k ? 1.0f : -1.0f, 0);
    s.positions.push_back({0, k * height, 0});
    s.normals.push_back(n);
    s.uvs.push_back({0.5f, 0.5f});
    for (int i = 0; i <= segments; ++i) {
      float a = twoPi * float(i) / float(segments);
      s.positions.push_back({std::cos(a) * radius, k * height, -std::sin(a) * radius});
      s.normals.push_back(n);
      s.uvs.push_back({0.5f + 0.5f * std::cos(a), 0.5f + 0.5f * std::sin(a)});
    }
    for (int i = 0; i < segments; ++i) {
      uint32_t a = center + 1 + uint32_t(i), b = a + 1;
      if (k) s.indices.insert(s.indices.end(), {center, a, b});
      else s.indices.insert(s.indices.end(), {center, b, a});
    }
  }
  return s;
}

Shape sphere(float radius, int segments, int rings) {
  Shape s;
  const float pi = 3.14159265359f;
  for (int r = 0; r <= rings; ++r) {
    float theta = pi * float(r) / float(rings);
    for (int i = 0; i <= segments; ++i) {
      float phi = 2.0f * pi * float(i) / float(segments);
      glm::vec3 n(std::sin(theta) * std::cos(phi), std::cos(theta), -std::sin(theta) * std::sin(phi));
      s.positions.push_back(n * radius);
      s.normals.push_back(n);
      s.uvs.push_back({float(i) / float(segments), float(r) / float(rings)});
    }
  }
  for (int r = 0; r < rings; ++r)
    for (int i = 0; i < segments; ++i) {
      uint32_t a = uint32_t(r * (segments + 1) + i), b = a + uint32_t(segments + 1);
      if (r != 0) s.indices.insert(s.indices.end(), {a, b, a + 1});
      if (r != rings - 1) s.indices.insert(s.indices.end(), {a + 1, b, b + 1});
    }
  return s;
}

Shape torus(float major, float minor, int segments, int sides) {
  Shape s;
  const float twoPi = 6.28318530718f;
  for (int i = 0; i <= segments; ++i) {
    float u = twoPi * float(i) / float(segments);
    glm::vec3 dir(std::cos(u), 0.0f, -std::sin(u));
    for (int j = 0; j <= sides; ++j) {
      float v = twoPi * float(j) / float(sides);
      glm::vec3 n = dir * std::cos(v) + glm::vec3(0, std::sin(v), 0);
      s.positions.push_back(dir * major + n * minor);
      s.normals.push_back(n);
      s.uvs.push_back({float(i) / float(segments), float(j) / float(sides)});
    }
  }
  for (int i = 0; i < segments; ++i)
    for (int j = 0; j < sides; ++j) {
      uint32_t a = uint32_t(i * (sides + 1) + j), b = a + uint32_t(sides + 1);
      s.indices.insert(s.indices.end(), {a, b, b + 1, a, b + 1, a + 1});
    }
  return s;
}

Shape transformed(const Shape& s, const glm::mat4& m) {
  Shape out = s;
  glm::mat3 nm = glm::transpose(glm::inverse(glm::mat3(m)));
  for (auto& p : out.positions) p = glm::vec3(m * glm::vec4(p, 1.0f));
  for (auto& n : out.normals) n = glm::normalize(nm * n);
  return out;
}

std::vector<unsigned char> encodeImage(const std::string& extension, int width, int height, int channels,
                                       const std::vector<float>& values, int bits) {
  std::vector<unsigned char> bytes;
  OIIO::Filesystem::IOVecOutput proxy(bytes);
  const std::string name = "memory." + extension;
  auto out = OIIO::ImageOutput::create(name, &proxy);
  const OIIO::TypeDesc type = bits == 8 ? OIIO::TypeDesc::UINT8 : bits == 16 ? OIIO::TypeDesc::UINT16
                              : bits == -16 ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
  OIIO::ImageSpec spec(width, height, channels, type);
  if (!out || !out->open(name, spec) || !out->write_image(OIIO::TypeDesc::FLOAT, values.data()) || !out->close())
    throw std::runtime_error("cannot encode a " + extension + " image: " + OIIO::geterror());
  return bytes;
}

SceneWriter::SceneWriter(std::string name) : name_(std::move(name)) {
  model_.asset.version = "2.0";
  model_.asset.generator = "Twinlight content generator";
}

int SceneWriter::accessor(const void* data, size_t bytes, size_t count, int componentType, int type, int target,
                          const std::vector<double>& min, const std::vector<double>& max) {
  while (bin_.size() % 4) bin_.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bin_.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  bin_.insert(bin_.end(), p, p + bytes);
  model_.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.bufferView = int(model_.bufferViews.size() - 1);
  a.componentType = componentType;
  a.count = count;
  a.type = type;
  a.minValues = min;
  a.maxValues = max;
  model_.accessors.push_back(a);
  return int(model_.accessors.size() - 1);
}

int SceneWriter::material(const MaterialSpec& spec) {
  tinygltf::Material m;
  m.name = spec.name;
  m.pbrMetallicRoughness.baseColorFactor = {spec.baseColor.r, spec.baseColor.g, spec.baseColor.b, spec.alpha};
  m.pbrMetallicRoughness.metallicFactor = spec.metallic;
  m.pbrMetallicRoughness.roughnessFactor = spec.roughness;
  if (glm::length(spec.emissive) > 0.0f) {
    m.emissiveFactor = {spec.emissive.r, spec.emissive.g, spec.emissive.b};
    if (spec.emissiveStrength != 1.0f) {
      tinygltf::Value::Object ext;
      ext["emissiveStrength"] = tinygltf::Value(double(spec.emissiveStrength));
      m.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(ext);
      if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), "KHR_materials_emissive_strength") ==
          model_.extensionsUsed.end())
        model_.extensionsUsed.push_back("KHR_materials_emissive_strength");
    }
  }
  if (spec.baseColorTextureIndex >= 0) {
    auto& info = m.pbrMetallicRoughness.baseColorTexture;
    info.index = spec.baseColorTextureIndex;
    info.texCoord = spec.baseColorUse.texCoord;
    if (spec.baseColorUse.transform) {
      const auto& u = spec.baseColorUse;
      tinygltf::Value::Object t;
      t["offset"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(u.offset.x)), tinygltf::Value(double(u.offset.y))});
      t["rotation"] = tinygltf::Value(double(u.rotation));
      t["scale"] = tinygltf::Value(tinygltf::Value::Array{tinygltf::Value(double(u.scale.x)), tinygltf::Value(double(u.scale.y))});
      if (u.texCoordOverride >= 0) t["texCoord"] = tinygltf::Value(u.texCoordOverride);
      info.extensions["KHR_texture_transform"] = tinygltf::Value(t);
      if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), "KHR_texture_transform") == model_.extensionsUsed.end())
        model_.extensionsUsed.push_back("KHR_texture_transform");
    }
  }
  if (spec.occlusionTextureIndex >= 0) {
    m.occlusionTexture.index = spec.occlusionTextureIndex;
    m.occlusionTexture.strength = spec.occlusionStrength;
  }
  if (spec.emissiveTextureIndex >= 0) m.emissiveTexture.index = spec.emissiveTextureIndex;
  if (spec.metallicRoughnessTextureIndex >= 0)
    m.pbrMetallicRoughness.metallicRoughnessTexture.index = spec.metallicRoughnessTextureIndex;
  if (spec.normalTextureIndex >= 0) m.normalTexture.index = spec.normalTextureIndex;
  if (!spec.alphaMode.empty()) {
    m.alphaMode = spec.alphaMode;
    if (spec.alphaMode == "MASK") m.alphaCutoff = spec.alphaCutoff;
  }
  m.doubleSided = spec.doubleSided;
  auto use = [&](const char* extension) {
    if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), extension) == model_.extensionsUsed.end())
      model_.extensionsUsed.push_back(extension);
  };
  if (spec.ior) {
    tinygltf::Value::Object e;
    e["ior"] = tinygltf::Value(double(*spec.ior));
    m.extensions["KHR_materials_ior"] = tinygltf::Value(e);
    use("KHR_materials_ior");
  }
  if (spec.specularFactor || spec.specularColorFactor) {
    tinygltf::Value::Object e;
    if (spec.specularFactor) e["specularFactor"] = tinygltf::Value(double(*spec.specularFactor));
    if (spec.specularColorFactor) {
      const glm::vec3 c = *spec.specularColorFactor;
      e["specularColorFactor"] = tinygltf::Value(
          tinygltf::Value::Array{tinygltf::Value(double(c.r)), tinygltf::Value(double(c.g)), tinygltf::Value(double(c.b))});
    }
    m.extensions["KHR_materials_specular"] = tinygltf::Value(e);
    use("KHR_materials_specular");
  }
  if (spec.unlit) {
    m.extensions["KHR_materials_unlit"] = tinygltf::Value(tinygltf::Value::Object{});
    use("KHR_materials_unlit");
  }
  if (spec.transmission > 0.0f) {
    tinygltf::Value::Object e;
    e["transmissionFactor"] = tinygltf::Value(double(spec.transmission));
    m.extensions["KHR_materials_transmission"] = tinygltf::Value(e);
    use("KHR_materials_transmission");
  }
  if (spec.clearcoat > 0.0f) {
    tinygltf::Value::Object e;
    e["clearcoatFactor"] = tinygltf::Value(double(spec.clearcoat));
    e["clearcoatRoughnessFactor"] = tinygltf::Value(double(spec.clearcoatRoughness));
    m.extensions["KHR_materials_clearcoat"] = tinygltf::Value(e);
    use("KHR_materials_clearcoat");
  }
  if (spec.thickness > 0.0f) {
    tinygltf::Value::Object e;
    e["thicknessFactor"] = tinygltf::Value(double(spec.thickness));
    const glm::vec3 c = spec.attenuationColor;
    e["attenuationColor"] = tinygltf::Value(tinygltf::Value::Array{
        tinygltf::Value(double(c.r)), tinygltf::Value(double(c.g)), tinygltf::Value(double(c.b))});
    if (spec.attenuationDistance) e["attenuationDistance"] = tinygltf::Value(double(*spec.attenuationDistance));
    m.extensions["KHR_materials_volume"] = tinygltf::Value(e);
    use("KHR_materials_volume");
  }
  if (!spec.baseColorTexture.empty()) {
    tinygltf::Image img;
    img.uri = spec.baseColorTexture;
    img.name = std::filesystem::path(spec.baseColorTexture).stem().string();
    m.pbrMetallicRoughness.baseColorTexture.index = texture(img);
  }
  model_.materials.push_back(m);
  return int(model_.materials.size() - 1);
}

int SceneWriter::embeddedTexture(const std::string& name, const std::vector<unsigned char>& bytes,
                                 const std::string& mimeType) {
  while (bin_.size() % 4) bin_.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = bin_.size();
  view.byteLength = bytes.size();
  bin_.insert(bin_.end(), bytes.begin(), bytes.end());
  model_.bufferViews.push_back(view);
  tinygltf::Image img;
  img.name = name;
  img.mimeType = mimeType;
  img.bufferView = int(model_.bufferViews.size() - 1);
  return texture(img);
}

int SceneWriter::dataUriTexture(const std::string& name, const std::string& uri) {
  tinygltf::Image img;
  img.name = name;
  img.uri = uri;
  return texture(img);
}

int SceneWriter::texture(const tinygltf::Image& img) {
  model_.images.push_back(img);
  if (model_.samplers.empty()) {
    tinygltf::Sampler s;
    s.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
    s.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
    model_.samplers.push_back(s);
  }
  tinygltf::Texture t;
  t.source = int(model_.images.size() - 1);
  t.sampler = 0;
  model_.textures.push_back(t);
  return int(model_.textures.size() - 1);
}

int SceneWriter::sampledTexture(int texture, int magFilter, int minFilter, int wrapS, int wrapT) {
  tinygltf::Sampler s;
  s.magFilter = magFilter;
  s.minFilter = minFilter;
  s.wrapS = wrapS;
  s.wrapT = wrapT;
  size_t k = 0;
  while (k < model_.samplers.size() && !(model_.samplers[k].magFilter == magFilter && model_.samplers[k].minFilter == minFilter &&
                                          model_.samplers[k].wrapS == wrapS && model_.samplers[k].wrapT == wrapT))
    ++k;
  if (k == model_.samplers.size()) model_.samplers.push_back(s);
  tinygltf::Texture t = model_.textures.at(size_t(texture));
  t.sampler = int(k);
  model_.textures.push_back(t);
  return int(model_.textures.size() - 1);
}

int SceneWriter::mesh(const std::string& name, const Shape& shape, int material) {
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (auto& p : shape.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = material;
  prim.attributes["POSITION"] = accessor(shape.positions.data(), shape.positions.size() * 12, shape.positions.size(),
                                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER,
                                         {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
  prim.attributes["NORMAL"] = accessor(shape.normals.data(), shape.normals.size() * 12, shape.normals.size(),
                                       TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
  prim.attributes["TEXCOORD_0"] = accessor(shape.uvs.data(), shape.uvs.size() * 8, shape.uvs.size(),
                                           TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (!shape.tangents.empty())
    prim.attributes["TANGENT"] = accessor(shape.tangents.data(), shape.tangents.size() * 16, shape.tangents.size(),
                                          TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (!shape.joints.empty()) {
    std::vector<uint8_t> j;
    for (const auto& v : shape.joints)
      for (int k = 0; k < 4; ++k) j.push_back(uint8_t(v[k]));
    prim.attributes["JOINTS_0"] = accessor(j.data(), j.size(), shape.joints.size(), TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE,
                                           TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.attributes["WEIGHTS_0"] = accessor(shape.weights.data(), shape.weights.size() * 16, shape.weights.size(),
                                            TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4, TINYGLTF_TARGET_ARRAY_BUFFER);
  }
  if (!shape.uvs1.empty())
    prim.attributes["TEXCOORD_1"] = accessor(shape.uvs1.data(), shape.uvs1.size() * 8, shape.uvs1.size(),
                                             TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, TINYGLTF_TARGET_ARRAY_BUFFER);
  if (!shape.colors.empty()) {
    const size_t n = shape.colors.size();
    int colorAccessor = -1;
    switch (shape.colorType) {
      case Shape::ColorType::FloatVec3: {
        std::vector<glm::vec3> rgb;
        for (const auto& c : shape.colors) rgb.emplace_back(c);
        colorAccessor = accessor(rgb.data(), n * 12, n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
        break;
      }
      case Shape::ColorType::FloatVec4:
        colorAccessor = accessor(shape.colors.data(), n * 16, n, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4,
                                 TINYGLTF_TARGET_ARRAY_BUFFER);
        break;
      case Shape::ColorType::UnormByteVec4: {
        std::vector<uint8_t> b;
        for (const auto& c : shape.colors)
          for (int k = 0; k < 4; ++k) b.push_back(uint8_t(std::lround(glm::clamp(c[k], 0.0f, 1.0f) * 255.0f)));
        colorAccessor = accessor(b.data(), b.size(), n, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4,
                                 TINYGLTF_TARGET_ARRAY_BUFFER);
        model_.accessors[size_t(colorAccessor)].normalized = true;
        break;
      }
      case Shape::ColorType::UnormShortVec4: {
        std::vector<uint16_t> u;
        for (const auto& c : shape.colors)
          for (int k = 0; k < 4; ++k) u.push_back(uint16_t(std::lround(glm::clamp(c[k], 0.0f, 1.0f) * 65535.0f)));
        colorAccessor = accessor(u.data(), u.size() * 2, n, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC4,
                                 TINYGLTF_TARGET_ARRAY_BUFFER);
        model_.accessors[size_t(colorAccessor)].normalized = true;
        break;
      }
    }
    prim.attributes["COLOR_0"] = colorAccessor;
  }
  prim.indices = accessor(shape.indices.data(), shape.indices.size() * 4, shape.indices.size(),
                          TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  tinygltf::Mesh m;
  m.name = name;
  m.primitives.push_back(prim);
  model_.meshes.push_back(m);
  return int(model_.meshes.size() - 1);
}

void SceneWriter::morphTargets(int mesh, const std::vector<std::vector<glm::vec3>>& positionDeltas,
                               const std::vector<std::vector<glm::vec3>>& normalDeltas, const std::vector<double>& weights) {
  auto& prim = model_.meshes[size_t(mesh)].primitives[0];
  for (size_t t = 0; t < positionDeltas.size(); ++t) {
    const auto& p = positionDeltas[t];
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (auto& d : p) lo = glm::min(lo, d), hi = glm::max(hi, d);
    std::map<std::string, int> target;
    target["POSITION"] = accessor(p.data(), p.size() * 12, p.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                  TINYGLTF_TARGET_ARRAY_BUFFER, {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
    const auto& n = normalDeltas[t];
    target["NORMAL"] = accessor(n.data(), n.size() * 12, n.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                                TINYGLTF_TARGET_ARRAY_BUFFER);
    prim.targets.push_back(target);
  }
  model_.meshes[size_t(mesh)].weights = weights;
}

void SceneWriter::weightsChannel(const std::string& animation, int node, const std::vector<float>& times,
                                 const std::vector<float>& weights) {
  auto it = std::find_if(model_.animations.begin(), model_.animations.end(), [&](auto& a) { return a.name == animation; });
  if (it == model_.animations.end()) {
    model_.animations.emplace_back();
    model_.animations.back().name = animation;
    it = std::prev(model_.animations.end());
  }
  tinygltf::AnimationSampler sampler;
  sampler.input = accessor(times.data(), times.size() * 4, times.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 0,
                           {times.front()}, {times.back()});
  sampler.output = accessor(weights.data(), weights.size() * 4, weights.size(), TINYGLTF_COMPONENT_TYPE_FLOAT,
                            TINYGLTF_TYPE_SCALAR, 0);
  sampler.interpolation = "LINEAR";
  it->samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = int(it->samplers.size() - 1);
  channel.target_node = node;
  channel.target_path = "weights";
  it->channels.push_back(channel);
}

void SceneWriter::nodeChannel(const std::string& animation, int node, const std::string& path,
                              const std::vector<float>& times, const std::vector<glm::vec4>& values,
                              const std::string& interpolation) {
  auto it = std::find_if(model_.animations.begin(), model_.animations.end(), [&](auto& a) { return a.name == animation; });
  if (it == model_.animations.end()) {
    model_.animations.emplace_back();
    model_.animations.back().name = animation;
    it = std::prev(model_.animations.end());
  }
  const bool rotation = path == "rotation";
  std::vector<float> packed;
  for (const glm::vec4& v : values)
    for (int c = 0; c < (rotation ? 4 : 3); ++c) packed.push_back(v[c]);
  tinygltf::AnimationSampler sampler;
  sampler.input = accessor(times.data(), times.size() * 4, times.size(), TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 0,
                           {times.front()}, {times.back()});
  sampler.output = accessor(packed.data(), packed.size() * 4, values.size(), TINYGLTF_COMPONENT_TYPE_FLOAT,
                            rotation ? TINYGLTF_TYPE_VEC4 : TINYGLTF_TYPE_VEC3, 0);
  sampler.interpolation = interpolation;
  it->samplers.push_back(sampler);
  tinygltf::AnimationChannel channel;
  channel.sampler = int(it->samplers.size() - 1);
  channel.target_node = node;
  channel.target_path = path;
  it->channels.push_back(channel);
}

int SceneWriter::skin(const std::string& name, const std::vector<int>& joints, const std::vector<glm::mat4>& inverseBind) {
  tinygltf::Skin skin;
  skin.name = name;
  skin.joints = joints;
  skin.inverseBindMatrices = accessor(inverseBind.data(), inverseBind.size() * 64, inverseBind.size(),
                                      TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_MAT4, 0);
  model_.skins.push_back(skin);
  return int(model_.skins.size() - 1);
}

void SceneWriter::skinNode(int node, int skin) { model_.nodes[size_t(node)].skin = skin; }

int SceneWriter::node(const std::string& name, int mesh, glm::vec3 t, glm::vec3 euler, glm::vec3 scale, int parent) {
  tinygltf::Node n;
  n.name = name;
  n.mesh = mesh;
  if (t != glm::vec3(0.0f)) n.translation = {t.x, t.y, t.z};
  if (euler != glm::vec3(0.0f)) {
    glm::quat q = glm::quat(glm::radians(euler));
    n.rotation = {q.x, q.y, q.z, q.w};
  }
  if (scale != glm::vec3(1.0f)) n.scale = {scale.x, scale.y, scale.z};
  model_.nodes.push_back(n);
  const int index = int(model_.nodes.size() - 1);
  if (parent >= 0)
    model_.nodes[size_t(parent)].children.push_back(index);
  else
    roots_.push_back(index);
  return index;
}

void SceneWriter::camera(const std::string& name, glm::vec3 from, glm::vec3 to, float yfovDegrees, double znear) {
  tinygltf::Camera c;
  c.name = name;
  c.type = "perspective";
  c.perspective.yfov = glm::radians(yfovDegrees);
  c.perspective.znear = znear;
  c.perspective.aspectRatio = 16.0 / 9.0;
  addCamera(c, from, to);
}

void SceneWriter::orthographicCamera(const std::string& name, glm::vec3 from, glm::vec3 to, float xmag, float ymag,
                                     float znear, float zfar) {
  tinygltf::Camera c;
  c.name = name;
  c.type = "orthographic";
  c.orthographic.xmag = xmag;
  c.orthographic.ymag = ymag;
  c.orthographic.znear = znear;
  c.orthographic.zfar = zfar;
  addCamera(c, from, to);
}

void SceneWriter::addCamera(const tinygltf::Camera& c, glm::vec3 from, glm::vec3 to) {
  const std::string name = c.name;
  model_.cameras.push_back(c);
  // glTF cameras look down -Z with +Y up.
  glm::mat4 view = glm::lookAt(from, to, glm::vec3(0, 1, 0));
  glm::quat q = glm::quat_cast(glm::inverse(glm::mat3(view)));
  tinygltf::Node n;
  n.name = name;
  n.camera = int(model_.cameras.size() - 1);
  n.translation = {from.x, from.y, from.z};
  n.rotation = {q.x, q.y, q.z, q.w};
  model_.nodes.push_back(n);
  roots_.push_back(int(model_.nodes.size() - 1));
}

void SceneWriter::sun(glm::vec3 travel, float irradiance, glm::vec3 color) {
  tinygltf::Light l;
  l.name = "sun";
  l.type = "directional";
  l.color = {color.r, color.g, color.b};
  l.intensity = double(irradiance) * 683.0;  // lux: Twinlight's irradiance times 683 lm/W
  light(l, glm::vec3(0.0f), travel);
}

void SceneWriter::pointLight(const std::string& name, glm::vec3 position, float candela, glm::vec3 color, float range) {
  tinygltf::Light l;
  l.name = name;
  l.type = "point";
  l.color = {color.r, color.g, color.b};
  l.intensity = candela;
  if (range > 0.0f) l.range = range;
  light(l, position, glm::vec3(0.0f, 0.0f, -1.0f));
}

void SceneWriter::spotLight(const std::string& name, glm::vec3 position, glm::vec3 direction, float candela,
                            float innerDegrees, float outerDegrees, glm::vec3 color) {
  tinygltf::Light l;
  l.name = name;
  l.type = "spot";
  l.color = {color.r, color.g, color.b};
  l.intensity = candela;
  l.spot.innerConeAngle = glm::radians(innerDegrees);
  l.spot.outerConeAngle = glm::radians(outerDegrees);
  light(l, position, direction);
}

void SceneWriter::light(tinygltf::Light l, glm::vec3 position, glm::vec3 direction) {
  const std::string name = l.name;
  model_.lights.push_back(std::move(l));
  if (std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), "KHR_lights_punctual") == model_.extensionsUsed.end())
    model_.extensionsUsed.push_back("KHR_lights_punctual");
  // Lights shine down their node's -Z.
  glm::vec3 d = glm::normalize(direction);
  glm::vec3 up = std::abs(d.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
  glm::quat q = glm::quat_cast(glm::inverse(glm::mat3(glm::lookAt(glm::vec3(0.0f), d, up))));
  tinygltf::Node n;
  n.name = name;
  if (position != glm::vec3(0.0f)) n.translation = {position.x, position.y, position.z};
  n.rotation = {q.x, q.y, q.z, q.w};
  tinygltf::Value::Object ext;
  ext["light"] = tinygltf::Value(int(model_.lights.size() - 1));
  n.extensions["KHR_lights_punctual"] = tinygltf::Value(ext);
  model_.nodes.push_back(n);
  roots_.push_back(int(model_.nodes.size() - 1));
}

void SceneWriter::sky(glm::vec3 radiance) {
  tinygltf::Value::Array a{tinygltf::Value(double(radiance.r)), tinygltf::Value(double(radiance.g)),
                           tinygltf::Value(double(radiance.b))};
  twinlightExtra("sky_radiance", tinygltf::Value(a));
}

void SceneWriter::twinlightExtra(const std::string& key, tinygltf::Value value) {
  tinygltf::Value::Object t;
  if (extras_.count("twinlight")) t = extras_["twinlight"].Get<tinygltf::Value::Object>();
  t[key] = std::move(value);
  extras_["twinlight"] = tinygltf::Value(t);
}

void SceneWriter::write(const std::filesystem::path& dir) {
  tinygltf::Buffer buffer;
  if (!binary_) buffer.uri = name_ + ".bin";
  buffer.data = bin_;
  model_.buffers = {buffer};
  tinygltf::Scene scene;
  scene.name = name_;
  scene.nodes = roots_;
  if (!extras_.empty()) scene.extras = tinygltf::Value(extras_);
  model_.scenes = {scene};
  model_.defaultScene = 0;
  tinygltf::TinyGLTF writer;
  // Images are written by the generator itself (OpenImageIO); tinygltf only records URIs.
  writer.SetImageWriter(
      [](const std::string*, const std::string*, const tinygltf::Image* image, bool, std::string* outUri, void*) {
        *outUri = image->uri;
        return true;
      },
      nullptr);
  auto path = dir / (name_ + (binary_ ? ".glb" : ".gltf"));
  if (!writer.WriteGltfSceneToFile(&model_, path.string(), false, binary_, !binary_, binary_))
    throw std::runtime_error("cannot write " + path.string());
}

}  // namespace tl::content
