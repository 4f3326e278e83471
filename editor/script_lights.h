// The editor script's light commands (editor/script.h lists them): dragging a viewport handle
// as a person does, and the expectations a test of light editing needs.
#pragma once

#include <string>

namespace tl::editor {

class EditorApp;

// Runs `cmd` when it is a light command: returns false when it is not one. A failed action or
// expectation sets `failure`.
bool runLightScriptCommand(EditorApp& app, const std::string& cmd, const std::string& arg, std::string& failure);

}  // namespace tl::editor
