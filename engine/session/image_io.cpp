#include "session/image_io.h"

#include "session/session.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string_view>
#include <system_error>
#include <stdlib.h>
#include <unistd.h>

namespace tl::session {
namespace {

// Writes `pixels` (float, `channels` interleaved) as `type`.
void writeAtomically(const std::filesystem::path& file, uint32_t w, uint32_t h, int channels, OIIO::TypeDesc type,
                     const std::vector<float>& pixels, const char* colorSpace) {
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) throw SessionError(fmt::format("{}: cannot write this image type", file.string()));
  writeFileAtomically(file, [&](const std::string& tmp) {
    OIIO::ImageSpec spec(int(w), int(h), channels, type);
    spec.attribute("oiio:ColorSpace", colorSpace);
    spec.attribute("Software", "Twinlight");
    if (out->open(tmp, spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close()) return true;
    throw SessionError(fmt::format("{}: write failed: {}", file.string(), out->geterror()));
  });
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& file, const std::function<bool(const std::string& tmp)>& write) {
  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  const std::filesystem::path tmp = file.string() + fmt::format(".tmp{}", ::getpid()) + file.extension().string();
  bool ok = false;
  try {
    ok = write(tmp.string());
  } catch (...) {
    std::filesystem::remove(tmp, ec);
    throw;
  }
  if (!ok) {
    std::filesystem::remove(tmp, ec);
    throw SessionError(fmt::format("{}: write failed", file.string()));
  }
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw SessionError(fmt::format("{}: cannot move the finished file into place", file.string()));
  }
}

void writeTextFile(const std::filesystem::path& file, const std::string& text) {
  writeFileAtomically(file, [&](const std::string& tmp) {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw SessionError(fmt::format("cannot write {}: {}", file.string(), std::strerror(errno)));
    const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const int writeErrno = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed)
      throw SessionError(fmt::format("cannot write {}: {}", file.string(), std::strerror(written ? errno : writeErrno)));
    return true;
  });
}

namespace {

// Whether `dir` (an existing folder) takes a new file: one is created and removed again. As
// root, access(W_OK) says yes to /proc and to read-only mounts; only trying tells.
std::optional<std::string> cannotCreateIn(const std::filesystem::path& dir) {
  std::string probe = (dir / ".twinlight-probe-XXXXXX").string();
  const int fd = ::mkstemp(probe.data());
  if (fd < 0) return std::string(std::strerror(errno));
  ::close(fd);
  ::unlink(probe.c_str());
  return std::nullopt;
}

// `failure`: "cannot write FILE" or "cannot write into FOLDER", the start of every message.
void checkOutputPath(const std::string& failure, const std::filesystem::path& folder) {
  std::error_code ec;
  // The nearest folder that exists: the rest would be created when writing.
  std::filesystem::path existing = std::filesystem::absolute(folder, ec).lexically_normal();
  while (!existing.empty() && !std::filesystem::exists(existing, ec)) {
    if (existing == existing.parent_path()) break;
    existing = existing.parent_path();
  }
  if (!std::filesystem::is_directory(existing, ec))
    throw SessionError(fmt::format("{}: {} is not a folder", failure, existing.string()));
  if (auto reason = cannotCreateIn(existing))
    throw SessionError(fmt::format("{}: cannot create a file in {}: {}", failure, existing.string(), *reason));
}

}  // namespace

void checkOutputFile(const std::filesystem::path& file) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw SessionError(fmt::format("cannot write {}: it is a folder", file.string()));
  checkOutputPath("cannot write " + file.string(), file.has_parent_path() ? file.parent_path() : std::filesystem::path("."));
}

void checkOutputFolder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (std::filesystem::exists(dir, ec) && !std::filesystem::is_directory(dir, ec))
    throw SessionError(fmt::format("cannot write into {}: it is a file, not a folder", dir.string()));
  checkOutputPath("cannot write into " + dir.string(), dir);
}

