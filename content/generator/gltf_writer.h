// A small builder over tinygltf for the project's own scenes: meshes from shapes,
// materials, nodes, cameras, the sun and the sky, written as .gltf + .bin. Output is
// deterministic byte for byte (no timestamps, fixed ordering).
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace tl::content {

struct Shape {
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<glm::vec4> tangents;  // optional: written as TANGENT (xyz, w = handedness) when present
  std::vector<glm::vec2> uvs1;      // optional: TEXCOORD_1
  std::vector<glm::vec4> colors;    // optional: COLOR_0, written as colorType below
  // COLOR_0's accessor: FLOAT VEC3 (alpha dropped), FLOAT VEC4, or normalized UNSIGNED_BYTE /
  // UNSIGNED_SHORT VEC4, the forms glTF allows.
  enum class ColorType { FloatVec3, FloatVec4, UnormByteVec4, UnormShortVec4 } colorType = ColorType::FloatVec4;
  // Optional skinning: per vertex four joints (indices into the skin's joint list) and their
  // weights, written as JOINTS_0 (unsigned byte) and WEIGHTS_0 (float).
  std::vector<glm::uvec4> joints;
  std::vector<glm::vec4> weights;
  std::vector<uint32_t> indices;
  void append(const Shape& other);
  // Binds every vertex to one joint with weight 1.
  Shape& boundTo(uint32_t joint);
};

// Shapes in metres, centred as documented per function.
Shape box(glm::vec3 size, float uvScale = 1.0f);                // centred on the origin
Shape quad(float width, float depth, float uvScale = 1.0f);     // in XZ, facing +Y
Shape cylinder(float radius, float height, int segments);       // base at y = 0
Shape sphere(float radius, int segments, int rings);            // centred
Shape torus(float major, float minor, int segments, int sides); // in XZ, centred
Shape transformed(const Shape& s, const glm::mat4& m);

// A textureInfo's UV set and KHR_texture_transform (written only when `transform` is set;
// texCoordOverride >= 0 becomes the extension's texCoord).
struct TextureUse {
  int texCoord = 0;
  bool transform = false;
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};
  int texCoordOverride = -1;
};

struct MaterialSpec {
  std::string name;
  glm::vec3 baseColor{0.8f};
  float metallic = 0.0f;
  float roughness = 0.8f;
  glm::vec3 emissive{0.0f};
  float emissiveStrength = 1.0f;
  std::string baseColorTexture;  // uri relative to the .gltf
  // Textures made with SceneWriter::embeddedTexture (-1: none).
  int baseColorTextureIndex = -1;
  int emissiveTextureIndex = -1;
  int normalTextureIndex = -1;
  int occlusionTextureIndex = -1;
  int metallicRoughnessTextureIndex = -1;
  float occlusionStrength = 1.0f;
  TextureUse baseColorUse;       // the base-colour texture's UV set and transform
  std::string alphaMode;         // "" (OPAQUE), "MASK" or "BLEND"
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  float alpha = 1.0f;            // baseColorFactor's alpha (coverage under MASK and BLEND)
  // KHR_materials_ior and KHR_materials_specular, written when set; KHR_materials_unlit when true.
  std::optional<float> ior;
  std::optional<float> specularFactor;
  std::optional<glm::vec3> specularColorFactor;
  bool unlit = false;
  // KHR_materials_transmission (written when above 0) and KHR_materials_volume (written when the
  // thickness is above 0): attenuationColor left after attenuationDistance.
  float transmission = 0.0f;
  float thickness = 0.0f;
  float clearcoat = 0.0f;  // KHR_materials_clearcoat, written when above 0
  float clearcoatRoughness = 0.0f;
  glm::vec3 attenuationColor{1.0f};
  std::optional<float> attenuationDistance;
};

// An image file's bytes encoded in memory by OpenImageIO (`extension`: "png", "exr", ...):
// `channels` interleaved values per texel, written as `type` (UINT8, UINT16, HALF, FLOAT).
std::vector<unsigned char> encodeImage(const std::string& extension, int width, int height, int channels,
                                       const std::vector<float>& values, int bits);

