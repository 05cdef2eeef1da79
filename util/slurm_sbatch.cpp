// The sbatch scripts' shared parts (see the header).
#include "util/slurm_sbatch.h"

#include <sys/vfs.h>

#include <algorithm>
#include <filesystem>
#include <regex>

#include "util/child_process.h"
#include "util/errors.h"

namespace fs = std::filesystem;

namespace ra::util {
namespace {

constexpr long kTmpfsMagic = 0x01021994, kRamfsMagic = 0x858458f6;

// Why `value` cannot stand in an #SBATCH line, or "". sbatch reads those lines with a tokenizer of
// its own (no shell): white space ends a value (a newline would end the line, and the next one runs
// as a command), quotes and backslashes are consumed or fatal, '#' starts a comment, and in a file
// name '%' introduces a pattern (%j, %a). Such characters are refused rather than escaped: no
// quoting is carried the same way by every Slurm version.
std::string sbatch_value_problem(const std::string& value) {
  for (const char c : value) {
    const unsigned char u = static_cast<unsigned char>(c);
    if (c == '\n' || c == '\r') return "a line break would end the #SBATCH line";
    if (u < 0x20 || u == 0x7f) return "a control character cannot be carried";
    if (c == ' ') return "sbatch splits an #SBATCH line at white space";
    if (c == '\'' || c == '"' || c == '\\') return std::string("sbatch's #SBATCH parser consumes ") + c;
    if (c == '#') return "'#' starts a comment in an #SBATCH line";
    if (c == '%') return "sbatch expands '%' patterns (%j, %a) in file names";
  }
  return "";
}

}  // namespace

void require_sbatch_value(const std::string& what, const std::string& value) {
  if (const std::string why = sbatch_value_problem(value); !why.empty())
    throw util::UserError("--slurm: " + what + " '" + value +
                          "' cannot go into an sbatch script: " + why +
                          " (allowed: no white space, quotes, backslash, '#' or '%')");
}

// The values that reach #SBATCH lines: partition names as Slurm spells them (letters, digits, '_',
// '-', '.', and ',' between several), a time limit in sbatch --time syntax.
void validate_slurm_options(const SlurmOptions& slurm) {
  static const std::regex partition("[A-Za-z0-9_.-]+(,[A-Za-z0-9_.-]+)*");
  if (!slurm.partition.empty() && !std::regex_match(slurm.partition, partition))
    throw util::UserError("--partition '" + slurm.partition +
                          "': not a Slurm partition name (allowed: "
                          "letters, digits, '_', '-', '.', and ',' between several partitions)");
  static const std::regex time(
      "[0-9]+(:[0-9]+){0,2}|[0-9]+-[0-9]+(:[0-9]+){0,2}|UNLIMITED|INFINITE|unlimited|infinite");
  if (!slurm.time_limit.empty() && !std::regex_match(slurm.time_limit, time))
    throw util::UserError("--time-limit '" + slurm.time_limit +
                          "': not in sbatch --time syntax "
                          "(allowed: MINUTES, MINUTES:SECONDS, HOURS:MINUTES:SECONDS, DAYS-HOURS, "
                          "DAYS-HOURS:MINUTES, DAYS-HOURS:MINUTES:SECONDS, UNLIMITED)");
}

std::string sbatch_header(const std::string& job_name, int jobs, const SlurmOptions& slurm,
                          const std::string& log, bool requeue) {
  std::string s = "#!/bin/bash\n";
  s += "#SBATCH --job-name=" + job_name + "\n";
  s += "#SBATCH --cpus-per-task=" + std::to_string(jobs) + "\n";
  // --requeue: a node failure runs the task again (a slice resumes); else the submitter retries
  s += requeue ? "#SBATCH --requeue\n" : "#SBATCH --no-requeue\n";
  s += "#SBATCH --open-mode=append\n";  // a requeued task's log follows the first attempt's
  s += "#SBATCH --output=" + log + "\n";
  if (!slurm.partition.empty()) s += "#SBATCH --partition=" + slurm.partition + "\n";
  if (!slurm.time_limit.empty()) s += "#SBATCH --time=" + slurm.time_limit + "\n";
  return s;
}

std::string submit_sbatch(const SlurmOptions& slurm, const std::vector<std::string>& args,
                   const std::string& script_path) {
  util::ChildSpec spec;
  spec.argv = {slurm.sbatch, "--parsable"};
  spec.argv.insert(spec.argv.end(), args.begin(), args.end());
  spec.argv.push_back(script_path);
  spec.capture_output = true;
  spec.stdin_null = true;
  const util::ProgramResult r = util::run_program(spec);
  if (r.exit_code() == 127)
    throw util::UserError("--slurm: cannot run '" + slurm.sbatch +
                          "' (is this a Slurm login node? Debian: apt-get install slurm-client)");
  std::string out = r.output;
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  if (!r.exited_ok())
    throw util::UserError("--slurm: sbatch refused " + script_path + " (" +
                          util::describe_exit_status(r.status) + "): " + out);
  // --parsable prints "JOBID" or "JOBID;CLUSTER" as its last line
  std::string id = out.substr(out.find_last_of('\n') == std::string::npos ? 0
                                                                          : out.find_last_of('\n') + 1);
  id = id.substr(0, id.find(';'));
  if (id.empty() || !std::all_of(id.begin(), id.end(), ::isdigit))
    throw util::UserError("--slurm: sbatch answered '" + out + "', not a job id");
  return id;
}

std::string node_local_reason(const std::string& dir) {
  for (const char* prefix : {"/tmp", "/var/tmp", "/dev/shm", "/run"}) {
    const std::string p = prefix;
    if (dir == p || dir.rfind(p + "/", 0) == 0)
      return "is under " + p + ", which every node has its own of";
  }
  // the nearest existing ancestor's file system
  fs::path probe = dir;
  std::error_code ec;
  while (!probe.empty() && !fs::exists(probe, ec)) probe = probe.parent_path();
  struct statfs st {};
  if (!probe.empty() && ::statfs(probe.c_str(), &st) == 0 &&
      (long(st.f_type) == kTmpfsMagic || long(st.f_type) == kRamfsMagic))
    return "is on a tmpfs (the memory of one node)";
  return "";
}

}  // namespace ra::util
