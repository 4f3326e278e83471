// `twinlight settings`: every render setting with its owner, default, range, unit and what it
// restarts, as text, as the user guide's Markdown table, or the defaults as a settings file.
#include "cli_command.h"

#include "session/settings_json.h"
#include "session/settings_reference.h"

#include <fmt/format.h>

namespace tl::editor {
namespace {

class SettingsCommand : public CliCommand {
 public:
  CLI::App* add(CLI::App& app) override {
    auto* cmd = app.add_subcommand("settings", "list every render setting: owner, default, range, unit, what it restarts");
    cmd->add_flag("--markdown", markdown_, "as the Markdown table in docs/user-guide.md");
    cmd->add_flag("--json", defaults_, "the defaults as a JSON settings file (for --settings)");
    return cmd;
  }

  int run() override {
    if (defaults_) fmt::print("{}\n", session::settingsJson(lighting::RenderSettings{}).dump(2));
    else fmt::print("{}", markdown_ ? session::settingsReferenceMarkdown() : session::settingsReferenceText());
    return 0;
  }

 private:
  bool markdown_ = false, defaults_ = false;
};

}  // namespace

std::unique_ptr<CliCommand> makeSettingsCommand() { return std::make_unique<SettingsCommand>(); }

}  // namespace tl::editor
