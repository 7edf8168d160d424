#pragma once
/// `--out` has one meaning per kind of output, stated the same way in every command's --help:
/// a file where the command writes one file, a prefix DIR/NAME where it writes a family of files
/// DIR/NAME.*, a directory where it writes a folder of files. Commands whose outputs are named by
/// their format name them by that flag instead (--csv FILE, --nrml FILE, --trajectory FILE).
#include <CLI/CLI.hpp>
#include <string>

namespace rigid::app {

/// `--out FILE`: "Output file: WHAT".
CLI::Option* add_output_file(CLI::App& cmd, std::string& path, const std::string& what);

/// `--out DIR/NAME`: "Output prefix DIR/NAME (DIR is created): WHAT", WHAT naming the files.
CLI::Option* add_output_prefix(CLI::App& cmd, std::string& prefix, const std::string& what);

/// `--out DIR`: "Output directory (created): WHAT".
CLI::Option* add_output_directory(CLI::App& cmd, std::string& dir, const std::string& what);

}  // namespace rigid::app
