// glTF features an artist's export uses, one probe each: images from every source glTF
// allows (a file, a data: URI, a .glb bufferView) at 8 and 16 bits and as floats, kept in a
// precision that holds their values; tangents generated the way MikkTSpace and the exporters
// write them, and supplied ones used as given.
#include "../common/temp_dir.h"
#include "scene/scene.h"
#include "scene/scene_internal.h"
#include "shared/color.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <iterator>
#include <utility>

namespace tl::scene {
namespace {

using tl::test::contentFile;
using tl::test::TempDir;

namespace fs = std::filesystem;



const Material& material(const Scene& s, const std::string& name) {
  for (auto& m : s.materials)
    if (m.name == name) return m;
  throw std::runtime_error("no material " + name);
}

const Mesh& mesh(const Scene& s, const std::string& name) {
  for (auto& m : s.meshes)
    if (m.name == name) return m;
  throw std::runtime_error("no mesh " + name);
}

void writeImage(const fs::path& file, int channels, const std::vector<float>& values, OIIO::TypeDesc type) {
  auto out = OIIO::ImageOutput::create(file.string());
  OIIO::ImageSpec spec(2, 2, channels, type);
  spec.attribute("oiio:UnassociatedAlpha", 1);  // colour written as given, as glTF exporters do
  ASSERT_TRUE(out && out->open(file.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close())
      << OIIO::geterror();
}

// One triangle with UVs whose material samples `images` (uris) as emissive, normal and
// base colour textures, in that order, as far as given.
void writeTexturedTriangle(const fs::path& file, const std::vector<std::string>& images) {
  const std::array<float, 15> data = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
  std::ofstream(file.parent_path() / "t.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(data.data()), sizeof data);
  nlohmann::json j = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"uri", "t.bin"}, {"byteLength", 60}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}}, {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
      {"meshes", {{{"name", "tri"}, {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}, {"material", 0}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  nlohmann::json material = {{"name", "m"}, {"emissiveFactor", {1, 1, 1}}};
  const char* slots[] = {"emissiveTexture", "normalTexture", "baseColorTexture"};
  for (size_t i = 0; i < images.size(); ++i) {
    j["images"].push_back({{"uri", images[i]}});
    j["textures"].push_back({{"source", i}});
    if (i == 2) material["pbrMetallicRoughness"]["baseColorTexture"]["index"] = i;
    else material[slots[i]]["index"] = i;
  }
  j["materials"] = {material};
  std::ofstream(file) << j.dump();
}

// The content generator's .glb: both images inside the binary, no warning; the 8-bit base
// colour stays 8-bit, the 16-bit emissive keeps its value (128/65535 decoded from sRGB, times
// the strength 1e4: 1.51, where 8 bits give 0).
TEST(GltfImages, GlbBufferViewsAt8And16Bits) {
  Scene s = loadGltf(contentFile("embedded_textures.glb"));
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const Material& base = material(s, "base_colour_8bit");
  ASSERT_TRUE(base.baseColorTexture);
  const Texture& b = s.textures[base.baseColorTexture->texture];
  EXPECT_EQ(b.source, ImageSource::BufferView);
  EXPECT_EQ(b.format, TexelFormat::Rgba8);
  EXPECT_FALSE(b.placeholder);
  EXPECT_EQ(b.rgba8[0], 188);
  EXPECT_EQ(b.rgba8[1], 94);

  const Material& glow = material(s, "emissive_16bit");
  ASSERT_TRUE(glow.emissiveTexture);
  const Texture& e = s.textures[glow.emissiveTexture->texture];
  EXPECT_EQ(e.source, ImageSource::BufferView);
  EXPECT_EQ(e.fileBits, 16);
  ASSERT_EQ(e.format, TexelFormat::Rgba16Float);
  const float linear = shared::tlSrgbToLinear1(128.0f / 65535.0f);
  EXPECT_NEAR(texelValue(e, 0).r / linear, 1.0f, 1e-3f);
  const float radiance = texelValue(e, 0).r * glow.emissiveFactor.r * glow.emissiveStrength;
  EXPECT_NEAR(radiance, 1.5118f, 0.002f);
}

TEST(GltfImages, DataUri) {
  Scene s = loadGltf(contentFile("normal_probe.gltf"));
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const Material& m = material(s, "normal_mapped");
  ASSERT_TRUE(m.normalTexture);
  const Texture& t = s.textures[m.normalTexture->texture];
  EXPECT_EQ(t.source, ImageSource::DataUri);
  EXPECT_FALSE(t.placeholder);
  EXPECT_FALSE(t.srgb);
  EXPECT_EQ(t.width, 4u);
}

// Files next to the .gltf: a float EXR keeps values above 1 (an emissive map in nits), a
// 16-bit PNG normal map stays 16-bit linear, a 16-bit colour PNG becomes linear half floats.
TEST(GltfImages, FilesAtEveryDepth) {
  TempDir tmp;
  writeImage(tmp.path / "glow.exr", 3, std::vector<float>(12, 123.5f), OIIO::TypeDesc::HALF);
  writeImage(tmp.path / "normal16.png", 3, std::vector<float>(12, 40000.0f / 65535.0f), OIIO::TypeDesc::UINT16);
  writeImage(tmp.path / "colour16.png", 4, std::vector<float>(16, 1000.0f / 65535.0f), OIIO::TypeDesc::UINT16);
  writeTexturedTriangle(tmp.path / "files.gltf", {"glow.exr", "normal16.png", "colour16.png"});
  Scene s = loadGltf(tmp.path / "files.gltf");
  EXPECT_TRUE(s.warnings.empty()) << s.warnings.front();
  const Material& m = s.materials[0];
  const Texture& glow = s.textures[m.emissiveTexture->texture];
  EXPECT_EQ(glow.source, ImageSource::File);
  EXPECT_EQ(glow.format, TexelFormat::Rgba16Float);
  EXPECT_EQ(texelValue(glow, 3).g, 123.5f);  // not clamped, not sRGB-decoded: EXR is linear
  EXPECT_EQ(texelValue(glow, 3).a, 1.0f);
  const Texture& normal = s.textures[m.normalTexture->texture];
  EXPECT_EQ(normal.format, TexelFormat::Rgba16Unorm);
  EXPECT_EQ(normal.rgba16[0], 40000);
  const Texture& colour = s.textures[m.baseColorTexture->texture];
  EXPECT_EQ(colour.format, TexelFormat::Rgba16Float);
  EXPECT_NEAR(texelValue(colour, 0).r / shared::tlSrgbToLinear1(1000.0f / 65535.0f), 1.0f, 1e-3f);
  EXPECT_NEAR(texelValue(colour, 0).a, 1000.0f / 65535.0f, 1e-4f);  // alpha is linear
  // Content hashes tell the texel formats apart and follow the texels.
  EXPECT_NE(glow.contentHash, colour.contentHash);
}

// Every channel count widens to RGBA texel by texel (grey -> rgb, grey + alpha, rgb opaque,
// rgba as is) in each decoding path: 8 bits, 16 bits linear, and float (read in the file's
// own type and converted by Twinlight, textures.cpp readPixels). Channels differ by 1/255.
// Colour comes back as stored, not premultiplied by alpha (glTF's convention; OpenImageIO's
// PNG reader premultiplies unless told not to).
TEST(GltfImages, EveryChannelCountWidensToRgba) {
  TempDir tmp;
  const std::pair<OIIO::TypeDesc, const char*> types[] = {
      {OIIO::TypeDesc::UINT8, "png"}, {OIIO::TypeDesc::UINT16, "png"}, {OIIO::TypeDesc::HALF, "exr"}};
  for (int ch = 1; ch <= 4; ++ch)
    for (const auto& [type, extension] : types) {
      std::vector<float> values;
      for (int p = 0; p < 4; ++p)
        for (int c = 0; c < ch; ++c) values.push_back(float(10 * (p + 1) + c) / 255.0f);
      const fs::path file = tmp.path / fmt::format("{}_{}.{}", ch, type.size(), extension);
      writeImage(file, ch, values, type);
      std::ifstream in(file, std::ios::binary);
      const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      Texture t;
      t.srgb = false;
      std::string error;
      ASSERT_TRUE(decodeImage(bytes, t, error)) << file << ": " << error;
      ASSERT_EQ(t.width * t.height, 4u);
      for (size_t p = 0; p < 4; ++p) {
        auto v = [&](int c) { return values[p * size_t(ch) + size_t(c)]; };
        const glm::vec4 expected = ch >= 3 ? glm::vec4(v(0), v(1), v(2), ch == 4 ? v(3) : 1.0f)
                                           : glm::vec4(v(0), v(0), v(0), ch == 2 ? v(1) : 1.0f);
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(texelValue(t, p)[c], expected[c], 1e-3f) << file << " pixel " << p << " channel " << c;
      }
    }
}

// Tangents: the exporters' convention. On a quad in XZ facing +Y with u along +X and v along
// -Z, the normal map's green axis (the image's top: decreasing v) is +Z = w * cross(N, T)
// with T = +X, so w = -1; mirroring u flips T and w. Generated tangents must equal what the
// probe scene supplies.
TEST(GltfTangents, GeneratedMatchSuppliedOnPlainAndMirroredUvs) {
  Scene s = loadGltf(contentFile("normal_probe.gltf"));
  for (const char* pair : {"plain", "mirrored"}) {
    const Mesh& generated = mesh(s, std::string(pair) + "_generated");
    const Mesh& supplied = mesh(s, std::string(pair) + "_supplied");
    EXPECT_TRUE(generated.generatedTangents);
    EXPECT_FALSE(supplied.generatedTangents);
    ASSERT_EQ(generated.vertices.size(), supplied.vertices.size());
    for (size_t v = 0; v < generated.vertices.size(); ++v) {
      const glm::vec4 g = generated.vertices[v].tangent, t = supplied.vertices[v].tangent;
      EXPECT_NEAR(glm::dot(glm::vec3(g), glm::vec3(t)), 1.0f, 1e-5f) << pair << " vertex " << v;
      EXPECT_EQ(g.w, t.w) << pair << " vertex " << v;
      const glm::vec3 bitangent = g.w * glm::cross(generated.vertices[v].normal, glm::vec3(g));
      EXPECT_NEAR(bitangent.z, 1.0f, 1e-5f) << pair << ": the green axis must point to the image's top (+Z)";
    }
  }
}

// A UV mirror seam: a vertex shared by triangles of both handednesses is split, each copy
// with its own w, and morph targets follow the copies.
TEST(GltfTangents, MirrorSeamSplitsTheSharedVertex) {
  // Two triangles sharing the edge x = 0; u = |x| mirrors the right one.
  Mesh m;
  const glm::vec3 p[4] = {{0, 0, 0}, {0, 0, -1}, {-1, 0, 0}, {1, 0, 0}};
  const glm::vec2 uv[4] = {{0, 0}, {0, 1}, {1, 0}, {1, 0}};
  for (int i = 0; i < 4; ++i) {
    Vertex v;
    v.position = p[i];
    v.uv = uv[i];
    m.vertices.push_back(v);
  }
  m.indices = {0, 2, 1, 0, 1, 3};
  const std::vector<uint32_t> source = finishVertices(m, false, false);
  EXPECT_EQ(m.vertices.size(), 6u) << "both seam vertices split";
  ASSERT_EQ(source.size(), m.vertices.size());
  for (size_t t = 0; t < m.indices.size(); t += 3) {
    const float w = m.vertices[m.indices[t]].tangent.w;
    for (size_t k = 1; k < 3; ++k) EXPECT_EQ(m.vertices[m.indices[t + k]].tangent.w, w) << "triangle " << t / 3;
  }
  EXPECT_NE(m.vertices[m.indices[0]].tangent.w, m.vertices[m.indices[3]].tangent.w);
  for (size_t v = 0; v < m.vertices.size(); ++v) EXPECT_EQ(m.vertices[v].position, p[source[v]]);
}

// One binary buffer: a triangle's positions (36 bytes), UVs (24), then `extra`.
void writeBin(const fs::path& file, const std::vector<uint8_t>& extra = {}) {
  const std::array<float, 15> data = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 1};
  std::ofstream f(file, std::ios::binary);
  f.write(reinterpret_cast<const char*>(data.data()), sizeof data);
  f.write(reinterpret_cast<const char*>(extra.data()), std::streamsize(extra.size()));
}

nlohmann::json baseTriangle(size_t binBytes) {
  return {{"asset", {{"version", "2.0"}}},
          {"buffers", {{{"uri", "t.bin"}, {"byteLength", binBytes}}}},
          {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}}, {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 24}}}},
          {"accessors",
           {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
            {{"bufferView", 1}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}},
          {"meshes", {{{"name", "tri"}, {"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}}}}}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"scenes", {{{"nodes", {0}}}}},
          {"scene", 0}};
}

// Every feature the renderer does not apply is one line of Scene::ignored (with its count)
// and one warning; a file using none of them has neither.
TEST(GltfIgnored, EachIgnoredFeatureIsOneLineAndOneWarning) {
  TempDir tmp;
  writeBin(tmp.path / "t.bin");
  auto j = baseTriangle(60);
  j["images"] = {{{"uri", "a.png"}}};
  writeImage(tmp.path / "a.png", 3, std::vector<float>(12, 0.5f), OIIO::TypeDesc::UINT8);
  j["samplers"] = {{{"wrapS", 33071}, {"magFilter", 9728}}};
  j["textures"] = {{{"source", 0}, {"sampler", 0}}};
  j["extensionsUsed"] = {"KHR_texture_transform", "KHR_materials_sheen"};
  nlohmann::json transform = {{"KHR_texture_transform", {{"scale", {2, 2}}}}};
  j["materials"] = {{{"name", "m"},
                     {"alphaMode", "BLEND"},  // applied (stochastic transparency): no line
                     {"occlusionTexture", {{"index", 0}}},  // applied: no line
                     {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}, {"texCoord", 2}, {"extensions", transform}}}}}},
                    {{"name", "n"}, {"alphaMode", "BLEND"}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  j["meshes"][0]["primitives"][0]["attributes"]["TEXCOORD_1"] = 1;  // read (no line)
  j["cameras"] = {{{"type", "orthographic"}, {"orthographic", {{"xmag", 1}, {"ymag", 1}, {"znear", 0.1}, {"zfar", 10}}}}};
  j["nodes"].push_back({{"camera", 0}});  // read (no line)
  j["scenes"][0]["nodes"].push_back(1);
  std::ofstream(tmp.path / "features.gltf") << j.dump();
  Scene s = loadGltf(tmp.path / "features.gltf");
  const std::vector<std::string> expected = {
      "extension KHR_materials_sheen (1x)", "TEXCOORD_2 in a baseColorTexture (1x)"};
  ASSERT_EQ(s.ignored.size(), expected.size());
  for (const auto& e : expected) {
    bool found = false;
    for (const auto& line : s.ignored) found |= line.rfind(e, 0) == 0;
    EXPECT_TRUE(found) << "no ignored line starting with `" << e << "`";
  }
  EXPECT_EQ(s.warnings.size(), expected.size());
  const auto report = sceneReport(s);
  EXPECT_EQ(report.back().rfind("ignored: ", 0), 0u);
  EXPECT_EQ(std::count_if(report.begin(), report.end(), [](auto& l) { return l.rfind("ignored: ", 0) == 0; }),
            std::ptrdiff_t(expected.size()));

  Scene plain = loadGltf(contentFile("cutout.gltf"));
  EXPECT_TRUE(plain.ignored.empty());
  EXPECT_EQ(sceneReport(plain).back(), "ignored: nothing");
}

// Orthographic cameras take their place among the file's cameras (--camera counts them) with
// their half-sizes; one out of glTF's ranges is one warning and left out.
TEST(GltfCameras, OrthographicCamerasAreReadWithTheirMagnification) {
  TempDir tmp;
  writeBin(tmp.path / "t.bin");
  auto j = baseTriangle(60);
  j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}},
                  {{"type", "orthographic"}, {"orthographic", {{"xmag", 2.0}, {"ymag", 1.5}, {"znear", 0.0}, {"zfar", 20.0}}}},
                  {{"type", "orthographic"}, {"orthographic", {{"xmag", 0.0}, {"ymag", 1.0}, {"znear", 0.0}, {"zfar", 20.0}}}},
                  {{"type", "orthographic"}, {"orthographic", {{"xmag", 1.0}, {"ymag", 1.0}, {"znear", 5.0}, {"zfar", 5.0}}}}};
  for (int c = 0; c < 4; ++c) {
    j["nodes"].push_back({{"camera", c}, {"translation", {0.0, 1.0, double(c)}}});
    j["scenes"][0]["nodes"].push_back(c + 1);
  }
  std::ofstream(tmp.path / "cameras.gltf") << j.dump();
  Scene s = loadGltf(tmp.path / "cameras.gltf");
  ASSERT_EQ(s.cameras.size(), 2u);
  EXPECT_FALSE(s.cameras[0].orthographic);
  EXPECT_TRUE(s.cameras[1].orthographic);
  EXPECT_FLOAT_EQ(s.cameras[1].xmag, 2.0f);
  EXPECT_FLOAT_EQ(s.cameras[1].ymag, 1.5f);
  EXPECT_FLOAT_EQ(s.cameras[1].znear, 0.0f);
  EXPECT_FLOAT_EQ(s.cameras[1].zfar.value_or(0.0f), 20.0f);
  EXPECT_DOUBLE_EQ(s.cameras[1].position.z, 1.0);
  EXPECT_TRUE(s.ignored.empty());
  ASSERT_EQ(s.warnings.size(), 2u);
  for (const auto& w : s.warnings) EXPECT_NE(w.find("orthographic camera"), std::string::npos) << w;
  const auto report = sceneReport(s);
  EXPECT_NE(std::find(report.begin(), report.end(), "cameras: 1 perspective, 1 orthographic"), report.end());
}

