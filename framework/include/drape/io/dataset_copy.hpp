#pragma once
// A dataset written again with something changed in every sample (`drape
// dataset unpose`, `drape dataset resample`): the done samples are read in
// slices (bounded memory), each slice's parameters, garments and statistics in
// one read each (DatasetReader::sample would read every statistic per sample,
// and rebuild a slim file's body only to have it replaced), handed to the
// caller to change, and written in order.
#include <drape/io/dataset.hpp>

#include <cstddef>
#include <functional>
#include <vector>

namespace drape {

// `change(slice, samples)` gets the rows of one slice and their samples with
// body_params, garment_vertices, split and every statistic of the reader's
// layout filled in, and the body left empty: it sets the body (and whatever
// else differs). Sample k of the done samples is written at position k.
// `done` is called after each sample.
using SampleChange = std::function<void(const std::vector<std::size_t>& slice, std::vector<DatasetSample>& samples)>;
void copy_done_samples(const DatasetReader& reader, DatasetWriter& writer, const SampleChange& change,
                       const std::function<void()>& done = {});

}  // namespace drape
