// The first summary of a run, written by `renderaudit run` when it finishes: per platform, kind and
// view, the visibility-class counts, the median and IQR of the main metric of each kind, the
// conformance with the reference rasterizer and the median render time. The full statistics are
// `renderaudit analyze`'s job.
#pragma once

#include <string>

namespace ra::analysis {

// Reads DIR/records/*.csv, writes DIR/summary.md and returns its text (Markdown).
std::string write_run_summary(const std::string& run_dir);

}  // namespace ra::analysis
