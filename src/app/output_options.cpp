#include "output_options.hpp"

#include <string>

namespace rigid::app {

CLI::Option* add_output_file(CLI::App& cmd, std::string& path, const std::string& what) {
  return cmd.add_option("--out", path, "Output file: " + what)->type_name("FILE");
}

CLI::Option* add_output_prefix(CLI::App& cmd, std::string& prefix, const std::string& what) {
  return cmd.add_option("--out", prefix, "Output prefix DIR/NAME (DIR is created): " + what)->type_name("DIR/NAME");
}

CLI::Option* add_output_directory(CLI::App& cmd, std::string& dir, const std::string& what) {
  return cmd.add_option("--out", dir, "Output directory (created): " + what)->type_name("DIR");
}

}  // namespace rigid::app
