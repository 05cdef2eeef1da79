// `run --expect-renderer REGEX`: stop a run as soon as a driver platform reports a GL_RENDERER
// that does not match (deqp-runner's --renderer-check), rather than audit the wrong driver for
// hours. Driver platforms are those drawn with GL (PlatformSpec::draws_with_gl); the project's own
// reference and test platforms are not checked.
#pragma once

#include <regex>
#include <set>
#include <string>

namespace ra {

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

}  // namespace ra
