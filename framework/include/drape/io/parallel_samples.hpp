#pragma once
// The worker pool of the jobs that fill a dataset one sample at a time
// (generate_dataset, drape optimize --data): samples are handed out in turn to
// `threads` workers; the first error stops the others after the sample they
// are on, and the dataset is then left as a partial file to resume, with a
// message, before the error is rethrown. Without an error it is finished.
#include <drape/io/dataset.hpp>
#include <drape/progress.hpp>

#include <functional>
#include <vector>

namespace drape {

// Each worker thread calls make_worker() once (its own state: a network
// copy, OpenMP settings) and then the returned function for every index of
// `todo` it is handed. Workers write their samples themselves (the writer is
// not thread-safe: guard it).
using SampleWorker = std::function<void(std::size_t index)>;
// `poll`, when given, is called on the calling thread every kPollSeconds
// while the workers run (the Python module's Ctrl-C check: Python runs its
// signal handlers in the main thread only). When it throws, the workers stop
// after the sample they are on (or within it, when their work learns of it
// from the caller's own flag), the dataset is left to resume as after any
// error, and poll's exception is the one rethrown.
inline constexpr double kPollSeconds = 0.1;
void make_samples_in_parallel(DatasetWriter& writer, ProgressBar& bar, const std::vector<std::size_t>& todo,
                              int threads, const std::function<SampleWorker()>& make_worker,
                              const std::function<void()>& poll = {});

}  // namespace drape
