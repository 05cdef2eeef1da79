// `run --expect-renderer REGEX`: stop a run as soon as a driver platform reports a GL_RENDERER
// that does not match (deqp-runner's --renderer-check), rather than audit the wrong driver for
// hours. Driver platforms are those drawn with GL or Vulkan (PlatformSpec::draws_with_driver;
// for Vulkan GL_RENDERER is the device name and GL_VERSION the API and driver); the project's own
// reference and test platforms are not checked.
#pragma once

#include <regex>
#include <set>
#include <string>

#include "rundir/platform_spec.h"

namespace ra::platforms {

struct DriverInfo;

// One driver per record: every process that draws for a run's platform (a worker, a retry, a part
// of a bisection, the audit's re-render, `show`) calls this before drawing. When the run's driver
// file DIR/drivers/PLATFORM.json exists and names another GL_RENDERER or GL_VERSION than the
// driver this process loaded, or a library (by file name) whose fingerprint differs from the one
// this process loaded, throws UserError starting with rundir::kDriverMismatch and naming both (callers
// stop with exit status 2; never a silent re-render on another driver). Does nothing for
// the non-GL platforms and when no driver file exists yet (the first worker writes it).
void require_run_driver(const std::string& run_dir, const std::string& platform,
                        const DriverInfo& loaded);

class RendererCheck {
 public:
  // An empty `pattern` checks nothing. Throws UserError for an invalid regex.
  RendererCheck(std::string run_dir, const std::string& pattern);
  // Reads the driver files workers have written since the last call (DIR/drivers/<platform>.json)
  // and returns why the run must stop ("osmesa-softpipe: GL_RENDERER 'softpipe' does not match
  // 'llvmpipe'"), or an empty string.
  std::string mismatch();

 private:
  std::string run_dir_, pattern_;
  std::regex regex_;
  std::set<std::string> checked_;
};

}  // namespace ra::platforms
