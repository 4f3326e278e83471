#include "cli_command.h"

namespace tl::editor {

std::vector<std::unique_ptr<CliCommand>> cliCommands() {
  std::vector<std::unique_ptr<CliCommand>> commands;
  commands.push_back(makeRenderCommand());
  commands.push_back(makeBenchCommand());
  commands.push_back(makeCompareCommand());
  commands.push_back(makeTuneCommand());
  commands.push_back(makeCaptureCommand());
  commands.push_back(makeBakeCommand());
  commands.push_back(makeDoctorCommand());
  commands.push_back(makeSettingsCommand());
  commands.push_back(makeInfoCommand());
  return commands;
}

}  // namespace tl::editor
