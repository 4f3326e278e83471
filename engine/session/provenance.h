// What every JSON file Twinlight writes records about the program that wrote it (capture
// manifests, bench figures, compare reports): the version from CMake's project() and the
// git commit it was built from.
#pragma once

#include <nlohmann/json.hpp>

namespace tl::session {

// {"version": "0.1.0", "commit": "<40 hex digits>" or null, "modified": bool}
nlohmann::json twinlightJson();

}  // namespace tl::session
