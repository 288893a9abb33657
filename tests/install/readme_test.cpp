// The README's two first commands are what CI runs: if one changes, so must the other.
#include <catch2/catch.hpp>

#include <fstream>
#include <sstream>

#include "test_support.hpp"

namespace {

std::string read(const std::filesystem::path& p) {
  std::ifstream in(p);
  REQUIRE(in);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// The command part (before any comment) of the `index`-th line of the README's
// first code block.
std::string readme_command(const std::string& readme, int index) {
  std::istringstream in(readme.substr(readme.find("```sh\n") + 6));
  std::string line;
  for (int i = 0; i <= index; ++i) std::getline(in, line);
  line = line.substr(0, line.find('#'));
  return line.substr(0, line.find_last_not_of(' ') + 1);
}

}  // namespace

TEST_CASE("README starts with the setup and test commands that CI runs", "[install][docs]") {
  const std::string readme = read(drape::test::source_dir() / "README.md");
  const std::string ci = read(drape::test::source_dir() / ".ci" / "run");
  REQUIRE(readme.find("```sh\n") != std::string::npos);
  const std::string setup = readme_command(readme, 0), tests = readme_command(readme, 1);
  CHECK(setup == "bash scripts/setup.sh");
  CHECK_THAT(tests, Catch::StartsWith("ctest --test-dir build"));
  CHECK_THAT(ci, Catch::Contains("\n" + tests + "\n") && Catch::Contains("scripts/setup.sh"));
}
