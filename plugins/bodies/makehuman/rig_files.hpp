#pragma once
// MakeHuman's own rig as its files hold it (rigs/default.mhskel and the
// weights file it names, default_weights.mhw; CC0, MakeHuman 1.1+): bones
// with a head and a tail joint, each joint a group of base-mesh vertices
// whose mean is its position (the helper "joint-*" cubes, or single skin
// vertices), and per bone the base-mesh vertices it moves with their weights.
// Only read and checked here; rig.hpp turns it into drape's skeleton.
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace drape::makehuman {

struct RigFiles {
  struct Bone {
    std::string name, parent;  // parent "" for the root
    std::string head, tail;    // joint names
  };
  std::vector<Bone> bones;  // parents before children
  std::map<std::string, std::vector<int>> joints;  // joint name -> base-mesh vertex indices
  std::map<std::string, std::vector<std::pair<int, double>>> weights;  // bone -> (base vertex, weight)
  std::filesystem::path skeleton_file, weights_file;  // for messages
};

// The rig files of a MakeHuman data folder, "" when both are there, else
// the sentence that names what is missing (why the body is not poseable).
std::string missing_rig_files(const std::filesystem::path& root);

// Reads <root>/rigs/default.mhskel and its weights file. ConfigError, one
// line naming the file and what is wrong: not JSON, a key missing or of the
// wrong type, a parent or joint that is not defined, a vertex index outside
// [0, `num_base_vertices`), a weight that is negative or not finite, or a
// weighted bone the skeleton does not have.
RigFiles read_rig_files(const std::filesystem::path& root, int num_base_vertices);

}  // namespace drape::makehuman
