// drape::h5::File: attributes (variable-length UTF-8 strings and f64 numbers).
#include "h5_internal.hpp"

#include <algorithm>

namespace drape::h5 {

using detail::guarded;

namespace {

H5::StrType utf8_string_type(const std::string& value) {
  // Fixed length, not variable: a variable-length string lives in HDF5's
  // global heap, which has no checksum, and a damaged heap entry can loop
  // HDF5's reader forever. A fixed-length one sits in the object header,
  // which the 1.8 format checksums. h5py reads it as bytes (docs/formats.md).
  H5::StrType type(H5::PredType::C_S1, std::max<std::size_t>(value.size(), 1));
  type.setStrpad(H5T_STR_NULLPAD);
  type.setCset(H5T_CSET_UTF8);
  return type;
}

std::string describe(const std::string& object, const std::string& name) {
  return "attribute '" + name + "' of " + normalize(object);
}

}  // namespace

void File::set_attribute(const std::string& object, const std::string& name, const std::string& value) {
  impl_->require_writable("writing " + describe(object, name));
  auto obj = impl_->open_object(object);
  guarded(*impl_, false, "writing " + describe(object, name) + " failed", [&] {
    if (obj->attrExists(name)) obj->removeAttr(name);
    const H5::StrType type = utf8_string_type(value);
    H5::Attribute attr = obj->createAttribute(name, type, H5::DataSpace(H5S_SCALAR));
    attr.write(type, value.empty() ? std::string(1, '\0') : value);
  });
}

void File::set_attribute(const std::string& object, const std::string& name, double value) {
  impl_->require_writable("writing " + describe(object, name));
  auto obj = impl_->open_object(object);
  guarded(*impl_, false, "writing " + describe(object, name) + " failed", [&] {
    if (obj->attrExists(name)) obj->removeAttr(name);
    H5::Attribute attr = obj->createAttribute(name, H5::PredType::IEEE_F64LE, H5::DataSpace(H5S_SCALAR));
    attr.write(H5::PredType::NATIVE_DOUBLE, &value);
  });
}

bool File::has_attribute(const std::string& object, const std::string& name) const {
  if (!exists(object)) return false;
  auto obj = impl_->open_object(object);
  return guarded(*impl_, true, "cannot look up " + describe(object, name), [&] { return obj->attrExists(name); });
}

std::vector<std::string> File::attribute_names(const std::string& object) const {
  auto obj = impl_->open_object(object);
  return guarded(*impl_, true, "cannot list the attributes of " + normalize(object), [&] {
    std::vector<std::string> names;
    const int n = obj->getNumAttrs();
    for (int i = 0; i < n; ++i) names.push_back(obj->openAttribute(static_cast<unsigned>(i)).getName());
    std::sort(names.begin(), names.end());
    return names;
  });
}

std::optional<std::string> File::string_attribute(const std::string& object, const std::string& name) const {
  if (!has_attribute(object, name)) return std::nullopt;
  auto obj = impl_->open_object(object);
  return guarded(*impl_, true, "cannot read " + describe(object, name), [&]() -> std::optional<std::string> {
    const H5::Attribute attr = obj->openAttribute(name);
    if (attr.getTypeClass() != H5T_STRING || attr.getSpace().getSimpleExtentNpoints() != 1)
      throw ConfigError(impl_->name() + ": " + describe(object, name) + " is not a single string");
    std::string value;
    // The attribute's own string type reads both variable-length (h5py's str)
    // and fixed-length strings (numpy bytes).
    attr.read(attr.getStrType(), value);
    return value;
  });
}

std::optional<double> File::number_attribute(const std::string& object, const std::string& name) const {
  if (!has_attribute(object, name)) return std::nullopt;
  auto obj = impl_->open_object(object);
  return guarded(*impl_, true, "cannot read " + describe(object, name), [&]() -> std::optional<double> {
    const H5::Attribute attr = obj->openAttribute(name);
    const H5T_class_t cls = attr.getTypeClass();
    if ((cls != H5T_FLOAT && cls != H5T_INTEGER) || attr.getSpace().getSimpleExtentNpoints() != 1)
      throw ConfigError(impl_->name() + ": " + describe(object, name) + " is not a single number");
    double value = 0.0;
    attr.read(H5::PredType::NATIVE_DOUBLE, &value);
    return value;
  });
}

std::string File::require_string_attribute(const std::string& object, const std::string& name) const {
  auto value = string_attribute(object, name);
  if (!value) throw ConfigError(impl_->name() + ": missing " + describe(object, name));
  return *value;
}

}  // namespace drape::h5
