// `renderaudit show RUN --platform P --kind K --view V --index I [--out FILE.png] [--scale S]`:
// one primitive of a run, re-rendered in this process, as a PNG (triage/primitive_image.h), and
// its record.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "app/commands.h"
#include "metrics/records.h"
#include "triage/primitive_image.h"
#include "util/cell_text.h"
#include "util/number_text.h"

namespace ra::app {
namespace {

// The measured columns of the record (status onwards), as the records file would hold them;
// columns that do not apply (empty cells) are left out.
std::string measured_fields(const metrics::Record& r) {
  std::ostringstream row;
  metrics::write_record(row, r);
  std::string line = row.str();
  if (!line.empty() && line.back() == '\n') line.pop_back();
  const std::vector<std::string> names = util::split_csv_line(metrics::records_header());
  const std::vector<std::string> values = util::split_csv_line(line);
  std::string out;
  bool measured = false;
  for (std::size_t i = 0; i < names.size() && i < values.size(); ++i) {
    measured = measured || names[i] == "status";
    if (!measured || values[i].empty()) continue;
    out += util::format_text("  %-16s %s\n", names[i].c_str(), values[i].c_str());
  }
  return out;
}

}  // namespace

void register_show_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand(
      "show",
      "Re-render one primitive of a run on a platform, in this process, and write it as a PNG:\n"
      "each window pixel a block (grey: lit by the platform and the reference rasterizer;\n"
      "orange: platform only; blue: reference only; black: lit where GL forbids it; hatched\n"
      "green: left dark where GL requires it; both ringed in magenta) and the ideal projection\n"
      "as a red line, with a legend of the colours and their counts under the picture. Where a\n"
      "window pixel is too small to see, an inset enlarges the pixels that differ.\n"
      "--against P2 draws the same primitive on P2 too (in a child process): the picture then\n"
      "shows the window pixels of both drawings and insets the pixels P2 draws otherwise, so that\n"
      "`show -p P --against P2` and `show -p P2 --against P` make a pair that compares.\n"
      "Prints the image's path and the primitive's record (visibility, pixels, metrics, "
      "ref_diff).");
  struct Options {
    triage::ShowRequest q;
  };
  const auto opts = std::make_shared<Options>();  // alive as long as the callbacks
  add_primitive_options(
      cmd, {opts->q.run_dir, opts->q.platform, opts->q.kind, opts->q.view, opts->q.index},
      "platform to render on (any known platform)");
  cmd->add_option("--out,-o", opts->q.out_path,
                  "PNG to write (default: RUN/show/PLATFORM.KIND.vVIEW.INDEX.png)");
  cmd->add_option("--against", opts->q.against,
                  "another platform drawing the same primitive, e.g. P@BUILD: the same window "
                  "pixels shown, the pixels it draws otherwise in an inset")
      ->option_text("P2");
  cmd->add_option("--scale", opts->q.scale,
                  "image pixels per window pixel (default: the image is about 512 px)")
      ->check(CLI::Range(1, triage::kMaxImageScale));
  cmd->callback([opts, &exit_code] {
    const triage::PrimitiveImage im = triage::show_primitive(opts->q);
    const geometry::View& v = im.view;
    std::printf(
        "wrote %s (%d x %d px: window pixels x %d-%d, y %d-%d of %d x %d, %d px each, in "
        "the top %d x %d; the legend under them)\n",
        im.path.c_str(), im.image_width, im.image_height, im.shown.x0, im.shown.x1 - 1, im.shown.y0,
        im.shown.y1 - 1, v.width, v.height, im.scale, im.width, im.height);
    if (!im.legend_note.empty()) std::fprintf(stderr, "renderaudit: %s\n", im.legend_note.c_str());
    // The legend's rows, as the picture gives them: one count per colour, each explained.
    for (const std::string& row : im.legend) std::printf("  %s\n", row.c_str());
    std::printf("%s %llu, view %d (group %s, fov %g deg, %d x %d px), platform %s:\n",
                im.record.kind.c_str(), static_cast<unsigned long long>(opts->q.index), v.id,
                v.group_name().c_str(), v.fov_deg, v.width, v.height, opts->q.platform.c_str());
    std::printf("%s", measured_fields(im.record).c_str());
    exit_code = kExitOk;
  });
}

}  // namespace ra::app
