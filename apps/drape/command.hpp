#pragma once
// Subcommands of the `drape` program. Each lives in its own cmd_*.cpp and
// registers itself; main.cpp dispatches and maps errors to exit codes
// (0 success, 2 usage/configuration, 1 runtime failure).

// Each command file's own names (run, registration, helpers) live in namespace
// DRAPE_UNITY_ID: the anonymous namespace, or in a unity build (scripts/setup.sh
// builds with CMAKE_UNITY_BUILD) a name CMake makes unique per file
// (UNITY_BUILD_UNIQUE_ID, apps/CMakeLists.txt), since several files are then
// compiled as one.
#ifndef DRAPE_UNITY_ID
#define DRAPE_UNITY_ID
#endif

#include <drape/errors.hpp>

#include <boost/program_options.hpp>

#include <functional>
#include <initializer_list>
#include <map>
#include <string>
#include <vector>

namespace drape::cli {

namespace po = boost::program_options;

struct Command {
  std::string name;
  std::string summary;
  std::function<int(const std::vector<std::string>& args)> run;
};

std::vector<Command>& commands();

struct RegisterCommand {
  explicit RegisterCommand(Command c) { commands().push_back(std::move(c)); }
};

// Thrown for bad command lines (drape/errors.hpp, a ConfigError); main prints it with the command's usage hint.
using drape::UsageError;

// The most --threads a command takes (0 is every core): a few per core of
// the largest machines it runs on, beyond which threads only queue.
inline constexpr int kMaxThreads = 1024;

// Parses `args` against `options` (+ --help and --plugin-path, added here) and
// the positional names. Returns false when --help was printed. Before any
// work, it refuses (UsageError) an output that cannot be written, two
// outputs (--out, --body-out, --svg, --csv) naming one file, and --threads
// outside [0, kMaxThreads].
bool parse(const std::string& usage, const std::vector<std::string>& args, po::options_description& options,
           const po::positional_options_description& positional, po::variables_map& vm);

// Before any work: each of these options that was given names a mesh file
// drape can write (format and folder; check_mesh_output). parse() has checked
// every output's folder already; this adds the mesh format.
void check_mesh_outputs(const po::variables_map& vm, std::initializer_list<const char*> options);

// Before any work: each of these options that was given names an HDF5 file
// (a dataset, a model), not a file another format's extension promises
// (generate --out drapes.obj wrote HDF5 into a .obj). Any other extension,
// or none, is taken.
void check_hdf5_outputs(const po::variables_map& vm, std::initializer_list<const char*> options);

// A word of a command line drape prints for the user to paste: as it is when
// a shell reads it so, else in single quotes (a path with a space, a
// dataset pattern's `*`).
std::string shell_word(const std::string& word);

// The plugin search directories given with --plugin-path.
std::vector<std::string> plugin_path(const po::variables_map& vm);

// The --set node.param=value options as Model::load overrides (UsageError for a malformed one).
std::map<std::string, std::map<std::string, std::string>> parse_param_overrides(const po::variables_map& vm);

// --push-out [m] (predict, eval: TailorNet's post-processing, geometry::push_out),
// with `help` saying what it pushes; and the clearance given, -1 without the
// option (UsageError outside [0, 0.1] m).
void add_push_out_option(po::options_description& options, const std::string& help);
double push_out_margin(const po::variables_map& vm);

// --girth name=value (repeatable, or a comma list): a proportion the body model holds while it
// reaches the BMI and height (BodyRequest::proportions; the parametric body's
// chest, waist, belly, hips, arms, thighs). body, simulate, predict and
// optimize take it, so a body of the body space is named the same way by
// each; `with` says which option it goes with.
void add_girth_option(po::options_description& options, const std::string& with);
// The --girth items by name (UsageError for one that is not name=number, or
// a name given twice); empty without the option.
std::map<std::string, double> parse_girths(const po::variables_map& vm);

}  // namespace drape::cli
