// `renderaudit reproduce RUN --platform P --kind K --view V --index I [--out FILE.c]`: one record
// of a run as a standalone C program for a driver developer (audit/reproducer.h).
#include <cstdio>
#include <filesystem>

#include "app/commands.h"
#include "audit/reproducer.h"
#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/errors.h"

namespace ra::app {

void register_reproduce_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "reproduce",
      "Write one record of a run as a small standalone C program (EGL surfaceless + desktop GL,\n"
      "the primitive's coordinates as hex floats, the worker's matrices, viewport and state)\n"
      "that draws it and prints the pixels lit beside the worker's and the reference's. Prints\n"
      "how to build it (beside the C file) and run it. The program exits 0 when its pixels are\n"
      "the reference's, or the worker's and the run found them allowed by GL (a snapped or\n"
      "rounded difference); 1 when they are the worker's and break GL's rules; 3 when they are\n"
      "neither (another driver or build: not judged); 2 when EGL or GL fails.");
  struct Options {
    audit::ReproduceRequest q;
    std::string out;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  add_primitive_options(
      cmd, {opts->q.run_dir, opts->q.platform, opts->q.kind, opts->q.view, opts->q.index},
      "the record's platform (PLATFORM or PLATFORM@BUILD)");
  cmd->add_option("--out,-o", opts->out,
                  "C file to write (default: RUN/reproduce/PLATFORM.KIND.vV.I.c); the program is "
                  "built beside it, without the .c");
  cmd->callback([opts, &exit_code] {
    const std::string path =
        !opts->out.empty() ? opts->out
                           : rundir::run_folder::reproducer_source(opts->q.run_dir, opts->q.platform,
                                                                   opts->q.kind, opts->q.view,
                                                                   opts->q.index);
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::is_directory(path, ec))
      throw util::UserError("reproduce: --out " + path +
                            " is a folder; name the C file to write "
                            "(e.g. " +
                            path + "/repro.c)");
    const fs::path parent = fs::path(path).parent_path();
    // The default folder RUN/reproduce is made; a folder the user named must exist.
    if (!opts->out.empty() && !parent.empty() && !fs::is_directory(parent, ec))
      throw util::UserError("reproduce: --out " + path + ": the folder " + parent.string() +
                            " does not exist");
    const audit::Reproducer r = audit::make_reproducer(opts->q, path);
    try {
      if (opts->out.empty()) fs::create_directories(parent);
      util::write_file_atomic(path, r.source);
    } catch (const std::exception& e) {  // a full disk, a folder it may not write: said, exit 2
      throw util::UserError("reproduce: cannot write " + path + ": " + e.what());
    }
    std::printf(
        "wrote %s\nbuild: %s\nrun:   %s\nworker: %llu pixels (hash %llu), %s; reference: %llu "
        "pixels (hash %llu)\n",
        path.c_str(), r.build_line.c_str(), r.run_line.c_str(),
        static_cast<unsigned long long>(r.record_pixels),
        static_cast<unsigned long long>(r.record_hash), r.verdict.text.c_str(),
        static_cast<unsigned long long>(r.reference_pixels),
        static_cast<unsigned long long>(r.reference_hash));
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
