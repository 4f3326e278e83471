#include "session/capture.h"

#include "gpu/formats.h"
#include "session/capture_encoding.h"
#include "session/image_io.h"
#include "session/provenance.h"
#include "session/settings_json.h"
#include "version/version.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <system_error>

namespace tl::session {
namespace {

// Version 2: decoded and named channels (capture_encoding.h), display images as PNG, every
// setting, the program's version. Version 1 (no "schema" key) stored raw values.
constexpr int kCaptureSchema = 2;

// Names become file names: everything but letters, digits, '.', '-' and '_' turns into '_'.
std::string fileStem(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return s;
}

// Writes one stored image (capture_encoding.h) with its channel names and what it holds in
// the header, so a reader needs neither the manifest nor Twinlight to take it right.
void writeStoredImage(const std::filesystem::path& file, const StoredImage& img, const std::string& resource) {
  writeFileAtomically(file, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) throw SessionError(fmt::format("{}: cannot write this image type", file.string()));
    const bool integer = img.encoding == "uint", display = img.encoding == "display";
    const OIIO::TypeDesc type = integer ? OIIO::TypeDesc::UINT
                                : display ? OIIO::TypeDesc::UINT8
                                : img.half ? OIIO::TypeDesc::HALF
                                           : OIIO::TypeDesc::FLOAT;
    OIIO::ImageSpec spec(int(img.width), int(img.height), int(img.channels.size()), type);
    spec.channelnames = img.channels;
    spec.alpha_channel = -1;
    spec.z_channel = -1;
    for (size_t c = 0; c < img.channels.size(); ++c) {
      if (img.channels[c] == "A") spec.alpha_channel = int(c);
      if (img.channels[c] == "Z") spec.z_channel = int(c);
    }
    spec.attribute("oiio:ColorSpace", display ? "sRGB" : "Linear");
    spec.attribute("Software", "Twinlight " + versionString());
    spec.attribute("ImageDescription", resource + ": " + img.meaning);
    if (!display) {
      spec.attribute("twinlight:resource", resource);
      spec.attribute("twinlight:encoding", img.encoding);
    }
    const bool ok = out->open(tmp, spec) &&
                    (integer ? out->write_image(OIIO::TypeDesc::UINT, img.integers.data())
                             : out->write_image(OIIO::TypeDesc::FLOAT, img.values.data())) &&
                    out->close();
    if (!ok) throw SessionError(fmt::format("{}: write failed: {}", file.string(), out->geterror()));
    return true;
  });
}

}  // namespace

nlohmann::json captureFrame(Session& session, const std::filesystem::path& dir, uint32_t frames) {
  session.requestAllBuffers();
  session.renderFrames(std::max(1u, frames));
  return writeCapture(session, dir);
}

