// `rigid export cells`: a cube's cells as a CSV table (io/cells_csv.hpp).
#include <cstdio>
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "old_spellings.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/cells_csv.hpp"
#include "rigid/io/cube.hpp"
#include "rigid/io/output_file.hpp"

namespace rigid::app {
namespace {

void export_cells(const std::string& cube_path, const std::string& out_path) {
  const bool to_stdout = out_path.empty() || out_path == "-";
  if (!to_stdout) io::refuse_output_over_inputs(out_path, {cube_path});
  const io::Cube cube = io::read_cube(cube_path);  // checks the file before any output is made
  if (const std::string w = io::old_cube_warning(cube_path, cube); !w.empty())
    std::fprintf(stderr, "rigid: warning: %s\n", w.c_str());
  if (to_stdout) {
    io::write_cells_csv(std::cout, cube);
    std::cout.flush();
    if (!std::cout) throw InputError("(stdout)", 0, "cannot write the table");
    return;
  }
  io::write_output_file(out_path, [&cube](std::ostream& out) { io::write_cells_csv(out, cube); });
}

}  // namespace

void register_export_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("export", "Export a fragility cube's contents as tables");
  cmd->require_subcommand(1);
  auto cube = std::make_shared<std::string>();
  auto csv = std::make_shared<std::string>();
  CLI::App* cells = cmd->add_subcommand("cells",
                                        "One CSV row per cell (object, record, scale, rotation) with "
                                        "its outcome, failure time, tilt, slip, failure reason and the contact "
                                        "solver's unconverged steps");
  cells->add_option("cube", *cube, "Fragility cube (.h5) written by rigid campaign")->required();
  // a format flag takes its file, as `rigid fragility --csv FILE` does; CSV is the one format so far,
  // so the table goes to standard output without it
  CLI::Option* to_csv = cells
                            ->add_option("--csv", *csv,
                                         "Write the table as CSV (RFC 4180 quoting) to FILE; without FILE, or "
                                         "with -, or without --csv: to standard output")
                            ->expected(0, 1)
                            ->default_str("-")
                            ->type_name("FILE");
  add_old_spelling(*cells, *to_csv, {"--out", "", {}});
  // the callback owns every option's storage: CLI11 keeps only references to it
  cells->callback([cube, csv] { export_cells(*cube, *csv); });
}

}  // namespace rigid::app
