// The garment each sample of a dataset wore, for the strain metric: a dataset
// made in each body's own size (size: auto, grade: auto, or sizes merged with
// --mixed-sizes) dresses a heavy body in a 5xlarge shirt whose edges rest
// 80-130 % longer than the template's (the design size's). Measured against
// the template, a settled 5xlarge drape reads as a cloth strained by 124 %;
// against its own pattern, by 20-30 %. drape eval measures strain_max against
// the garment the body wore, predicted and simulated alike.
#pragma once

#include <drape/io/dataset.hpp>
#include <drape/registry.hpp>
#include <drape/training/evaluation.hpp>

#include <cstddef>
#include <vector>

namespace drape {

// The garments the samples `indices` of `data` wore (WornGarments, in the
// order of indices): the stored scene's garment template built in each
// sample's size (its statistic garment_size, the size's flag), or its
// pattern graded by the sample's garment_grade (grade: auto), as
// garment_materials (assets.hpp) builds them; only their material spaces,
// no simulation. Empty when every sample wore the template (one size, no
// grade: auto: nothing is built). ConfigError naming the sample when a
// sample's size is not one of the garment's sizes.
WornGarments worn_garments(const Registry& registry, const DatasetReader& data, const std::vector<std::size_t>& indices);

}  // namespace drape
