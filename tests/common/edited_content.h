// A content/ scene with its glTF JSON edited, for importer tests of bad files: written with its
// .bin into a scratch folder and loaded; or each of several edits checked to be refused with
// one clear line.
#pragma once

#include "temp_dir.h"
#include "scene/scene.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <functional>
#include <string>
#include <vector>

namespace tl::test {

using JsonEdit = std::function<void(nlohmann::json&)>;

// content/<stem>.gltf with `edit` applied, written with content/<stem>.bin into `dir`, loaded.
inline scene::Scene loadEditedContent(const std::filesystem::path& dir, const std::string& stem, const JsonEdit& edit) {
  auto j = nlohmann::json::parse(std::ifstream(contentFile((stem + ".gltf").c_str())));
  edit(j);
  std::ofstream(dir / (stem + ".gltf")) << j.dump();
  std::filesystem::copy_file(contentFile((stem + ".bin").c_str()), dir / (stem + ".bin"),
                             std::filesystem::copy_options::overwrite_existing);
  return scene::loadGltf(dir / (stem + ".gltf"));
}

struct ContentEdit {
  const char* what;      // what the edit breaks, for the failure message
  JsonEdit edit;
  const char* expected;  // a part of the one error it must give
};

// Each edit of content/<stem>.gltf is refused with one line that names the file and says `expected`.
inline void expectEachEditIsOneClearError(const std::string& stem, const std::vector<ContentEdit>& edits) {
  TempDir dir("twinlight-edited-" + stem);
  for (const auto& e : edits) {
    std::string error;
    try {
      loadEditedContent(dir.path, stem, e.edit);
    } catch (const scene::SceneError& x) {
      error = x.what();
    }
    EXPECT_NE(error.find(e.expected), std::string::npos) << e.what << ": " << error;
    EXPECT_NE(error.find(stem + ".gltf"), std::string::npos) << e.what << ": " << error;
    EXPECT_EQ(error.find('\n'), std::string::npos) << e.what;
  }
}

}  // namespace tl::test
