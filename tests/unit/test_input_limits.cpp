// Hard input: every file the importer reads is a regular file within its limits,
// JSON nesting is bounded before any parser sees it, accessor bounds survive offsets near
// 2^64, files stay inside the scene's folder unless allowed, and every number from a file is
// finite as the float it becomes and within its range (negative light clamped with a warning).
// Each test is a reproducer from the issue or the fuzzers: before the fix it crashed, hung,
// read outside its buffer or produced NaN.
#include "../common/temp_dir.h"
#include "scene/input_limits.h"
#include "scene/scene.h"
#include "scene/scene_internal.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>

#include <sys/stat.h>
#include <unistd.h>

namespace tl::scene {
namespace {

using tl::test::contentFile;
using tl::test::TempDir;

namespace fs = std::filesystem;


void writeBytes(const fs::path& p, const std::string& bytes) { std::ofstream(p, std::ios::binary) << bytes; }

std::string loadError(const fs::path& file, const LoadOptions& options = {}) {
  try {
    loadGltf(file, options);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

#define EXPECT_CONTAINS(haystack, needle) EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << (haystack)

// A one-triangle glTF with its buffer embedded as a data URI (positions, then 3 indices).
nlohmann::json triangle() {
  const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t idx[3] = {0, 1, 2};
  std::string bytes(reinterpret_cast<const char*>(pos), sizeof pos);
  bytes.append(reinterpret_cast<const char*>(idx), sizeof idx);
  static const char* b64 = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string enc;
  for (size_t i = 0; i < bytes.size(); i += 3) {
    uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    if (i + 1 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) v |= uint32_t(uint8_t(bytes[i + 2]));
    enc += b64[(v >> 18) & 63];
    enc += b64[(v >> 12) & 63];
    enc += i + 1 < bytes.size() ? b64[(v >> 6) & 63] : '=';
    enc += i + 2 < bytes.size() ? b64[v & 63] : '=';
  }
  return {{"asset", {{"version", "2.0"}}},
          {"buffers", {{{"uri", "data:application/octet-stream;base64," + enc}, {"byteLength", bytes.size()}}}},
          {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}}, {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 6}}}},
          {"accessors",
           {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}},
            {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
          {"meshes", {{{"name", "tri"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
          {"nodes", {{{"mesh", 0}, {"name", "tri"}}}},
          {"scenes", {{{"nodes", {0}}}}},
          {"scene", 0}};
}

fs::path write(const TempDir& dir, const std::string& name, const nlohmann::json& j) {
  writeBytes(dir.path / name, j.dump());
  return dir.path / name;
}

// The triangle with a textured material whose image has `uri`.
nlohmann::json texturedTriangle(const std::string& uri) {
  auto j = triangle();
  j["images"] = {{{"uri", uri}}};
  j["textures"] = {{{"source", 0}}};
  j["materials"] = {{{"name", "m"}, {"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  return j;
}

// ---- files --------------------------------------------------------------------------------

TEST(InputFiles, JsonDepthSkipsStringsAndStopsAtTheLimit) {
  EXPECT_EQ(jsonNestingDepth(R"({"a": [1, {"b": "[[[{{{"}]})", 100), 3u);
  EXPECT_EQ(jsonNestingDepth(R"({"a": "\"[[[", "b": []})", 100), 2u);
  EXPECT_EQ(jsonNestingDepth(std::string(100000, '['), 65), 65u);
  EXPECT_EQ(jsonNestingDepth("no json at all", 10), 0u);
}

TEST(InputFiles, OnlyRegularFilesAreRead) {
  TempDir tmp;
  const fs::path fifo = tmp.path / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // Opening a FIFO with no writer blocks forever unless the reader refuses it first.
  try {
    readRegularFile(fifo, 1024);
    FAIL() << "read a FIFO";
  } catch (const InputFileError& e) {
    EXPECT_CONTAINS(e.what(), "is a FIFO, not a regular file");
  }
  try {
    readRegularFile("/dev/zero", 1024);
    FAIL() << "read /dev/zero";
  } catch (const InputFileError& e) {
    EXPECT_CONTAINS(e.what(), "is a character device, not a regular file");
  }
  EXPECT_THROW(readRegularFile(tmp.path, 1024), InputFileError);
  EXPECT_THROW(requireRegularFile(fifo, true), InputFileError);
  EXPECT_NO_THROW(requireRegularFile(tmp.path / "absent", true));
  EXPECT_THROW(requireRegularFile(tmp.path / "absent", false), InputFileError);
}

TEST(InputFiles, SizeIsCheckedBeforeReading) {
  TempDir tmp;
  writeBytes(tmp.path / "big", std::string(2000, 'x'));
  EXPECT_EQ(readRegularFile(tmp.path / "big", 2000).size(), 2000u);
  try {
    readRegularFile(tmp.path / "big", 1999);
    FAIL() << "read past the limit";
  } catch (const InputFileError& e) {
    EXPECT_CONTAINS(e.what(), "is 2000 bytes, more than the 1999 bytes (2.0 KiB) allowed");
  }
}

TEST(InputFiles, FolderContainment) {
  TempDir tmp;
  fs::create_directories(tmp.path / "scene" / "sub");
  EXPECT_TRUE(isInsideFolder(tmp.path / "scene", tmp.path / "scene" / "sub" / "x.bin"));
  EXPECT_TRUE(isInsideFolder(tmp.path / "scene", tmp.path / "scene" / "sub" / ".." / "x.bin"));
  EXPECT_FALSE(isInsideFolder(tmp.path / "scene", tmp.path / "scene" / ".." / "x.bin"));
  EXPECT_FALSE(isInsideFolder(tmp.path / "scene", tmp.path / "scenery" / "x.bin"));
  EXPECT_FALSE(isInsideFolder(tmp.path / "scene", "/etc/passwd"));
  fs::create_directory_symlink(tmp.path, tmp.path / "scene" / "out");
  EXPECT_FALSE(isInsideFolder(tmp.path / "scene", tmp.path / "scene" / "out" / "x.bin"));
}

// ---- glTF documents -------------------------------------------------------------------------

TEST(HardImport, JsonNested20000DeepIsRefusedBeforeParsing) {
  // Overflowed the stack in tinygltf's recursive extras parser (SIGSEGV, nothing on stderr).
  TempDir tmp;
  writeBytes(tmp.path / "deep.gltf",
             R"({"asset": {"version": "2.0"}, "extras": )" + std::string(20000, '[') + std::string(20000, ']') + "}");
  EXPECT_CONTAINS(loadError(tmp.path / "deep.gltf"), "deep.gltf: JSON nests deeper than 64 levels");
}

TEST(HardImport, GlbJsonChunkNestedDeepIsRefused) {
  TempDir tmp;
  std::string json = R"({"asset": {"version": "2.0"}, "extras": )" + std::string(5000, '[') + std::string(5000, ']') + "}";
  while (json.size() % 4) json += ' ';
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  writeBytes(tmp.path / "deep.glb", "glTF" + u32(2) + u32(uint32_t(20 + json.size())) + u32(uint32_t(json.size())) + "JSON" + json);
  EXPECT_CONTAINS(loadError(tmp.path / "deep.glb"), "JSON nests deeper than 64 levels");
}

TEST(HardImport, ImageBufferViewPastItsBufferIsRefused) {
  // fuzz_gltf's first finding: tinygltf passes an image's bufferView to the image callback
  // without checking it lies inside its buffer (a heap-buffer-overflow read under ASan).
  TempDir tmp;
  std::string bin(64, '\0');
  nlohmann::json j = {{"asset", {{"version", "2.0"}}},
                      {"buffers", {{{"byteLength", bin.size()}}}},
                      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 16}, {"byteLength", 4096}}}},
                      {"images", {{{"bufferView", 0}, {"mimeType", "image/png"}}}}};
  std::string json = j.dump();
  while (json.size() % 4) json += ' ';
  auto u32 = [](uint32_t v) { return std::string(reinterpret_cast<const char*>(&v), 4); };
  const uint32_t total = uint32_t(12 + 8 + json.size() + 8 + bin.size());
  writeBytes(tmp.path / "view.glb", "glTF" + u32(2) + u32(total) + u32(uint32_t(json.size())) + "JSON" + json +
                                         u32(uint32_t(bin.size())) + std::string("BIN\0", 4) + bin);
  EXPECT_CONTAINS(loadError(tmp.path / "view.glb"), "image 0 refers to bufferView 0, which reaches past the end of its buffer");
  // The input the fuzzer found, as it found it.
  const fs::path found = fs::path(TWINLIGHT_SOURCE_ROOT) / "fuzz/regressions/gltf/image_view_past_buffer.glb";
  EXPECT_CONTAINS(loadError(found), "reaches past the end of its buffer");
}

TEST(HardImport, SceneFileMustBeRegular) {
  TempDir tmp;
  ASSERT_EQ(::mkfifo((tmp.path / "fifo.gltf").c_str(), 0600), 0);
  EXPECT_CONTAINS(loadError(tmp.path / "fifo.gltf"), "fifo.gltf: is a FIFO, not a regular file");
  EXPECT_CONTAINS(loadError(tmp.path), "is a directory, not a regular file");
}

TEST(HardImport, AccessorOffsetsNear2To64DoNotWrap) {
  // byteOffset + needed wrapped past zero: a 700-byte file read in front of its buffer.
  TempDir tmp;
  auto j = triangle();
  j["accessors"][0]["byteOffset"] = 18446744073709551000ull;
  EXPECT_CONTAINS(loadError(write(tmp, "wrap.gltf", j)), "accessor 0 (POSITION) reaches past the end of its buffer");
  j = triangle();
  j["bufferViews"][0]["byteOffset"] = 18446744073709551600ull;
  EXPECT_CONTAINS(loadError(write(tmp, "view_wrap.gltf", j)), "reaches past the end of its buffer");
  j = triangle();
  j["accessors"][0]["count"] = 1537228672809129302ull;  // count * 12 wraps to a small number
  EXPECT_CONTAINS(loadError(write(tmp, "count_wrap.gltf", j)), "reaches past the end of its buffer");
}

TEST(HardImport, BuffersOutsideTheFolderNeedPermission) {
  TempDir tmp;
  fs::create_directories(tmp.path / "scene");
  fs::create_directories(tmp.path / "elsewhere");
  const float pos[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const uint16_t idx[3] = {0, 1, 2};
  writeBytes(tmp.path / "elsewhere" / "t.bin", std::string(reinterpret_cast<const char*>(pos), 36) +
                                                   std::string(reinterpret_cast<const char*>(idx), 6));
  auto j = triangle();
  j["buffers"][0]["uri"] = "../elsewhere/t.bin";
  const fs::path file = write(tmp, "scene/climb.gltf", j);
  EXPECT_CONTAINS(loadError(file), "lies outside the folder of climb.gltf");
  EXPECT_EQ(loadGltf(file, LoadOptions{true}).instances.size(), 1u);
  j["buffers"][0]["uri"] = "../../../../../../../../etc/passwd";
  EXPECT_CONTAINS(loadError(write(tmp, "scene/passwd.gltf", j)), "lies outside the folder of passwd.gltf");
}

TEST(HardImport, DeviceAndFifoImagesAreRefusedNotRead) {
  // /dev/zero as an image URI spun forever in the image reader; a FIFO blocked forever.
  TempDir tmp;
  ASSERT_EQ(::mkfifo((tmp.path / "fifo.png").c_str(), 0600), 0);
  fs::create_symlink("/dev/zero", tmp.path / "zero.png");
  struct Case {
    std::string uri;
    LoadOptions options;
    std::string reason;
  };
  for (const Case& c : {Case{"/dev/zero", {}, "lies outside the folder"}, Case{"/dev/zero", {true}, "is a character device"},
                        Case{"zero.png", {true}, "is a character device"}, Case{"fifo.png", {}, "is a FIFO"}}) {
    Scene s = loadGltf(write(tmp, "t.gltf", texturedTriangle(c.uri)), c.options);
    ASSERT_EQ(s.warnings.size(), 1u) << c.uri;
    EXPECT_CONTAINS(s.warnings[0], c.reason);
    EXPECT_TRUE(s.textures.at(0).placeholder);
  }
}

std::string pngHeader(uint32_t width, uint32_t height) {
  auto crc = [](const std::string& data) {
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : data) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  auto be32 = [](uint32_t v) {
    return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)};
  };
  auto chunk = [&](const std::string& type, const std::string& data) {
    return be32(uint32_t(data.size())) + type + data + be32(crc(type + data));
  };
  const std::string ihdr = be32(width) + be32(height) + std::string{8, 6, 0, 0, 0};  // 8-bit RGBA
  return std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", std::string(16, '\0')) + chunk("IEND", "");
}

TEST(HardImport, ImagesAreLimitedBeforeTheirPixelsAreAllocated) {
  Texture t;
  std::string error;
  const std::string huge = pngHeader(100000, 100000);  // 40 GB of RGBA8 if believed
  EXPECT_FALSE(decodeImage(std::vector<uint8_t>(huge.begin(), huge.end()), t, error));
  EXPECT_CONTAINS(error, "100000x100000 pixels, more than");
  const std::string tall = pngHeader(8, 16385);
  EXPECT_FALSE(decodeImage(std::vector<uint8_t>(tall.begin(), tall.end()), t, error));
  EXPECT_CONTAINS(error, "more than the 16384 per side");
  const std::string gif = "GIF89a......";
  EXPECT_FALSE(decodeImage(std::vector<uint8_t>(gif.begin(), gif.end()), t, error));
  EXPECT_EQ(error, "neither PNG, JPEG, OpenEXR nor Radiance HDR");
}

bool hasJpegSegment(const std::vector<uint8_t>& bytes, uint8_t marker) {
  for (size_t i = 0; i + 1 < bytes.size(); ++i)
    if (bytes[i] == 0xFF && bytes[i + 1] == marker) return true;
  return false;
}

// A JPEG's metadata segments are dropped before OpenImageIO sees them: its IPTC reader read past
// the end of an APP13 segment (fuzz_image, heap-buffer-overflow under ASan; the input is kept in
// fuzz/regressions/image/ and replayed here, where an ASan build catches it). A JPEG with EXIF,
// IPTC and a comment keeps its pixels.
TEST(HardImport, JpegMetadataNeverReachesTheDecoder) {
  std::ifstream found(fs::path(TWINLIGHT_SOURCE_ROOT) / "fuzz/regressions/image/iptc_past_app13.jpg", std::ios::binary);
  const std::vector<uint8_t> iptc((std::istreambuf_iterator<char>(found)), std::istreambuf_iterator<char>());
  ASSERT_TRUE(hasJpegSegment(iptc, 0xED));
  EXPECT_FALSE(hasJpegSegment(jpegWithoutMetadata(iptc), 0xED));
  Texture t;
  std::string error;
  decodeImage(iptc, t, error);  // refused or decoded; never read out of bounds

  TempDir tmp;
  const fs::path file = tmp.path / "tagged.jpg";
  OIIO::ImageSpec spec(8, 8, 3, OIIO::TypeDesc::UINT8);
  spec.attribute("ImageDescription", "a comment");
  spec.attribute("IPTC:Caption", "a caption");
  spec.attribute("Exif:ImageUniqueID", "an exif tag");
  std::vector<uint8_t> pixels(8 * 8 * 3);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = uint8_t(i * 5);
  auto out = OIIO::ImageOutput::create(file.string());
  ASSERT_TRUE(out && out->open(file.string(), spec) && out->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && out->close());
  std::ifstream in(file, std::ios::binary);
  const std::vector<uint8_t> tagged((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::vector<uint8_t> plain = jpegWithoutMetadata(tagged);
  for (uint8_t marker : {0xE1, 0xED, 0xFE}) {
    EXPECT_TRUE(hasJpegSegment(tagged, marker)) << int(marker);
    EXPECT_FALSE(hasJpegSegment(plain, marker)) << int(marker);
  }
  EXPECT_TRUE(hasJpegSegment(plain, 0xE0));  // JFIF stays
  std::vector<uint8_t> expected(8 * 8 * 3);
  auto reader = OIIO::ImageInput::open(file.string());
  ASSERT_TRUE(reader && reader->read_image(0, 0, 0, 3, OIIO::TypeDesc::UINT8, expected.data()));
  ASSERT_TRUE(decodeImage(tagged, t, error)) << error;
  ASSERT_EQ(t.rgba8.size(), 8u * 8u * 4u);
  for (size_t p = 0; p < 64; ++p)
    for (size_t c = 0; c < 3; ++c) EXPECT_EQ(t.rgba8[p * 4 + c], expected[p * 3 + c]) << p << " " << c;
}

// ---- numbers --------------------------------------------------------------------------------

nlohmann::json withLight(nlohmann::json light) {
  auto j = triangle();
  j["extensionsUsed"] = {"KHR_lights_punctual"};
  j["extensions"] = {{"KHR_lights_punctual", {{"lights", {light}}}}};
  j["nodes"].push_back({{"name", "lamp"}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  j["scenes"][0]["nodes"] = {0, 1};
  return j;
}

TEST(HardNumbers, LightAboveTheFloatRangeIsRefused) {
  // 1e39 is a finite double and an infinite float: it gave NaN/Inf images.
  TempDir tmp;
  EXPECT_CONTAINS(loadError(write(tmp, "sun.gltf", withLight({{"type", "directional"}, {"intensity", 1e39}}))),
                  "light `lamp` intensity is 1e+39, not a finite number (as a 32-bit float)");
  EXPECT_CONTAINS(loadError(write(tmp, "colour.gltf", withLight({{"type", "point"}, {"color", {1, 1e39, 1}}}))),
                  "light `lamp` color is 1e+39, not a finite number");
  EXPECT_CONTAINS(loadError(write(tmp, "product.gltf", withLight({{"type", "point"}, {"color", {1e6, 1, 1}}, {"intensity", 1e6}}))),
                  "above the 1e+10 a light or emission may have");
}

TEST(HardNumbers, NegativeLightIsClampedWithAWarning) {
  TempDir tmp;
  Scene s = loadGltf(write(tmp, "neg.gltf", withLight({{"type", "directional"}, {"color", {-1, 0.5, 1}}, {"intensity", 3}})));
  ASSERT_EQ(s.lights.size(), 1u);
  EXPECT_EQ(s.lights[0].color, glm::vec3(0.0f, 0.5f, 1.0f));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_CONTAINS(s.warnings[0], "light `lamp` color is negative");
  // The sun's irradiance is colour x lux on Twinlight's radiometric scale (683 lm/W).
  EXPECT_EQ(s.environment.sunIrradiance, glm::vec3(0.0f, 1.5f, 3.0f) / 683.0f);

  s = loadGltf(write(tmp, "neg_intensity.gltf", withLight({{"type", "point"}, {"intensity", -5}})));
  EXPECT_EQ(s.lights.at(0).intensity, 0.0f);
  EXPECT_CONTAINS(s.warnings.at(0), "intensity is negative");

  auto j = triangle();
  j["materials"] = {{{"name", "glow"}, {"emissiveFactor", {-1, -2, 0.5}}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  s = loadGltf(write(tmp, "neg_emission.gltf", j));
  EXPECT_EQ(s.materials.at(0).emissiveFactor, glm::vec3(0.0f, 0.0f, 0.5f));
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_CONTAINS(s.warnings[0], "material `glow` emissiveFactor is negative");
}

TEST(HardNumbers, EmissionAboveTheLimitIsRefused) {
  // emissive 1e38 gave Inf in the reference.
  TempDir tmp;
  auto j = triangle();
  j["materials"] = {{{"name", "sun"},
                     {"emissiveFactor", {1, 1, 1}},
                     {"extensions", {{"KHR_materials_emissive_strength", {{"emissiveStrength", 1e38}}}}}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  EXPECT_CONTAINS(loadError(write(tmp, "strong.gltf", j)), "material `sun` emission (emissiveFactor x emissiveStrength) reaches 1e+38");
}

TEST(HardNumbers, FactorsOutsideTheirRangeAreClamped) {
  TempDir tmp;
  auto j = triangle();
  j["materials"] = {{{"name", "bright"}, {"pbrMetallicRoughness", {{"baseColorFactor", {2, 0.5, -1, 1}}, {"roughnessFactor", 7}}}}};
  j["meshes"][0]["primitives"][0]["material"] = 0;
  Scene s = loadGltf(write(tmp, "bright.gltf", j));
  EXPECT_EQ(s.materials.at(0).baseColorFactor, glm::vec4(1.0f, 0.5f, 0.0f, 1.0f));  // an albedo above 1 creates energy
  EXPECT_EQ(s.materials.at(0).roughness, 1.0f);
  EXPECT_EQ(s.warnings.size(), 3u);
  j["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 1e39;
  EXPECT_CONTAINS(loadError(write(tmp, "inf.gltf", j)), "metallicFactor is 1e+39, not a finite number");
}

TEST(HardNumbers, TransformsMustBeFiniteFloatsWithinTheWorld) {
  TempDir tmp;
  auto j = triangle();
  j["nodes"][0]["translation"] = {1e300, 0, 0};
  EXPECT_CONTAINS(loadError(write(tmp, "far.gltf", j)), "node 0 has a non-finite transform or one placing it beyond 1e+09 m");
  j["nodes"][0]["translation"] = {1e8, 0, 0};
  EXPECT_EQ(loadGltf(write(tmp, "far_ok.gltf", j)).instances.size(), 1u);
  j["nodes"][0].erase("translation");
  j["nodes"][0]["scale"] = {1e30, 1e30, 1e30};
  EXPECT_CONTAINS(loadError(write(tmp, "huge.gltf", j)), "beyond 1e+09 m from the origin");
  // A zero scale hides a node: nothing to draw, and no normal transform to give it.
  j["nodes"][0]["scale"] = {1, 0, 1};
  j["nodes"].push_back({{"mesh", 0}, {"name", "visible"}});
  j["scenes"][0]["nodes"] = {0, 1};
  Scene s = loadGltf(write(tmp, "flat.gltf", j));
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].name, "visible");
  EXPECT_CONTAINS(s.warnings.at(0), "node `tri` has a singular transform");
}

TEST(HardNumbers, CamerasOutOfRangeAreIgnoredWithAWarning) {
  TempDir tmp;
  auto j = triangle();
  j["cameras"] = {{{"type", "perspective"}, {"perspective", {{"yfov", 0.0}, {"znear", 0.1}}}},
                  {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 1e39}}}},
                  {{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}};
  for (int c = 0; c < 3; ++c) j["nodes"].push_back({{"camera", c}, {"translation", {0, 0, 5}}});
  j["scenes"][0]["nodes"] = {0, 1, 2, 3};
  Scene s = loadGltf(write(tmp, "cams.gltf", j));
  EXPECT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.warnings.size(), 2u);
}

TEST(HardNumbers, SkyAboveTheFloatRangeIsRefused) {
  TempDir tmp;
  auto j = triangle();
  j["scenes"][0]["extras"] = {{"twinlight", {{"sky_radiance", {1, 1e39, 1}}}}};
  EXPECT_CONTAINS(loadError(write(tmp, "sky.gltf", j)), "extras.twinlight.sky_radiance is 1e+39, not a finite number");
}

TEST(HardNumbers, MorphWeightsAreBounded) {
  TempDir tmp;
  auto j = triangle();
  j["meshes"][0]["primitives"][0]["targets"] = {{{"POSITION", 0}}};
  j["meshes"][0]["weights"] = {1e38};
  EXPECT_CONTAINS(loadError(write(tmp, "weights.gltf", j)), "mesh `tri` weight 0 is 1e+38, beyond the +-1000");
}

}  // namespace
}  // namespace tl::scene