// Sparse accessors: substitutions over a base bufferView, and over zeros without one.
TEST(GltfAccessors, SparseSubstitutesTheListedElements) {
  TempDir tmp;
  // Sparse data after the UVs (byte 60): indices {2} as a ushort (+2 pad), values {(0, 5, 0)}.
  std::vector<uint8_t> extra(4 + 12, 0);
  extra[0] = 2;
  const float five = 5.0f;
  std::memcpy(&extra[4 + 4], &five, 4);
  writeBin(tmp.path / "t.bin", extra);
  auto j = baseTriangle(76);
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 2}});
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 64}, {"byteLength", 12}});
  j["accessors"][0]["sparse"] = {{"count", 1},
                                 {"indices", {{"bufferView", 2}, {"componentType", 5123}}},
                                 {"values", {{"bufferView", 3}}}};
  j["accessors"][0]["max"] = {1, 5, 0};
  std::ofstream(tmp.path / "sparse.gltf") << j.dump();
  Scene s = loadGltf(tmp.path / "sparse.gltf");
  ASSERT_EQ(s.meshes[0].vertices.size(), 3u);
  EXPECT_EQ(s.meshes[0].vertices[1].position, glm::vec3(1, 0, 0));
  EXPECT_EQ(s.meshes[0].vertices[2].position, glm::vec3(0, 5, 0));

  // Without a base bufferView the other elements are zeros.
  j["accessors"][0].erase("bufferView");
  std::ofstream(tmp.path / "sparse_zeros.gltf") << j.dump();
  Scene z = loadGltf(tmp.path / "sparse_zeros.gltf");
  EXPECT_EQ(z.meshes[0].vertices[1].position, glm::vec3(0, 0, 0));
  EXPECT_EQ(z.meshes[0].vertices[2].position, glm::vec3(0, 5, 0));
}

