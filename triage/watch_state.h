// The watch's state between nights: STATE/watch.json, the last good night (triage/watch.h).
#pragma once

#include <string>

namespace ra::triage {

// The last good night: its commit and build, the branch the tree follows and the tree itself
// (STATE/watch.json). Every value is checked before it reaches git or a path: the file is input
// like any other, and a commit such as `--output=FILE` would be read by git as an option.
struct LastNight {
  std::string commit, build_dir, branch, source;
};

// STATE/watch.json read back; every field empty when the file is missing (night 1). Throws
// UserError naming the file, and how to start again, when it is not a valid last night.
LastNight read_last(const std::string& path);

// The last night written to `path` atomically (a night cut short leaves the old file whole).
void write_last(const std::string& path, const LastNight& last);

}  // namespace ra::triage
