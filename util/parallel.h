// The project's one way to spread independent tasks over threads (records files, tables, figures).
#pragma once

#include <cstddef>
#include <functional>

namespace ra::util {

// Runs task(0) ... task(count - 1) on up to `jobs` threads (0: the number of cores; the calling
// thread is one of them). Each task must write only its own results. The first exception (by task
// index) is rethrown after all tasks finish.
void run_in_parallel(std::size_t count, unsigned jobs,
                     const std::function<void(std::size_t)>& task);

}  // namespace ra::util
