// OUT/bisect.json: a bisection's inputs, selection and every built step, written after each step
// so that the same command resumes where it stopped. Sealed (util/json_seal.h): a copy changed
// after it was written (a flipped digit of a pixel hash, a primitive lost from a drawing) is
// refused before any of it is used. Read back field by field: a missing or mistyped field is a
// UserError naming the file and the key ("steps[3].commit"), never a JSON library message; a commit
// is a full hash and the original head a branch name or a full hash (util/git_ref_check.h), so that no
// value reaches git as an option. Version 2 files, from before the seal, are read with the same
// checks of each field; the bisection checks every drawing against its selection on resume.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "rundir/bisection_document.h"
#include "triage/bisect_types.h"

namespace ra::triage {

struct BisectState {
  nlohmann::json inputs;   // what must match for a resume
  BisectResult result;
};

// The document written to bisect.json (schema rundir::kBisectionDocument, this version, sealed;
// rundir/bisection_document.h reads its header, and its culprits for the readers outside triage/).
constexpr int kBisectStateVersion = rundir::kBisectionDocumentVersion;
nlohmann::json bisect_state_json(const BisectState& state);
void save_bisect_state(const std::string& path, const BisectState& state);

// The state in `path`, its steps, ends and original head read back; inputs as written.
BisectState load_bisect_state(const std::string& path);

}  // namespace ra::triage
