#pragma once
// The command line of every tool, parsed the same way: CLI11's own exit codes (100 to 114, one
// per kind of parse error) are replaced by one documented code for any bad argument, so a
// script needs to know only the codes each tool's --help footer lists.
#include <CLI/CLI.hpp>

#include <optional>

namespace headingd::cli {

// The exit status of every tool for a bad or missing argument.
inline constexpr int kExitBadArguments = 2;

// What every tool does with files (files/input_file.hpp, files/output_file.hpp), for the end
// of each --help footer.
inline constexpr const char* kFileRules =
    "Files: inputs must be regular files (a FIFO, a device or a directory is refused) within a size limit "
    "by kind: TOML configuration and calibration 1 MiB, WMM coefficients 4 MiB, DBC 16 MiB, NMEA captures read "
    "whole 1 GiB (gzip: the inflated text); CSV and log lines up to 1 MiB each. Outputs are written to a "
    "temporary file in the same folder and renamed into place when complete; an output named - is standard "
    "output.";

// Parses; returns the status to exit with when the program must stop here (0 after --help or
// --version, kExitBadArguments after printing what is wrong), nothing when it goes on.
inline std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : kExitBadArguments;  // app.exit prints the help or the message
  }
  return std::nullopt;
}

}  // namespace headingd::cli
