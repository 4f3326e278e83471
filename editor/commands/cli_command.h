// The command line's subcommands, one file each, behind one table. A subcommand adds itself
// and its options to the parser (`add`) and does its work once the line has parsed (`run`),
// returning the exit status: 0, 1 (bad values, files, failures at run time, validation
// errors), 3 (a failed regression gate). Usage errors it finds itself throw UsageError (exit 2).
// A new subcommand: a file in editor/commands/ with a CliCommand and a line in cliCommands().
#pragma once

#include <CLI/CLI.hpp>

#include <memory>
#include <vector>

namespace tl::editor {

class CliCommand {
 public:
  virtual ~CliCommand() = default;
  // Adds the subcommand to `app` and returns it (what parsing marks as given).
  virtual CLI::App* add(CLI::App& app) = 0;
  virtual int run() = 0;
};

std::unique_ptr<CliCommand> makeRenderCommand();
std::unique_ptr<CliCommand> makeBenchCommand();
std::unique_ptr<CliCommand> makeCompareCommand();
std::unique_ptr<CliCommand> makeTuneCommand();
std::unique_ptr<CliCommand> makeCaptureCommand();
std::unique_ptr<CliCommand> makeBakeCommand();
std::unique_ptr<CliCommand> makeDoctorCommand();
std::unique_ptr<CliCommand> makeSettingsCommand();
std::unique_ptr<CliCommand> makeInfoCommand();

// Every subcommand, in the order `twinlight --help` lists them.
std::vector<std::unique_ptr<CliCommand>> cliCommands();

}  // namespace tl::editor
