#include "gpu/renderdoc.h"

#include <renderdoc_app.h>

#include <dlfcn.h>

#include <vector>

namespace tl::gpu {
namespace {

const RENDERDOC_API_1_4_1* api(const void* p) { return static_cast<const RENDERDOC_API_1_4_1*>(p); }
RENDERDOC_DevicePointer devicePointer(VkInstance instance) { return RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(instance); }

}  // namespace

RenderDoc& RenderDoc::get() {
  static RenderDoc instance;
  return instance;
}

RenderDoc::RenderDoc() {
  // RTLD_NOLOAD: only a library RenderDoc injected; loading it ourselves would not hook Vulkan.
  void* lib = dlopen("librenderdoc.so", RTLD_NOW | RTLD_NOLOAD);
  if (!lib) {
    reason_ = "not running under RenderDoc (launch twinlight from qrenderdoc, or with `renderdoccmd capture`)";
    return;
  }
  auto getApi = reinterpret_cast<pRENDERDOC_GetAPI>(dlsym(lib, "RENDERDOC_GetAPI"));
  void* p = nullptr;
  if (!getApi || getApi(eRENDERDOC_API_Version_1_4_1, &p) != 1 || !p) {
    reason_ = "RenderDoc is loaded but does not offer its in-application API 1.4.1";
    return;
  }
  api_ = p;
}

void RenderDoc::startFrame(VkInstance instance) {
  if (api_) api(api_)->StartFrameCapture(devicePointer(instance), nullptr);
}

bool RenderDoc::endFrame(VkInstance instance) { return api_ && api(api_)->EndFrameCapture(devicePointer(instance), nullptr) == 1; }

void RenderDoc::triggerCapture() {
  if (api_) api(api_)->TriggerCapture();
}

void RenderDoc::setCaptureTemplate(const std::string& pathTemplate) {
  if (api_) api(api_)->SetCaptureFilePathTemplate(pathTemplate.c_str());
}

uint32_t RenderDoc::captureCount() const { return api_ ? api(api_)->GetNumCaptures() : 0; }

std::optional<std::string> RenderDoc::capturePath(uint32_t index) const {
  if (!api_) return std::nullopt;
  uint32_t length = 0;
  if (api(api_)->GetCapture(index, nullptr, &length, nullptr) != 1 || length == 0) return std::nullopt;
  std::vector<char> path(length + 1, '\0');
  api(api_)->GetCapture(index, path.data(), &length, nullptr);
  return std::string(path.data());
}

}  // namespace tl::gpu