// KHR_mesh_quantization may be required: normalized 16-bit positions load.
TEST(GltfAccessors, MeshQuantizationIsRead) {
  TempDir tmp;
  const std::array<int16_t, 12> q = {0, 0, 0, 0, 32767, 0, 0, 0, 0, 32767, 0, 0};  // 3 x VEC3 padded to 8 bytes
  std::vector<uint8_t> extra(sizeof q);
  std::memcpy(extra.data(), q.data(), sizeof q);
  writeBin(tmp.path / "t.bin", extra);
  auto j = baseTriangle(84);
  j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", 60}, {"byteLength", 24}, {"byteStride", 8}});
  j["accessors"][0] = {{"bufferView", 2}, {"componentType", 5122}, {"normalized", true}, {"count", 3}, {"type", "VEC3"},
                       {"min", {0, 0, 0}}, {"max", {1, 1, 0}}};
  j["extensionsUsed"] = {"KHR_mesh_quantization"};
  j["extensionsRequired"] = {"KHR_mesh_quantization"};
  std::ofstream(tmp.path / "quantized.gltf") << j.dump();
  Scene s = loadGltf(tmp.path / "quantized.gltf");
  EXPECT_TRUE(s.ignored.empty());
  EXPECT_EQ(s.meshes[0].vertices[1].position, glm::vec3(1, 0, 0));
  EXPECT_EQ(s.meshes[0].vertices[2].position, glm::vec3(0, 1, 0));
}

}  // namespace
}  // namespace tl::scene
