#include "command.hpp"
#include "mpi_ranks.hpp"

#include <drape/errors.hpp>
#include <drape/geometry/push_out.hpp>
#include <drape/io/mesh_io.hpp>
#include <drape/nn/gemm.hpp>
#include <drape/io/write_failure.hpp>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <typeinfo>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

namespace drape::cli {

std::vector<Command>& commands() {
  static std::vector<Command> list;
  return list;
}

bool parse(const std::string& usage, const std::vector<std::string>& args, po::options_description& options,
           const po::positional_options_description& positional, po::variables_map& vm) {
  options.add_options()("help,h", "show this help")(
      "plugin-path", po::value<std::vector<std::string>>()->composing(),
      "extra directory searched for plugins (repeatable; also $DRAPE_PLUGIN_PATH)");
  try {
    po::store(po::command_line_parser(args).options(options).positional(positional).run(), vm);
    if (vm.count("help")) {
      std::cout << "usage: " << usage << "\n\n" << options << "\n";
      return false;
    }
    po::notify(vm);
  } catch (const po::unknown_option& e) {
    // A mistyped flag gets the command's closest ones, as a mistyped scene key does.
    std::string name = e.get_option_name();
    while (!name.empty() && name.front() == '-') name.erase(name.begin());
    std::vector<std::string> known;
    for (const auto& option : options.options()) known.push_back(option->long_name());
    std::string hint;
    for (const std::string& match : closest_matches(name, known)) hint += (hint.empty() ? "; did you mean " : ", ") + ("--" + match);
    if (!hint.empty()) hint += "?";
    throw UsageError(std::string(e.what()) + hint + "\nusage: " + usage);
  } catch (const po::required_option& e) {
    // A missing positional argument was "the option '--file' is required",
    // an option the usage line never shows.
    std::string name = e.get_option_name();
    while (!name.empty() && name.front() == '-') name.erase(name.begin());
    for (unsigned i = 0; i < positional.max_total_count() && i < 16; ++i)
      if (positional.name_for_position(i) == name)
        throw UsageError("missing " + name + ": give it after the command (its place in the usage line)\nusage: " + usage);
    throw UsageError(std::string(e.what()) + "\nusage: " + usage);
  } catch (const po::error& e) {
    throw UsageError(std::string(e.what()) + "\nusage: " + usage);
  }
  // An unsigned option given a negative number: Boost reads "-1" as 2^64 - 1
  // (an outside check's --seed -1 ran as seed 18446744073709551615).
  for (const auto& [name, value] : vm) {
    const boost::any& held = value.value();
    if (held.type() != typeid(std::uint64_t) && held.type() != typeid(unsigned)) continue;
    for (std::size_t i = 0; i < args.size(); ++i) {
      const std::string flag = "--" + name;
      std::string given;
      if (args[i] == flag && i + 1 < args.size()) given = args[i + 1];
      else if (args[i].rfind(flag + "=", 0) == 0) given = args[i].substr(flag.size() + 1);
      const std::size_t start = given.find_first_not_of(" \t");
      if (start != std::string::npos && given[start] == '-')
        throw UsageError(flag + " " + given + ": expected a whole number 0 or more\nusage: " + usage);
    }
  }
  // A number option given NaN or infinity: no option means either (spectral
  // --unit inf printed "inf mm" errors, hierarchy --ratio inf ran on).
  for (const auto& [name, value] : vm) {
    const boost::any& held = value.value();
    double number = 0;
    if (const double* d = boost::any_cast<double>(&held)) number = *d;
    else if (const float* f = boost::any_cast<float>(&held)) number = *f;
    else continue;
    if (!std::isfinite(number))
      throw UsageError("--" + name + " " + std::to_string(number) + ": not a finite number\nusage: " + usage);
  }
  // Outputs are checked before any work: a drape simulated for a minute must
  // not be lost to a missing or read-only folder. A value without an
  // extension is a folder to write into (hierarchy --out), made by its command.
  // Two outputs named alike would leave one file holding the last written
  // (predict --out g.obj --body-out g.obj kept the body and lost the garment).
  // A path given empty is a shell variable never set: said as such (it was
  // "filesystem error: cannot make absolute path", exit 1).
  for (const char* option : {"out", "body-out", "before", "svg", "csv", "pose-out", "out-dir", "write-garment", "body", "unpose",
                             "data", "model", "pose-file", "smpl-theta", "drapes", "init", "mesh", "graph", "scene",
                             "data-dir", "cache-dir", "work"}) {
    if (!vm.count(option)) continue;
    const boost::any& value = vm[option].value();
    if (const std::string* given = boost::any_cast<std::string>(&value); given && given->empty())
      throw UsageError(std::string("--") + option + " is empty (a shell variable never set?): give a path\nusage: " + usage);
  }
  std::map<std::filesystem::path, std::string> written;
  for (const char* option : {"out", "body-out", "before", "svg", "csv", "pose-out", "write-garment"}) {
    if (!vm.count(option)) continue;
    const boost::any& value = vm[option].value();
    const std::string* file = boost::any_cast<std::string>(&value);
    if (!file) continue;
    // A picture goes where its extension says (predict --svg o.png wrote SVG text into o.png).
    const std::string ext = std::filesystem::path(*file).extension().string();
    if (option == std::string("svg") && ext != ".svg" && ext != ".html" && ext != ".htm")
      throw UsageError("--svg " + *file + ": expected a .svg (a drawing) or .html (a 3D viewer) file\nusage: " + usage);
    if (!ext.empty()) check_writable_output(*file, std::string("--") + option);
    const std::filesystem::path same = std::filesystem::weakly_canonical(std::filesystem::absolute(*file));
    if (const auto [it, fresh] = written.emplace(same, option); !fresh)
      throw UsageError("--" + it->second + " and --" + option + " name the same file " + *file +
                       ": each output needs its own\nusage: " + usage);
  }
  // An output naming an input file would replace it (predict --body b.obj
  // --out b.obj wrote the garment over the user's body; body --unpose's
  // --pose-out its own mesh).
  for (const char* option : {"body", "unpose", "data", "model", "pose-file", "smpl-theta", "drapes", "init", "mesh"}) {
    if (!vm.count(option)) continue;
    const boost::any& value = vm[option].value();
    const std::string* file = boost::any_cast<std::string>(&value);
    std::error_code ec;
    if (!file || !std::filesystem::is_regular_file(*file, ec)) continue;
    for (const auto& [path, output] : written)
      if (std::filesystem::exists(path, ec) && std::filesystem::equivalent(path, *file, ec))
        throw UsageError("--" + output + " " + path.string() + " is also an input (--" + option + " " + *file +
                         "): the job would write over what it reads; name another file\nusage: " + usage);
  }
  // --threads: more threads than a machine runs at once only queue, and
  // tens of thousands exhausted the stacks (simulate --threads 100000
  // crashed, 5000 hung in OpenMP's start-up).
  if (vm.count("threads")) {
    const boost::any& value = vm["threads"].value();
    if (const int* threads = boost::any_cast<int>(&value); threads && (*threads < 0 || *threads > kMaxThreads))
      throw UsageError("--threads " + std::to_string(*threads) + ": expected 0 (every core) to " +
                       std::to_string(kMaxThreads) + " (this machine runs " +
                       std::to_string(std::max(1u, std::thread::hardware_concurrency())) + " at once)\nusage: " + usage);
  }
  return true;
}

void check_mesh_outputs(const po::variables_map& vm, std::initializer_list<const char*> options) {
  for (const char* option : options)
    if (vm.count(option)) check_mesh_output(vm[option].as<std::string>());
}

void check_hdf5_outputs(const po::variables_map& vm, std::initializer_list<const char*> options) {
  static const std::set<std::string> other_formats = {".obj", ".ply", ".gltf", ".glb", ".stl", ".off", ".fbx", ".dae",
                                                      ".svg", ".html", ".htm", ".png", ".jpg", ".csv", ".json",
                                                      ".yaml", ".yml", ".txt", ".md", ".npy", ".npz", ".pt"};
  for (const char* option : options) {
    if (!vm.count(option)) continue;
    const std::filesystem::path file = vm[option].as<std::string>();
    std::string ext = file.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (other_formats.count(ext))
      throw UsageError(std::string("--") + option + " " + file.string() + ": drape writes an HDF5 file here, not a " + ext + " file" +
                       ": name it " + file.stem().string() + ".h5");
  }
}

std::string shell_word(const std::string& word) {
  if (!word.empty() && word.find_first_of(" \t\n*?[]{}$'\"\\;&|<>()!#~`") == std::string::npos) return word;
  std::string quoted = "'";
  for (const char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::vector<std::string> plugin_path(const po::variables_map& vm) {
  return vm.count("plugin-path") ? vm["plugin-path"].as<std::vector<std::string>>() : std::vector<std::string>{};
}

std::map<std::string, std::map<std::string, std::string>> parse_param_overrides(const po::variables_map& vm) {
  std::map<std::string, std::map<std::string, std::string>> out;
  if (!vm.count("set")) return out;
  for (const auto& item : vm["set"].as<std::vector<std::string>>()) {
    const auto dot = item.find('.'), eq = item.find('=');
    if (dot == std::string::npos || eq == std::string::npos || dot == 0 || eq < dot + 2 || eq + 1 == item.size())
      throw UsageError("--set wants node.param=value, got '" + item + "'");
    out[item.substr(0, dot)][item.substr(dot + 1, eq - dot - 1)] = item.substr(eq + 1);
  }
  return out;
}

void add_push_out_option(po::options_description& options, const std::string& help) {
  options.add_options()("push-out", po::value<double>()->implicit_value(geometry::kPushOutMargin),
                        (help + " (TailorNet's post-processing; 0.001 m when given without a value)").c_str());
}

double push_out_margin(const po::variables_map& vm) {
  if (!vm.count("push-out")) return -1.0;
  const double margin = vm["push-out"].as<double>();
  if (!(margin >= 0 && margin <= 0.1)) throw UsageError("--push-out wants a clearance in m within [0, 0.1]");
  return margin;
}

void add_girth_option(po::options_description& options, const std::string& with) {
  options.add_options()("girth", po::value<std::vector<std::string>>()->composing(),
                        (with + "a proportion held while BMI is reached, name=value (repeatable, or a list a=x,b=y; "
                                "parametric: chest, waist, belly, hips, arms, thighs in [-0.15, 0.15], log factors)")
                            .c_str());
}

std::map<std::string, double> parse_girths(const po::variables_map& vm) {
  std::map<std::string, double> out;
  if (!vm.count("girth")) return out;
  // Repeated (--girth chest=0.1 --girth waist=0.05) or a comma list as --pose
  // takes (--girth chest=0.1,waist=0.05).
  std::vector<std::string> items;
  for (const auto& given : vm["girth"].as<std::vector<std::string>>()) {
    std::istringstream list(given);
    for (std::string item; std::getline(list, item, ',');) items.push_back(item);
  }
  // An empty value is a shell variable never set, not "no girths".
  if (items.empty()) throw UsageError("--girth is empty: give name=value (e.g. --girth belly=0.1)");
  for (const auto& item : items) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0) throw UsageError("--girth wants name=value, got '" + item + "'");
    const std::string name = item.substr(0, eq), value = item.substr(eq + 1);
    std::size_t used = 0;
    double number = 0;
    try {
      number = std::stod(value, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != value.size() || !std::isfinite(number))
      throw UsageError("--girth " + item + ": the value is not a number");
    if (!out.emplace(name, number).second) throw UsageError("--girth " + name + " is given twice");
  }
  return out;
}

}  // namespace drape::cli

namespace {

void print_overview() {
  using drape::cli::commands;
  std::cout << "drape: predict how a garment drapes on a body, then make it physically right.\n\n"
               "usage: drape <command> [options]   (drape <command> --help for its options)\n\ncommands:\n";
  auto list = commands();
  std::sort(list.begin(), list.end(), [](auto& a, auto& b) { return a.name < b.name; });
  for (const auto& c : list) std::cout << "  " << c.name << std::string(c.name.size() < 12 ? 12 - c.name.size() : 1, ' ') << c.summary << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  using namespace drape::cli;
  // OpenBLAS on a CPU newer than itself runs SSE3 kernels: start again asking
  // for the AVX-512/AVX2 ones the CPU has (if exec fails, carry on as we are).
  drape::nn::reexec_with_native_blas(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_overview();
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--version") {
    std::cout << "drape 0.1.0\n";
    return 0;
  }
  const std::string name = args[0];
  args.erase(args.begin());
  for (const auto& c : commands()) {
    if (c.name != name) continue;
    try {
      refuse_parallel_launch(name, args);
      return c.run(args);
    } catch (const UsageError& e) {
      // "error:" as a ConfigError says it (an outside check read "drape
      // predict: --pose ..." as something other than the refusal it is).
      std::cerr << "drape " << name << ": error: " << e.what() << "\n";
      return 2;
    } catch (const drape::ConfigError& e) {
      std::cerr << "drape " << name << ": error: " << e.what() << "\n";
      return 2;
    } catch (const std::exception& e) {
      std::cerr << "drape " << name << ": failed: " << e.what() << "\n";
      return 1;
    }
  }
  std::vector<std::string> names;
  for (const auto& c : commands()) names.push_back(c.name);
  std::cerr << "drape: error: unknown command '" << name << "'" << drape::did_you_mean(name, names)
            << " (drape --help lists them)\n";
  return 2;
}
