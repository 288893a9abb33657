#pragma once
// What a training learns from, as one number: a resumed training must learn
// from the same drapes as the run it continues. The split sizes alone let
// another shard of the same size through (the friction drapes resumed a
// model six epochs into the frictionless ones), and a path says nothing of
// what a file holds now.
#include <drape/io/dataset.hpp>

#include <cstddef>
#include <string>
#include <vector>

namespace drape {

// FNV-1a (64 bit, drape/fnv1a.hpp) over the training and validation samples' indices and
// their drapes' vertices as stored (float32), in that order; 16 hex digits.
// The same drapes in another file (a merge of the same shards, a copy) give
// the same fingerprint.
std::string training_data_fingerprint(const DatasetReader& reader, const std::vector<std::size_t>& train,
                                      const std::vector<std::size_t>& val);

}  // namespace drape
