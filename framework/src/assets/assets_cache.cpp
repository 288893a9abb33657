#include "assets_cache.hpp"

#include <drape/io/atomic_file.hpp>
#include <drape/errors.hpp>
#include <drape/io/h5.hpp>

namespace drape::assets_cache {
namespace {

constexpr const char* kFormat = "drape-assets-1";

template <class Matrix>
void put(h5::File& f, const std::string& name, const Matrix& m) {
  using Scalar = typename Matrix::Scalar;
  const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> rm = m;
  f.write(name, {static_cast<std::size_t>(rm.rows()), static_cast<std::size_t>(rm.cols())}, rm.data());
}

template <class Scalar>
Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> get(const h5::File& f, const std::string& name) {
  h5::Dims dims;
  const std::vector<Scalar> v = f.read<Scalar>(name, &dims);
  if (dims.size() != 2) throw ConfigError(f.path().string() + ": " + name + " must be 2-D");
  return Eigen::Map<const Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
      v.data(), static_cast<Eigen::Index>(dims[0]), static_cast<Eigen::Index>(dims[1]));
}

void put_mesh(h5::File& f, const std::string& g, const Mesh& m) {
  put(f, g + "/vertices", m.vertices);
  put(f, g + "/faces", m.faces);
  if (m.has_uv()) {
    put(f, g + "/uv", m.uv);
    put(f, g + "/uv_faces", m.uv_faces);
  }
}

Mesh get_mesh(const h5::File& f, const std::string& g) {
  Mesh m;
  m.vertices = get<double>(f, g + "/vertices");
  m.faces = get<int>(f, g + "/faces");
  if (f.exists(g + "/uv")) {
    m.uv = get<double>(f, g + "/uv");
    m.uv_faces = get<int>(f, g + "/uv_faces");
  }
  return m;
}

}  // namespace

void save(const std::filesystem::path& file, const Assets& a) {
  write_atomically(file, [&](const std::filesystem::path& tmp) {
    h5::File f = h5::File::create(tmp);
    f.set_attribute("/", "format", kFormat);
    f.set_attribute("/", "hash", a.hash);
    f.set_attribute("/", "spec", a.spec_text);
    std::vector<std::int32_t> corr(a.correspondence.begin(), a.correspondence.end());
    f.write("/correspondence", {corr.size()}, corr.data());
    for (int l = 0; l < a.hierarchy.num_levels(); ++l) {
      const auto& level = a.hierarchy.levels[static_cast<std::size_t>(l)];
      const std::string g = "/hierarchy/level" + std::to_string(l);
      put_mesh(f, g, level.mesh);
      put(f, g + "/fine_index", level.fine_index);
      put(f, g + "/uv_fine_index", level.uv_fine_index);
      put(f, g + "/face_chart", level.face_chart);
      if (level.upsample.nonZeros() > 0) {  // coordinate form: rows, cols, weights
        std::vector<std::int32_t> rows, cols;
        std::vector<float> values;
        for (int r = 0; r < level.upsample.outerSize(); ++r)
          for (Eigen::SparseMatrix<float, Eigen::RowMajor>::InnerIterator it(level.upsample, r); it; ++it) {
            rows.push_back(static_cast<std::int32_t>(it.row()));
            cols.push_back(static_cast<std::int32_t>(it.col()));
            values.push_back(it.value());
          }
        f.write(g + "/upsample_rows", {rows.size()}, rows.data());
        f.write(g + "/upsample_cols", {cols.size()}, cols.data());
        f.write(g + "/upsample_values", {values.size()}, values.data());
        f.set_attribute(g, "upsample_cols_count", static_cast<double>(level.upsample.cols()));
      }
    }
    f.write("/spectral/values", {static_cast<std::size_t>(a.eigenvalues.size())}, a.eigenvalues.data());
    put(f, "/spectral/vectors", a.eigenvectors);
    f.close();
  });
}

void load(const std::filesystem::path& file, Assets& a) {
  const h5::File f = h5::File::open(file);
  if (f.require_string_attribute("/", "format") != kFormat || f.require_string_attribute("/", "hash") != a.hash)
    throw ConfigError(file.string() + ": not the assets cache for this template (format or hash differs)");
  const std::vector<std::int32_t> corr = f.read<std::int32_t>("/correspondence");
  a.correspondence.assign(corr.begin(), corr.end());
  a.hierarchy.levels.clear();
  for (int l = 0; f.exists("/hierarchy/level" + std::to_string(l)); ++l) {
    const std::string g = "/hierarchy/level" + std::to_string(l);
    geometry::HierarchyLevel level;
    level.mesh = get_mesh(f, g);
    level.fine_index = get<int>(f, g + "/fine_index");
    level.uv_fine_index = get<int>(f, g + "/uv_fine_index");
    level.face_chart = get<int>(f, g + "/face_chart");
    if (f.exists(g + "/upsample_rows")) {
      const auto rows = f.read<std::int32_t>(g + "/upsample_rows");
      const auto cols = f.read<std::int32_t>(g + "/upsample_cols");
      const auto values = f.read<float>(g + "/upsample_values");
      std::vector<Eigen::Triplet<float>> t;
      for (std::size_t i = 0; i < rows.size(); ++i) t.emplace_back(rows[i], cols[i], values[i]);
      const auto n_cols = static_cast<Eigen::Index>(*f.number_attribute(g, "upsample_cols_count"));
      level.upsample.resize(level.mesh.num_vertices(), n_cols);
      level.upsample.setFromTriplets(t.begin(), t.end());
    }
    a.hierarchy.levels.push_back(std::move(level));
  }
  const std::vector<double> values = f.read<double>("/spectral/values");
  a.eigenvalues = Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
  a.eigenvectors = get<float>(f, "/spectral/vectors");
}

}  // namespace drape::assets_cache
