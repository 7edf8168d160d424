// Outputs never replace inputs, whatever the path's spelling, and are written whole or not at all.
// Oracle: the file system itself (hard and symbolic links made by the test, the bytes read back).
#include "rigid/io/output_file.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "rigid/core/error.hpp"

namespace fs = std::filesystem;
using rigid::InputError;

namespace {

fs::path scratch() {
  const fs::path dir = fs::temp_directory_path() / ("rigid_output_file_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(OutputFile, AnInputIsRefusedAsOutputUnderEverySpelling) {
  const fs::path dir = scratch();
  std::ofstream(dir / "input.csv") << "a,b\n";
  fs::create_hard_link(dir / "input.csv", dir / "hard.csv");
  fs::create_symlink(dir / "input.csv", dir / "soft.csv");
  fs::create_directories(dir / "sub");
  const std::string input = (dir / "input.csv").string();
  for (const fs::path& out : {dir / "hard.csv", dir / "soft.csv", dir / "sub" / ".." / "input.csv"}) {
    EXPECT_THROW(rigid::io::refuse_output_over_inputs(out.string(), {input}), InputError) << out;
  }
  EXPECT_NO_THROW(rigid::io::refuse_output_over_inputs((dir / "new.csv").string(), {input}));
  rigid::io::InputFiles files;
  files.add(input);
  EXPECT_THROW(files.refuse_as_output((dir / "sub").string()), InputError);  // a directory
  EXPECT_THROW(files.refuse_folder(dir.string()), InputError);               // holds the input
  EXPECT_NO_THROW(files.refuse_folder((dir / "sub").string()));
  EXPECT_EQ(read(dir / "input.csv"), "a,b\n");
  fs::remove_all(dir);
}

TEST(OutputFile, AFailedWriteLeavesTheOldFileAndNoTemporary) {
  const fs::path dir = scratch();
  const std::string out = (dir / "table.csv").string();
  rigid::io::write_output_file(out, [](std::ostream& o) { o << "old\n"; });
  EXPECT_THROW(rigid::io::write_output_file(out,
                                            [](std::ostream& o) {
                                              o << "half";
                                              throw std::runtime_error("interrupted");
                                            }),
               std::exception);
  EXPECT_EQ(read(out), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}