ImageWriteReport writeImageAtomically(const std::filesystem::path& file, const graph::Readback& image, ImageEncoding encoding) {
  const uint32_t w = image.extent.width, h = image.extent.height;
  const uint32_t srcChannels = image.channels();
  std::vector<float> texels = image.texels();
  if (texels.size() != size_t(w) * h * srcChannels)
    throw SessionError(fmt::format("buffer `{}` cannot be written as an image", image.name));
  // RGB for colour images, alpha dropped: radiance and display images carry none.
  const int outChannels = srcChannels >= 3 ? 3 : int(srcChannels);
  std::vector<float> pixels(size_t(w) * h * outChannels);
  for (size_t i = 0; i < size_t(w) * h; ++i)
    for (int c = 0; c < outChannels; ++c) pixels[i * outChannels + c] = texels[i * srcChannels + c];
  ImageWriteReport report;
  report.pixels = uint64_t(w) * h;
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    bool beyond = false, nonFinite = false;
    for (int c = 0; c < outChannels; ++c) {
      const float v = pixels[i * outChannels + c];
      nonFinite |= !std::isfinite(v);
      beyond |= std::isfinite(v) && std::abs(v) > 65504.0f;
    }
    report.beyondHalf += beyond;
    report.nonFinite += nonFinite;
  }
  if (encoding == ImageEncoding::Linear) {
    report.float32 = report.beyondHalf > 0;
    writeAtomically(file, w, h, outChannels, report.float32 ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::HALF, pixels, "Linear");
  } else {
    writeAtomically(file, w, h, outChannels, OIIO::TypeDesc::UINT8, pixels, "sRGB");
  }
  return report;
}

std::optional<RgbImage> readExrRgb(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) return std::nullopt;
  auto in = OIIO::ImageInput::open(file.string());
  if (!in) return std::nullopt;
  const auto& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels < 3) return std::nullopt;
  RgbImage img;
  img.width = uint32_t(spec.width);
  img.height = uint32_t(spec.height);
  img.rgb.resize(size_t(img.width) * img.height * 3);
  if (!in->read_image(0, 0, 0, 3, OIIO::TypeDesc::FLOAT, img.rgb.data())) return std::nullopt;
  return img;
}

void writeExrRgb(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& rgb) {
  writeAtomically(file, w, h, 3, OIIO::TypeDesc::FLOAT, rgb, "Linear");
}

void writeExrGray(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& values) {
  writeAtomically(file, w, h, 1, OIIO::TypeDesc::FLOAT, values, "Linear");
}

void writePngRgb(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& rgb01) {
  writeAtomically(file, w, h, 3, OIIO::TypeDesc::UINT8, rgb01, "sRGB");
}

std::vector<float> falseColour(const std::vector<float>& values, float maxValue) {
  // Piecewise-linear ramp through dark blue, purple, red, orange, yellow, white: dark is
  // small error, bright is large, and the hue says roughly how large.
  static const float ramp[][3] = {{0.02f, 0.02f, 0.10f}, {0.35f, 0.05f, 0.45f}, {0.80f, 0.10f, 0.20f},
                                  {0.98f, 0.50f, 0.05f}, {0.99f, 0.90f, 0.20f}, {1.00f, 1.00f, 1.00f}};
  const int n = 6;
  std::vector<float> out(values.size() * 3);
  for (size_t i = 0; i < values.size(); ++i) {
    float v = std::isfinite(values[i]) ? std::clamp(values[i] / std::max(maxValue, 1e-20f), 0.0f, 1.0f) : 1.0f;
    float x = v * float(n - 1);
    int k = std::min(int(x), n - 2);
    float f = x - float(k);
    for (int c = 0; c < 3; ++c) out[i * 3 + c] = ramp[k][c] * (1.0f - f) + ramp[k + 1][c] * f;
  }
  return out;
}

void writeFalseColourPng(const std::filesystem::path& file, uint32_t w, uint32_t h, const std::vector<float>& values,
                         float maxValue) {
  writePngRgb(file, w, h, falseColour(values, maxValue));
}

std::string imageFileFormat(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char head[10] = {};
  in.read(head, sizeof head);
  const std::string_view h(head, size_t(in.gcount()));
  const auto starts = [&](std::string_view magic) { return h.substr(0, magic.size()) == magic; };
  using namespace std::string_view_literals;  // the magic numbers hold NUL bytes
  if (starts("\x76\x2f\x31\x01"sv)) return "EXR";
  if (starts("\x89PNG"sv)) return "PNG";
  if (starts("\xff\xd8\xff"sv)) return "JPEG";
  if (starts("#?RADIANCE"sv) || starts("#?RGBE"sv)) return "HDR";
  if (starts("II*\x00"sv) || starts("MM\x00*"sv)) return "TIFF";
  return {};
}

}  // namespace tl::session