class SceneWriter {
 public:
  explicit SceneWriter(std::string name);
  int material(const MaterialSpec& spec);
  // An image stored in the binary buffer (a bufferView, as exporters write .glb textures)
  // and a texture sampling it; returns the texture's index for MaterialSpec.
  int embeddedTexture(const std::string& name, const std::vector<unsigned char>& bytes, const std::string& mimeType);
  // An image given as a data: URI (base64 in the JSON) and a texture sampling it.
  int dataUriTexture(const std::string& name, const std::string& uri);
  // A texture with the same image as `texture` and its own sampler (glTF's GL enums; the
  // writer keeps one sampler per distinct set of values).
  int sampledTexture(int texture, int magFilter, int minFilter, int wrapS, int wrapT);
  // Writes a single .glb (JSON, buffer and embedded images in one file) instead of .gltf + .bin.
  void binary() { binary_ = true; }
  int mesh(const std::string& name, const Shape& shape, int material);
  // Morph targets of a mesh written by mesh(): per target, position and normal deltas (one
  // per vertex), and the mesh's default weights.
  void morphTargets(int mesh, const std::vector<std::vector<glm::vec3>>& positionDeltas,
                    const std::vector<std::vector<glm::vec3>>& normalDeltas, const std::vector<double>& weights);
  // A LINEAR channel of morph weights for `node` in the animation called `animation`
  // (created on first use): per key, one weight per target.
  void weightsChannel(const std::string& animation, int node, const std::vector<float>& times,
                      const std::vector<float>& weights);
  // A skin over `joints` (node indices) with their inverse bind matrices; returns its index.
  int skin(const std::string& name, const std::vector<int>& joints, const std::vector<glm::mat4>& inverseBind);
  // Gives node `node`, which holds a mesh with joints, the skin `skin`.
  void skinNode(int node, int skin);
  // Returns the node's index. A root of the scene, or a child of node `parent` (>= 0), whose
  // transform it then follows. `mesh` -1: a node without a mesh (a hinge, a pivot).
  int node(const std::string& name, int mesh, glm::vec3 translation, glm::vec3 eulerDegrees = glm::vec3(0.0f),
            glm::vec3 scale = glm::vec3(1.0f), int parent = -1);
  // A channel of `node`'s "translation", "rotation" (values: quaternions x, y, z, w) or
  // "scale" (x, y, z; w unused) in the animation called `animation`, LINEAR or STEP.
  void nodeChannel(const std::string& animation, int node, const std::string& path, const std::vector<float>& times,
                   const std::vector<glm::vec4>& values, const std::string& interpolation = "LINEAR");
  // znear: glTF's near plane in metres (the project's own scenes keep 5 cm).
  void camera(const std::string& name, glm::vec3 from, glm::vec3 to, float yfovDegrees, double znear = 0.05);
  // glTF's orthographic camera: xmag and ymag are half the view's width and height in metres.
  void orthographicCamera(const std::string& name, glm::vec3 from, glm::vec3 to, float xmag, float ymag, float znear,
                          float zfar);
  // The sun's irradiance on Twinlight's scale (white Lambertian facing it: E / pi), written as
  // glTF's lux: E x 683 lm/W (shaders/shared/lights.h).
  void sun(glm::vec3 travelDirection, float irradiance, glm::vec3 color = glm::vec3(1.0f));
  // KHR_lights_punctual point and spot lights, in candela; range 0: unlimited. A spot shines
  // along `direction` with cone half-angles in degrees.
  void pointLight(const std::string& name, glm::vec3 position, float candela, glm::vec3 color = glm::vec3(1.0f),
                  float range = 0.0f);
  void spotLight(const std::string& name, glm::vec3 position, glm::vec3 direction, float candela, float innerDegrees,
                 float outerDegrees, glm::vec3 color = glm::vec3(1.0f));
  void sky(glm::vec3 radiance);
  // A value in the scene's extras.twinlight object (beside sky_radiance).
  void twinlightExtra(const std::string& key, tinygltf::Value value);
  void write(const std::filesystem::path& dir);

 private:
  // Adds the camera and a root node holding it at `from`, looking at `to` (+Y up).
  void addCamera(const tinygltf::Camera& camera, glm::vec3 from, glm::vec3 to);
  // Adds the light and a root node holding it, turned so its -Z is `direction`.
  void light(tinygltf::Light l, glm::vec3 position, glm::vec3 direction);
  int accessor(const void* data, size_t bytes, size_t count, int componentType, int type, int target,
               const std::vector<double>& min = {}, const std::vector<double>& max = {});
  int texture(const tinygltf::Image& image);
  std::string name_;
  tinygltf::Model model_;
  std::vector<unsigned char> bin_;
  std::vector<int> roots_;
  tinygltf::Value::Object extras_;
  bool binary_ = false;
};

}  // namespace tl::content
