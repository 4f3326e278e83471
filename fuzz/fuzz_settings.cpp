// libFuzzer target: settings JSON as `bench --set` and `compare --settings` take it
// (session/settings_json.h): parsed under the nesting limit, then every object -- the
// document itself, or each configuration's "settings" -- applied through the range table.
// A SessionError is a refusal; anything else is a finding, and so is an applied value
// outside its stated range.
#include "session/session.h"
#include "session/settings_json.h"

#include <cmath>

namespace {

void apply(const nlohmann::json& overrides) {
  try {
    const auto s = tl::session::applySettingsJson(tl::lighting::RenderSettings{}, overrides);
    // What the table promises, for a few settings whose ceilings bound the work of a frame.
    if (s.rtPretraceSteps < 1 || s.rtPretraceSteps > 256 || s.shadowMapSize < 64 || s.shadowMapSize > 8192 ||
        !(s.legacyConeStep >= 0.2f) || !std::isfinite(s.rtAoRadius))
      __builtin_trap();
  } catch (const tl::session::SessionError&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  nlohmann::json document;
  try {
    document = tl::session::parseSettingsText(std::string_view(reinterpret_cast<const char*>(data), size), "fuzz input");
  } catch (const tl::session::SessionError&) {
    return 0;
  }
  if (document.is_array()) {
    for (const auto& configuration : document)
      if (configuration.is_object() && configuration.contains("settings")) apply(configuration["settings"]);
  } else {
    apply(document);
  }
  return 0;
}
