#include "builds/git_command.h"

#include "util/child_process.h"

namespace ra::builds {

GitResult git(const std::string& dir, std::vector<std::string> args) {
  args.insert(args.begin(), {"git", "-C", dir, "-c", "advice.detachedHead=false"});
  util::ChildSpec spec;
  spec.argv = args;
  spec.stdin_null = true;
  spec.capture_output = true;
  const util::ProgramResult r = util::run_program(spec);
  GitResult g{r.exited_ok(), r.output};
  while (!g.out.empty() && (g.out.back() == '\n' || g.out.back() == ' ')) g.out.pop_back();
  return g;
}

}  // namespace ra::builds
