// drape::h5::File: numeric datasets, whole or row by row.
#include "h5_internal.hpp"

#include <algorithm>

namespace drape::h5 {

using detail::guarded;

namespace {

std::vector<hsize_t> to_hsize(const Dims& dims) { return std::vector<hsize_t>(dims.begin(), dims.end()); }

H5::DataSpace simple_space(const Dims& dims, const std::vector<hsize_t>* max_dims = nullptr) {
  if (dims.empty()) return H5::DataSpace(H5S_SCALAR);
  const auto d = to_hsize(dims);
  return H5::DataSpace(static_cast<int>(d.size()), d.data(), max_dims ? max_dims->data() : nullptr);
}

std::size_t element_size(DType type) {
  switch (type) {
    case DType::F32: case DType::I32: return 4;
    case DType::F64: case DType::I64: return 8;
    case DType::I8: case DType::U8: return 1;
  }
  return 1;
}

bool is_integer(DType type) { return type != DType::F32 && type != DType::F64; }

// What the dataset holds, where HDF5 would convert it without a word or
// fail as if the file were damaged: floating-point numbers read as integers
// are cut (a parent index 15.9 of a user's SMPL file was read as 15, a
// vertex index 3.4 as 3), and text or records are not numbers at all (it
// said "the file is corrupt or truncated"). Integers read as floats are
// exact, and an enum (h5py's bool) is left to HDF5's own conversion.
void check_element_class(const H5::DataSet& ds, const std::string& file, const std::string& p, DType type) {
  const H5T_class_t cls = ds.getTypeClass();
  if (cls == H5T_INTEGER || cls == H5T_ENUM) return;
  if (cls == H5T_FLOAT) {
    if (is_integer(type))
      throw ConfigError(file + ": dataset " + p + " holds floating-point numbers; it must hold integers (" +
                        to_string(type) + ": indices and counts are stored as an integer type)");
    return;
  }
  const char* what = cls == H5T_STRING ? "text" : cls == H5T_COMPOUND ? "records (a compound type)" : "a non-numeric type";
  throw ConfigError(file + ": dataset " + p + " holds " + what + ", not numbers (expected " + to_string(type) + ")");
}

}  // namespace

void File::write_raw(const std::string& dataset, const Dims& shape, DType type, const void* data) {
  const std::string p = normalize(dataset);
  impl_->require_writable("writing " + p);
  if (exists(p)) {
    const Dims have = this->shape(p);
    if (have != shape)
      throw Error(impl_->name() + ": cannot write " + to_string(shape) + " into dataset " + p + " of shape " + to_string(have));
  } else {
    create(p, type, shape);
  }
  const H5::DataSet ds = impl_->open_dataset(p);
  guarded(*impl_, false, "writing " + p + " failed", [&] {
    if (element_count(shape) > 0) ds.write(data, detail::memory_type(type));
  });
}

void File::read_raw(const std::string& dataset, const Dims& expected, DType type, void* out) const {
  const std::string p = normalize(dataset);
  const Dims have = shape(p);
  if (have != expected)
    throw ConfigError(impl_->name() + ": dataset " + p + " has shape " + to_string(have) + ", expected " + to_string(expected));
  const H5::DataSet ds = impl_->open_dataset(p);
  guarded(*impl_, true, "cannot read the type of " + p, [&] { check_element_class(ds, impl_->name(), p, type); });
  guarded(*impl_, true, "cannot read " + p + ", the file is corrupt or truncated", [&] {
    if (element_count(have) > 0) ds.read(out, detail::memory_type(type));
  });
}

void File::create(const std::string& dataset, DType type, const Dims& shape, const CreateOptions& options) {
  const std::string p = normalize(dataset);
  impl_->require_writable("creating " + p);
  if (exists(p)) throw Error(impl_->name() + ": cannot create dataset " + p + ": it already exists");
  if (options.extendible && shape.empty()) throw Error(impl_->name() + ": extendible dataset " + p + " needs at least one axis");
  create_group(p.substr(0, p.rfind('/')));
  guarded(*impl_, false, "cannot create dataset " + p + " " + to_string(shape), [&] {
    H5::DSetCreatPropList dcpl;
    // No timestamps: identical content gives identical files, and writing rows
    // never has a reason to touch the object header.
    H5Pset_obj_track_times(dcpl.getId(), false);
    std::vector<hsize_t> max_dims = to_hsize(shape);
    if (options.extendible) {
      max_dims[0] = H5S_UNLIMITED;
      std::vector<hsize_t> chunk = to_hsize(shape);
      std::size_t row_bytes = element_size(type);
      for (std::size_t i = 1; i < shape.size(); ++i) {
        chunk[i] = std::max<hsize_t>(chunk[i], 1);
        row_bytes *= chunk[i];
      }
      chunk[0] = options.chunk_rows ? options.chunk_rows : std::max<std::size_t>(1, (256u << 10) / row_bytes);
      dcpl.setChunk(static_cast<int>(chunk.size()), chunk.data());
    } else if (options.preallocate) {
      dcpl.setLayout(H5D_CONTIGUOUS);
      dcpl.setAllocTime(H5D_ALLOC_TIME_EARLY);
    }
    if (options.fill) {
      const double fill = *options.fill;
      dcpl.setFillValue(H5::PredType::NATIVE_DOUBLE, &fill);
      dcpl.setFillTime(H5D_FILL_TIME_ALLOC);
    } else {
      dcpl.setFillTime(H5D_FILL_TIME_NEVER);
    }
    const H5::DataSpace space = simple_space(shape, options.extendible ? &max_dims : nullptr);
    impl_->file.createDataSet(p, detail::file_type(type), space, dcpl);
  });
}

void File::resize_rows(const std::string& dataset, std::size_t rows) {
  const std::string p = normalize(dataset);
  impl_->require_writable("resizing " + p);
  Dims dims = shape(p);
  const H5::DataSet ds = impl_->open_dataset(p);
  guarded(*impl_, false, "cannot resize " + p, [&] {
    std::vector<hsize_t> max_dims(dims.size());
    if (!dims.empty()) ds.getSpace().getSimpleExtentDims(nullptr, max_dims.data());
    if (dims.empty() || max_dims[0] != H5S_UNLIMITED)
      throw Error(impl_->name() + ": cannot resize " + p + ": it was not created extendible");
    dims[0] = rows;
    const auto d = to_hsize(dims);
    ds.extend(d.data());
  });
}

void File::rows_raw(const std::string& dataset, std::size_t first, std::size_t count, DType type, void* data, bool write) {
  const std::string p = normalize(dataset);
  if (write) impl_->require_writable("writing " + p);
  const Dims dims = shape(p);
  if (dims.empty()) throw Error(impl_->name() + ": " + p + " is a scalar, it has no rows");
  if (first + count > dims[0])
    throw Error(impl_->name() + ": rows " + std::to_string(first) + ".." + std::to_string(first + count) + " of " + p +
                " are out of range (it has " + std::to_string(dims[0]) + ")");
  if (count == 0) return;
  const H5::DataSet ds = impl_->open_dataset(p);
  if (!write) guarded(*impl_, true, "cannot read the type of " + p, [&] { check_element_class(ds, impl_->name(), p, type); });
  const std::string what = (write ? "writing rows of " : "cannot read rows of ") + p + (write ? " failed" : ", the file is corrupt or truncated");
  guarded(*impl_, !write, what, [&] {
    std::vector<hsize_t> start(dims.size(), 0), extent = to_hsize(dims);
    start[0] = first;
    extent[0] = count;
    H5::DataSpace file_space = ds.getSpace();
    file_space.selectHyperslab(H5S_SELECT_SET, extent.data(), start.data());
    const H5::DataSpace memory_space(static_cast<int>(extent.size()), extent.data());
    if (write) ds.write(data, detail::memory_type(type), memory_space, file_space);
    else ds.read(data, detail::memory_type(type), memory_space, file_space);
  });
}

}  // namespace drape::h5
