// The scene model: what a glTF file becomes on the CPU. Everything here is plain data;
// gpu_scene.h uploads it. Positions and transforms are double where they are world-space
// so scenes far from the origin stay exact until the camera-relative subtraction.
#pragma once

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace tl::scene {

// One interleaved vertex; attribute locations in shaders/shared/scene.h.
struct Vertex {
  glm::vec3 position{0.0f};
  glm::vec3 normal{0.0f, 1.0f, 0.0f};
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w handedness (+1/-1)
  glm::vec2 uv{0.0f};                        // TEXCOORD_0
  glm::vec2 uv1{0.0f};                       // TEXCOORD_1 (zeros when the file has none)
  glm::vec4 color{1.0f};                     // COLOR_0, linear RGBA (white when the file has none)
};
static_assert(sizeof(Vertex) == 72);

struct Bounds {
  glm::dvec3 min{std::numeric_limits<double>::max()};
  glm::dvec3 max{std::numeric_limits<double>::lowest()};
  bool valid() const { return min.x <= max.x && min.y <= max.y && min.z <= max.z; }
  void extend(const glm::dvec3& p) { min = glm::min(min, p); max = glm::max(max, p); }
  void extend(const Bounds& b) { if (b.valid()) { extend(b.min); extend(b.max); } }
  glm::dvec3 center() const { return (min + max) * 0.5; }
  glm::dvec3 size() const { return max - min; }
  // Corner i (0..7): bit 0 picks max.x, bit 1 max.y, bit 2 max.z.
  glm::dvec3 corner(int i) const {
    return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
  }
};

// How a texture's texels are stored, on the CPU and on the GPU alike:
// - Rgba8: 8 bits per channel as in the file (`rgba8`); the sampler decodes sRGB where `srgb`.
// - Rgba16Unorm: 16 bits per channel (`rgba16`), linear data from a 16-bit file (normal,
//   metallic-roughness, occlusion maps): R16G16B16A16_UNORM.
// - Rgba16Float: half floats (`rgba16`, IEEE binary16 bits), already linear: float images
//   (EXR, HDR) and 16-bit sRGB colour, decoded on the CPU because Vulkan has no 16-bit sRGB
//   format (a 16-bit emissive of 128/65535 is 1.5e-4 linear, which 8 bits would cut to 0).
enum class TexelFormat : uint8_t { Rgba8, Rgba16Unorm, Rgba16Float };

// Where a texture's image came from (what `twinlight info --scene` reports).
enum class ImageSource : uint8_t { File, DataUri, BufferView, Generated };

// A glTF sampler: wrap per axis and filters (glTF's GL enums resolved).
enum class Wrap : uint8_t { Repeat, ClampToEdge, MirroredRepeat };
struct SamplerMode {
  Wrap wrapS = Wrap::Repeat;
  Wrap wrapT = Wrap::Repeat;
  bool magNearest = false;     // magFilter NEAREST (else LINEAR)
  bool minNearest = false;     // minFilter NEAREST_* (else LINEAR_*)
  bool mipNearest = false;     // minFilter *_MIPMAP_NEAREST
  bool noMipmaps = false;      // minFilter NEAREST or LINEAR: the finest level only
  bool operator==(const SamplerMode&) const = default;
};

struct Texture {
  std::string name;
  SamplerMode sampler;           // how materials sample it (one entry per glTF texture)
  std::filesystem::path path;    // empty for embedded images
  uint32_t width = 0;
  uint32_t height = 0;
  TexelFormat format = TexelFormat::Rgba8;
  std::vector<uint8_t> rgba8;    // width * height * 4 (Rgba8)
  std::vector<uint16_t> rgba16;  // width * height * 4 (Rgba16Unorm, Rgba16Float)
  bool srgb = true;              // the material reads it as colour (decoded as sRGB unless Rgba16Float)
  bool placeholder = false;      // the file was missing or unreadable: a magenta checker
  ImageSource source = ImageSource::Generated;
  std::string fileFormat;        // the decoder's name for the image's format ("png", "openexr", ...)
  int fileBits = 8;              // bits per channel in the file (8, 16, 32 for float)
  uint64_t contentHash = 0;      // xxHash64 of the decoded texels + size (not of the file name)
};

// Texel i (0 .. width*height-1) as the shader sees it before sRGB decoding: 0..1 for
// normalized formats, the stored value for floats.
glm::vec4 texelValue(const Texture& t, size_t i);

enum class AlphaMode : uint8_t { Opaque, Mask, Blend };

// A texture a material reads: the texture, its UV set and its KHR_texture_transform
// (uv' = T(offset) R(rotation) S(scale) uv, rotation counter-clockwise in radians).
struct TextureRef {
  uint32_t texture = 0;       // index into Scene::textures
  uint32_t texCoord = 0;      // 0: TEXCOORD_0, 1: TEXCOORD_1
  glm::vec2 offset{0.0f};
  float rotation = 0.0f;
  glm::vec2 scale{1.0f};
  bool operator==(const TextureRef&) const = default;
};

struct Material {
  std::string name;
  glm::vec4 baseColorFactor{1.0f};
  float metallic = 1.0f;
  float roughness = 1.0f;
  glm::vec3 emissiveFactor{0.0f};
  float emissiveStrength = 1.0f;  // KHR_materials_emissive_strength
  float normalScale = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  float occlusionStrength = 1.0f;
  std::optional<TextureRef> baseColorTexture;
  std::optional<TextureRef> normalTexture;
  std::optional<TextureRef> metallicRoughnessTexture;
  std::optional<TextureRef> emissiveTexture;
  std::optional<TextureRef> occlusionTexture;
  // KHR_materials_ior and KHR_materials_specular: the dielectric's Fresnel, F0 = min(((ior - 1) /
  // (ior + 1))^2 specularColor, 1) specular and F90 = specular (shared/scene.h tlDielectricFresnel).
  float ior = 1.5f;
  float specularFactor = 1.0f;
  glm::vec3 specularColorFactor{1.0f};
  std::optional<TextureRef> specularTexture;       // its alpha scales specularFactor
  std::optional<TextureRef> specularColorTexture;  // its rgb (sRGB) scales specularColorFactor
  bool unlit = false;                              // KHR_materials_unlit: shows its base colour, reflects nothing
  // KHR_materials_transmission: the share of the dielectric's diffuse layer that passes through
  // the surface instead (factor x texture red); KHR_materials_volume: a thickness above 0 makes
  // the mesh the boundary of a volume that absorbs by Beer-Lambert, attenuationColor left after
  // attenuationDistance (metres of the file; infinite: clear). How each path renders them:
  // shared/shading.h and docs/user-guide.md "What of glTF 2.0 renders".
  float transmission = 0.0f;
  std::optional<TextureRef> transmissionTexture;  // its red channel scales the factor
  float thickness = 0.0f;
  glm::vec3 attenuationColor{1.0f};
  float attenuationDistance = std::numeric_limits<float>::infinity();
  bool transmits() const { return transmission > 0.0f && !unlit; }
  // KHR_materials_clearcoat: a clear coat of this factor and roughness over the surface (the
  // factors; its textures and normal are not read: a line of the scene report).
  float clearcoat = 0.0f;
  float clearcoatRoughness = 0.0f;
  bool clearcoatTexturesUnread = false;
  // KHR_materials_pbrSpecularGlossiness, converted on import to the fields above: how far glTF's
  // reference shading of the result is from the file's (the larger of the F0 and the diffuse
  // colour's largest difference; -1: not converted), and whether a specularGlossinessTexture
  // was left unread (the factors' conversion holds across the surface).
  float specularGlossinessError = -1.0f;
  bool specularGlossinessTextureUnread = false;
  uint64_t contentHash = 0;  // parameters + the content hashes of the textures it uses
};

// A glTF morph target: per-vertex displacements added with a weight.
struct MorphTarget {
  std::vector<glm::vec3> positions;  // deltas, one per vertex
  std::vector<glm::vec3> normals;    // deltas, one per vertex (zeros when the file has none)
};

// One glTF primitive (triangles). A glTF mesh with several primitives becomes several
// Meshes named "<mesh>" , "<mesh>#1", ... each with its own material. A mesh with morph
// targets deforms; it has exactly one instance (the importer gives every node that uses one
// its own copy), so its vertices can follow that node's weights.
struct Mesh {
  std::string name;
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;  // triangle list
  uint32_t material = 0;          // index into Scene::materials (a default material exists)
  Bounds bounds;                  // object space
  bool generatedTangents = false;
  uint64_t contentHash = 0;       // xxHash64 of vertices + indices
  std::vector<MorphTarget> morphTargets;
  std::vector<float> morphWeights;  // the pose without animation (node weights, else the mesh's)
  // Skinning (JOINTS_0 / WEIGHTS_0): per vertex four joints (indices into the skin's list) and
  // their weights (summing to 1); `skin` the node's skin (Scene::skins), -1 for a mesh drawn as
  // stored. Like a morphing mesh, a skinned one has exactly one instance.
  std::vector<glm::u16vec4> joints;
  std::vector<glm::vec4> weights;
  int32_t skin = -1;
  bool skinned() const { return skin >= 0; }
  bool deforms() const { return !morphTargets.empty() || skinned(); }
};

// A glTF skin: the nodes that are its joints, and per joint the inverse bind matrix that takes
// the mesh's bind-pose space to the joint's (identity where the file gives none).
struct Skin {
  std::string name;
  std::vector<uint32_t> joints;  // indices into Scene::nodes
  std::vector<glm::dmat4> inverseBind;
};

// A glTF animation channel of morph weights, resolved to the mesh it deforms: keyframe times
// (seconds, increasing) and, per key, one weight per target.
struct MorphAnimation {
  uint32_t mesh = 0;
  std::vector<float> times;
  std::vector<float> weights;  // times.size() x mesh's target count
  bool step = false;           // STEP interpolation (else LINEAR)
};

// A glTF node as animation needs it: its parent and its local transform, as TRS (the pose
// without animation) or as the matrix the file gives (glTF never animates a matrix node).
struct Node {
  std::string name;
  int32_t parent = -1;  // index into Scene::nodes; -1: a root
  glm::dvec3 translation{0.0};
  glm::dquat rotation{1.0, 0.0, 0.0, 0.0};
  glm::dvec3 scale{1.0};
  std::optional<glm::dmat4> matrix;
};

// A glTF animation channel of a node's translation, rotation or scale: keyframe times
// (seconds, increasing) and per key the value (xyz, or a rotation's quaternion as x, y, z, w).
// CUBICSPLINE keys hold three values each: in-tangent, value, out-tangent.
enum class NodeProperty : uint8_t { Translation, Rotation, Scale };
enum class Interpolation : uint8_t { Linear, Step, CubicSpline };
struct NodeAnimation {
  uint32_t node = 0;  // index into Scene::nodes
  NodeProperty property = NodeProperty::Translation;
  Interpolation interpolation = Interpolation::Linear;
  std::vector<float> times;
  std::vector<glm::dvec4> values;  // times.size() values, or 3 x that for CUBICSPLINE
};

struct Instance {
  std::string name;       // the node's name (or "node<i>")
  uint32_t mesh = 0;      // index into Scene::meshes
  uint32_t node = 0;      // glTF node index (= index into Scene::nodes)
  glm::dmat4 transform{1.0};  // object -> world (at the animation time the session last posed)
  Bounds worldBounds;
};

struct Camera {
  std::string name;
  glm::dvec3 position{0.0};
  glm::dquat orientation{1.0, 0.0, 0.0, 0.0};  // glTF: looks down -Z, +Y up
  float yfovRadians = 0.8f;
  float znear = 0.05f;
  std::optional<float> zfar;  // an orthographic camera always has one
  std::optional<float> aspectRatio;
  // glTF's orthographic camera: half the view's width and height in metres (xmag, ymag).
  bool orthographic = false;
  float xmag = 1.0f, ymag = 1.0f;
};

// Rect, Disk and Tube are area lights: glTF has none (KHR_lights_punctual), so they come only
// from the lighting sidecar (session/lighting_file.h) and are never written into a glTF.
enum class LightType : uint8_t { Directional, Point, Spot, Rect, Disk, Tube };
inline bool isAreaLight(LightType t) { return t == LightType::Rect || t == LightType::Disk || t == LightType::Tube; }
// The name KHR_lights_punctual and the lighting file give a kind of light (the editor shows it too).
inline const char* lightTypeName(LightType t) {
  switch (t) {
    case LightType::Directional: return "directional";
    case LightType::Spot: return "spot";
    case LightType::Rect: return "rect";
    case LightType::Disk: return "disk";
    case LightType::Tube: return "tube";
    case LightType::Point: break;
  }
  return "point";
}

// KHR_lights_punctual, in its units: directional intensity is illuminance in lux, point and spot
// intensity is luminous intensity in candela. Twinlight shades them on its radiometric scale,
// the photometric value divided by kLumensPerWatt (shaders/shared/lights.h states the
// convention): radiometric() gives that. An area light's intensity is its radiance in nits
// (cd/m^2), the same on both faces of a two-sided one (shared/area_lights.h).
inline constexpr double kLumensPerWatt = 683.0;
struct Light {
  std::string name;
  LightType type = LightType::Point;
  glm::vec3 color{1.0f};
  float intensity = 1.0f;                // lux (directional), candela (point, spot) or nits (area)
  std::optional<float> range;            // metres; empty: unlimited
  float innerConeAngle = 0.0f;           // spot, radians, 0 <= inner < outer
  float outerConeAngle = 0.7853982f;     // spot, radians, <= pi/2
  glm::dvec3 position{0.0};
  glm::dvec3 direction{0.0, 0.0, -1.0};  // the direction the light travels (area: the front normal; a tube's axis)
  // Area lights (metres): a rectangle's width (along widthAxis) and height, a disk's or tube's
  // radius, a tube's length; a rectangle or disk emits from its front face only unless twoSided.
  float width = 1.0f, height = 1.0f, radius = 0.1f, length = 1.0f;
  bool twoSided = false;
  glm::dvec3 widthAxis{1.0, 0.0, 0.0};   // projected perpendicular to direction (any other way if parallel)
  // Hidden by the artist (the editor's outliner): kept, saved, not shaded. The lighting file
  // keeps it; a glTF does not hold hidden lights (KHR_lights_punctual has no such flag).
  bool hidden = false;
  // The glTF node the light came from (or was last saved to): saving the lights back into the
  // file moves that node rather than adding one (session/gltf_lights_writer.h).
  std::optional<uint32_t> node;
  // Irradiance E (directional), intensity I (point, spot) or radiance L (area) on Twinlight's
  // scale, per channel.
  glm::vec3 radiometric() const { return color * float(double(intensity) / kLumensPerWatt); }
};

// Lighting environment. The sun is the scene's first directional light (its illuminance on
// Twinlight's scale: lux / kLumensPerWatt); the sky comes from the scene's extras
// {"twinlight": {"sky_radiance": [r,g,b]}}; defaults when absent.
struct Environment {
  glm::dvec3 sunDirection = glm::normalize(glm::dvec3(-0.4, -1.0, -0.3));  // travel direction
  glm::vec3 sunIrradiance{20.0f};  // E, W/m^2-like units: white Lambertian facing it has radiance E/pi
  glm::vec3 skyRadiance{1.0f};     // uniform sky radiance L
  bool sunFromFile = false;
  std::optional<size_t> sunLight;  // which of Scene::lights is the sun (the others are shaded from the light table)
};

struct Scene {
  std::string name;                 // file stem
  std::filesystem::path path;
  std::vector<Texture> textures;
  std::vector<Material> materials;  // never empty: index 0 may be the default material
  std::vector<Mesh> meshes;
  std::vector<Instance> instances;
  std::vector<Camera> cameras;
  std::vector<Light> lights;        // every KHR_lights_punctual light, the sun (Environment::sunLight) included
  Environment environment;
  std::vector<MorphAnimation> morphAnimations;
  std::vector<Node> nodes;                   // every glTF node, in the file's order
  std::vector<Skin> skins;
  std::vector<NodeAnimation> nodeAnimations;  // TRS channels of nodes that place instances
  double animationSeconds = 0.0;    // the longest channel: animations loop over it
  Bounds bounds;                    // world bounds of all instances (every animated pose's keys included)
  std::vector<std::string> warnings;  // e.g. missing texture (placeholder used), an ignored feature
  // Every feature of the file Twinlight ignores or approximates, one line each ("feature: what
  // happens instead"); each also gave one warning. Empty when everything the file uses renders.
  std::vector<std::string> ignored;
  std::vector<std::string> extensionsUsed;  // as the file lists them
  uint64_t contentHash = 0;         // hash of all meshes, materials, instances, environment
};

// One clear error naming the file and what is wrong with it.
struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct LoadOptions {
  // Buffers and images a glTF names may lie outside the glTF's folder (`../`, absolute
  // paths, symbolic links leading out). Off: a downloaded scene reads nothing but its own files.
  bool allowOutsideFolder = false;
};

// Loads .gltf or .glb under the limits of scene/input_limits.h. Throws SceneError for a file
// that cannot be used; a missing texture is a warning (Scene::warnings) and a visible
// placeholder.
Scene loadGltf(const std::filesystem::path& file, const LoadOptions& options = {});

// What a loaded scene holds and what of its file Twinlight ignores, one line each, for
// `twinlight info --scene` and the editor: counts of meshes, materials, textures by format and
// source, lights by type, cameras, animations, extensions, then one "ignored: ..." line per
// ignored or approximated feature.
std::vector<std::string> sceneReport(const Scene& scene);

// xxHash64 helpers (seed 0) shared by the importer and, later, the albedo keys.
uint64_t hashBytes(const void* data, size_t size, uint64_t seed = 0);

}  // namespace tl::scene
