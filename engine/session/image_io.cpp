#include "session/image_io.h"

#include "session/session.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <system_error>
#include <unistd.h>

namespace tl::session {

void writeImageAtomically(const std::filesystem::path& file, const graph::Readback& image, ImageEncoding encoding) {
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

  std::error_code ec;
  if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path(), ec);
  const std::filesystem::path tmp = file.string() + fmt::format(".tmp{}", ::getpid()) + file.extension().string();
  auto out = OIIO::ImageOutput::create(file.string());
  if (!out) throw SessionError(fmt::format("{}: cannot write this image type", file.string()));
  OIIO::ImageSpec spec(int(w), int(h), outChannels,
                       encoding == ImageEncoding::LinearHalf ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::UINT8);
  if (encoding == ImageEncoding::LinearHalf) spec.attribute("oiio:ColorSpace", "Linear");
  else spec.attribute("oiio:ColorSpace", "sRGB");
  spec.attribute("Software", "Twinlight");
  bool ok = out->open(tmp.string(), spec) && out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close();
  if (!ok) {
    std::filesystem::remove(tmp, ec);
    throw SessionError(fmt::format("{}: write failed: {}", file.string(), out->geterror()));
  }
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw SessionError(fmt::format("{}: cannot move the finished image into place", file.string()));
  }
}

}  // namespace tl::session
