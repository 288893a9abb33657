#pragma once
// The assets of the template a dataset was made for: what training, eval,
// render and the benchmarks build before they read a dataset's samples.
#include <drape/assets/assets.hpp>

#include <filesystem>
#include <memory>

namespace drape {

class DatasetReader;
class Registry;

// The assets of the template a dataset was generated for (its scene's body
// model and garment, with eigen_k eigenvectors), checked against the
// dataset's sizes and template hash (ConfigError when they differ).
// `encoder_body`: AssetsSpec::encoder_body (empty: none).
std::shared_ptr<const Assets> assets_for_dataset(const Registry& registry, const DatasetReader& reader,
                                                 const std::filesystem::path& data, int eigen_k,
                                                 const std::filesystem::path& cache_dir, AssetsSpec* spec = nullptr,
                                                 const std::string& encoder_body = {});
// The same check for assets from elsewhere (a model's).
void check_dataset_template(const DatasetReader& reader, const std::filesystem::path& data, const Assets& assets);

}  // namespace drape
