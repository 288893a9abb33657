#pragma once
// Why a file cannot be written, in the user's words: a full disk, a read-only
// folder, a missing one. HDF5 and assimp report only that a write failed
// ("H5Dwrite failed", naming a temporary file); the outputs' writers add the
// cause this finds, naming the user's file and its folder.
#include <filesystem>
#include <string>
#include <vector>

namespace drape {

// "no space left on <folder>", "cannot write in <folder> (read-only file
// system)", "cannot write in <folder> (permission denied)" or "folder <folder>
// does not exist" for the folder `file` is written in; "" when none holds.
// After a write failed (`failed`), a folder with less than a megabyte free is
// full (HDF5 and assimp extend a file by up to a few hundred kilobytes at a
// time); before any work, only a folder with no byte free is: a small output,
// or a finished job with nothing to write, goes ahead (they were refused with
// 936 KB free: an outside check).
std::string write_failure_cause(const std::filesystem::path& file, bool failed = true);

// Before any work: throws ConfigError (exit 2) with write_failure_cause when
// `file` cannot be written; `option` names where it was given (e.g. "--out").
void check_writable_output(const std::filesystem::path& file, const std::string& option);

// Before any work: throws ConfigError when the output folder `folder` (made
// with its missing parents when the job writes) is a file, lies under one,
// or cannot be written in (write_failure_cause of the nearest folder that
// exists).
void check_output_folder(const std::filesystem::path& folder, const std::string& option);

// Before any work: throws ConfigError when the output `out` is one of the
// files a job reads (the same file by any path: a symlink, a hard link,
// ./x): its dataset, model or shards. A job writing over its own input loses
// it whatever the outcome (dataset unpose --force deleted its input before
// reading it; train --data X --out X wrote a model over the dataset).
void refuse_output_among_inputs(const std::filesystem::path& out, const std::vector<std::filesystem::path>& inputs,
                                const std::string& option);
// Before any work: throws ConfigError when `out` exists and is not a drape
// model file (a dataset, a mesh): model set and model domain replace a model
// in place, never another kind of file.
void refuse_replacing_other_than_a_model(const std::filesystem::path& out, const std::string& option);
// The other way round: ConfigError when `out` is a drape model file (dataset
// slim, merge, expand ... --force replace a dataset, never a model: an
// outside check's --force replaced a model with a dataset without a word).
void refuse_replacing_a_model(const std::filesystem::path& out, const std::string& option);

}  // namespace drape
