#include "session/capture.h"

#include "gpu/formats.h"
#include "session/image_io.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <fstream>
#include <system_error>

namespace tl::session {
namespace {

// Names become file names: everything but letters, digits, '.', '-' and '_' turns into '_'.
std::string fileStem(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '-' && c != '_') c = '_';
  return s;
}

void writeExr(const std::filesystem::path& file, const graph::Readback& rb) {
  const gpu::FormatInfo fi = gpu::formatInfo(rb.format);
  const uint32_t w = rb.extent.width, h = rb.extent.height * std::max(1u, rb.extent.depth);
  const bool integer = fi.kind == gpu::TexelKind::Uint || fi.kind == gpu::TexelKind::Sint;
  const int channels = int(fi.channels);
  writeFileAtomically(file, [&](const std::string& tmp) {
    auto out = OIIO::ImageOutput::create(file.string());
    if (!out) return false;
    if (integer) {
      // 32-bit integer channels: lossless for every uint/sint format.
      OIIO::ImageSpec spec(int(w), int(h), channels, OIIO::TypeDesc::UINT);
      std::vector<uint32_t> values(size_t(w) * h * channels);
      const std::vector<float> decoded = rb.texels();
      if (fi.bytes == 4u * fi.channels) {
        std::memcpy(values.data(), rb.bytes.data(), values.size() * 4);
      } else {
        for (size_t i = 0; i < values.size() && i < decoded.size(); ++i) values[i] = uint32_t(int64_t(decoded[i]));
      }
      return out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::UINT, values.data()) && out->close();
    }
    // Float, unorm, snorm, depth: stored as half where that is exact (16-bit floats, 8-bit
    // normalised values), else as float (16-bit normalised values need more than half's 11 bits).
    const uint32_t bytesPerChannel = fi.channels ? fi.bytes / fi.channels : 4;
    const bool half = (fi.kind == gpu::TexelKind::Float && bytesPerChannel == 2) || bytesPerChannel == 1;
    OIIO::ImageSpec spec(int(w), int(h), channels, half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
    spec.attribute("oiio:ColorSpace", fi.kind == gpu::TexelKind::Srgb ? "sRGB" : "Linear");
    const std::vector<float> values = rb.texels();
    return out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::FLOAT, values.data()) && out->close();
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
  manifest["scene"] = session.scene().name;
  manifest["scenePath"] = session.scene().path.string();
  manifest["lightingPath"] = session.path();
  manifest["frame"] = session.frameIndex() - 1;
  manifest["camera"] = {{"position", {v.position.x, v.position.y, v.position.z}},
                        {"forward", {v.forward.x, v.forward.y, v.forward.z}},
                        {"up", {v.up.x, v.up.y, v.up.z}},
                        {"yfovRadians", v.yfovRadians}};
  const auto& l = session.lighting();
  manifest["lighting"] = {{"sunDirection", {l.sunDirection.x, l.sunDirection.y, l.sunDirection.z}},
                          {"sunIrradiance", {l.sunIrradiance.r, l.sunIrradiance.g, l.sunIrradiance.b}},
                          {"sunAngularRadius", l.sunAngularRadius},
                          {"skyRadiance", {l.skyRadiance.r, l.skyRadiance.g, l.skyRadiance.b}},
                          {"exposureEv", session.exposureEv()}};
  const auto& s = session.settings();
  manifest["settings"] = {{"width", s.width}, {"height", s.height}, {"softShadows", s.softShadows},
                          {"rtHalfRays", s.rtHalfRays}, {"rtPretrace", s.rtPretrace},
                          {"rtSimplifyRatio", s.rtSimplifyRatio}, {"legacyVoxelResolution", s.legacyVoxelResolution},
                          {"legacyAoDivisor", s.legacyAoDivisor}, {"legacyConeDivisor", s.legacyConeDivisor},
                          {"referenceBounces", s.referenceBounces},
                          {"materials", lighting::materialModeName(s.materials)}};
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
  // Instance names by index: what gbuffer.instanceId's values mean, for a viewer without the scene.
  nlohmann::json instances = nlohmann::json::array();
  for (const auto& i : session.scene().instances) instances.push_back(i.name);
  manifest["instances"] = instances;
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
      const std::string file = fileStem(info.name) + ".exr";
      writeExr(dir / file, *rb);
      r["file"] = file;
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
        return bool(out);
      });
      r["file"] = file;
      r["bytes"] = rb->bytes.size();
    }
    resources.push_back(r);
  }
  manifest["resources"] = resources;
  writeFileAtomically(dir / "manifest.json", [&](const std::string& tmp) {
    std::ofstream out(tmp);
    out << manifest.dump(2) << "\n";
    return bool(out);
  });
  return manifest;
}

CapturedImage readCaptureImage(const std::filesystem::path& file) {
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) throw SessionError(fmt::format("{}: not a readable capture image", file.string()));
  const auto& spec = in->spec();
  CapturedImage img;
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.channels = uint32_t(spec.nchannels);
  const size_t n = size_t(img.width) * img.height * img.channels;
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
  return img;
}

}  // namespace tl::session