nlohmann::json writeCapture(Session& session, const std::filesystem::path& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw SessionError(fmt::format("{}: cannot create the capture folder", dir.string()));

  const View& v = session.view();
  nlohmann::json manifest;
  manifest["schema"] = kCaptureSchema;
  manifest["twinlight"] = twinlightJson();
  manifest["scene"] = session.scene().name;
  manifest["scenePath"] = session.scene().path.string();
  manifest["lightingPath"] = session.path();
  manifest["frame"] = session.frameIndex() - 1;
  manifest["camera"] = {{"position", {v.position.x, v.position.y, v.position.z}},
                        {"forward", {v.forward.x, v.forward.y, v.forward.z}},
                        {"up", {v.up.x, v.up.y, v.up.z}},
                        {"yfovRadians", v.yfovRadians},
                        {"znear", v.znear}};
  if (v.orthographic) {
    manifest["camera"]["orthographicHalfHeight"] = v.orthoHalfHeight;
    manifest["camera"]["zfar"] = v.zfar;
  }
  const auto& l = session.lighting();
  manifest["lighting"] = {{"sunDirection", {l.sunDirection.x, l.sunDirection.y, l.sunDirection.z}},
                          {"sunIrradiance", {l.sunIrradiance.r, l.sunIrradiance.g, l.sunIrradiance.b}},
                          {"sunAngularRadius", l.sunAngularRadius},
                          {"skyRadiance", {l.skyRadiance.r, l.skyRadiance.g, l.skyRadiance.b}},
                          {"exposureEv", session.exposureEv()}};
  if (l.environmentMap)
    manifest["lighting"]["environment"] = {{"file", l.environmentMap->path.string()},
                                           {"rotationRadians", l.environmentRotation},
                                           {"intensity", l.environmentIntensity}};
  manifest["settings"] = settingsJson(session.settings());
  // Which albedo the RT hits read: the database (file, schema, revision) and how many
  // combinations resolve to each source; null database: texture averages and unsaved edits.
  {
    const albedo::AlbedoLibrary& lib = session.albedo();
    nlohmann::json sources = {{"override", 0}, {"baked", 0}, {"texture average", 0}};
    for (const auto& e : lib.entries()) sources[albedo::sourceName(e.source)] = sources[albedo::sourceName(e.source)].get<int>() + 1;
    nlohmann::json db = nullptr;
    if (const albedo::AlbedoDatabase* d = lib.database())
      db = {{"file", d->file().string()}, {"schema", d->schemaVersion()}, {"revision", d->revision()}};
    manifest["albedoDatabase"] = db;
    manifest["albedoSources"] = sources;
    manifest["albedoUnsavedEdits"] = lib.unsaved();
  }
  manifest["device"] = session.device().name();
  // Instance names by index, and the same as the table of the values gbuffer.instanceId's
  // `id` channel holds (index + 1; 0 where nothing was drawn): for readers without the scene.
  nlohmann::json instances = nlohmann::json::array(), ids = nlohmann::json::array();
  ids.push_back({{"id", 0}, {"name", nullptr}});
  for (const auto& i : session.scene().instances) {
    ids.push_back({{"id", instances.size() + 1}, {"name", i.name}});
    instances.push_back(i.name);
  }
  manifest["instances"] = instances;
  manifest["instanceIds"] = ids;
  nlohmann::json timings = nlohmann::json::array();
  for (const auto& t : session.timings()) timings.push_back({{"pass", t.pass}, {"gpuMs", t.gpuMs}});
  manifest["timings"] = timings;

  nlohmann::json resources = nlohmann::json::array();
  for (const auto& info : session.resources()) {
    nlohmann::json r = {{"name", info.name},
                        {"writer", info.writer},
                        {"persistent", info.persistent},
                        {"imported", info.imported},
                        {"aliased", info.aliased},
                        {"firstUse", info.firstUse == graph::kNone ? -1 : int64_t(info.firstUse)},
                        {"lastUse", info.lastUse == graph::kNone ? -1 : int64_t(info.lastUse)},
                        {"memoryBytes", info.bytes},
                        {"description", info.desc.description},
                        {"decoder", info.desc.decoder}};
    const graph::Readback* rb = nullptr;
    try {
      rb = &session.buffer(info.name);
    } catch (const std::exception&) {
      r["file"] = nullptr;
      r["note"] = "not read back (culled or not touched this frame)";
      resources.push_back(r);
      continue;
    }
    if (info.desc.type == graph::ResourceType::Image) {
      const gpu::FormatInfo fi = gpu::formatInfo(rb->format);
      const StoredImage stored = encodeCaptureImage(info.desc, *rb, v.znear);
      const std::string file = fileStem(info.name) + stored.fileExtension;
      writeStoredImage(dir / file, stored, info.name);
      r["file"] = file;
      r["encoding"] = stored.encoding;
      r["channelNames"] = stored.channels;
      r["values"] = stored.meaning;
      r["format"] = fi.name;
      r["width"] = rb->extent.width;
      r["height"] = rb->extent.height;
      r["depth"] = rb->extent.depth;
      r["channels"] = fi.channels;
      r["mips"] = info.desc.mipLevels;
      if (rb->extent.depth > 1) r["layout"] = "z slices stacked downwards (height x depth rows), mip 0";
      else if (info.desc.mipLevels > 1) r["layout"] = "mip 0";
    } else {
      const std::string file = fileStem(info.name) + ".bin";
      writeFileAtomically(dir / file, [&](const std::string& tmp) {
        std::ofstream out(tmp, std::ios::binary);
        out.write(reinterpret_cast<const char*>(rb->bytes.data()), std::streamsize(rb->bytes.size()));
        out.close();  // a failed final flush (a full disk) must fail the write too
        return !out.fail();
      });
      r["file"] = file;
      r["bytes"] = rb->bytes.size();
    }
    resources.push_back(r);
  }
  manifest["resources"] = resources;
  writeTextFile(dir / "manifest.json", manifest.dump(2) + "\n");
  return manifest;
}

CapturedImage readCaptureImage(const std::filesystem::path& file, const std::vector<std::string>& channels) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) throw SessionError(fmt::format("{}: not a readable capture image", file.string()));
  const auto& spec = in->spec();
  CapturedImage img;
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.channels = uint32_t(spec.nchannels);
  const size_t texels = size_t(img.width) * img.height, n = texels * img.channels;
  img.integer = spec.format == OIIO::TypeDesc::UINT;
  if (img.integer) {
    img.integers.resize(n);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT, img.integers.data()))
      throw SessionError(fmt::format("{}: read failed", file.string()));
    img.values.assign(img.integers.begin(), img.integers.end());
  } else {
    img.values.resize(n);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, img.values.data()))
      throw SessionError(fmt::format("{}: read failed", file.string()));
  }
  if (channels.empty() || channels == spec.channelnames) return img;
  // Reorder to the names asked for.
  if (channels.size() != spec.channelnames.size())
    throw SessionError(fmt::format("{}: holds {} channels, the manifest names {}", file.string(), spec.channelnames.size(), channels.size()));
  std::vector<size_t> from;
  for (const std::string& name : channels) {
    auto it = std::find(spec.channelnames.begin(), spec.channelnames.end(), name);
    if (it == spec.channelnames.end()) throw SessionError(fmt::format("{}: no channel `{}`", file.string(), name));
    from.push_back(size_t(it - spec.channelnames.begin()));
  }
  const CapturedImage stored = img;
  for (size_t t = 0; t < texels; ++t)
    for (size_t c = 0; c < from.size(); ++c) {
      img.values[t * from.size() + c] = stored.values[t * from.size() + from[c]];
      if (img.integer) img.integers[t * from.size() + c] = stored.integers[t * from.size() + from[c]];
    }
  return img;
}

}  // namespace tl::session
