#include "session/provenance.h"

#include "version/version.h"

namespace tl::session {

nlohmann::json twinlightJson() {
  const VersionInfo& v = versionInfo();
  return {{"version", v.version},
          {"commit", *v.commit ? nlohmann::json(v.commit) : nlohmann::json(nullptr)},
          {"modified", v.modified}};
}

}  // namespace tl::session
