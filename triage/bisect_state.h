// OUT/bisect.json: a bisection's inputs, selection and every built step, written after each step
// so that the same command resumes where it stopped. Read back field by field: a missing or
// mistyped field is a UserError naming the file and the key ("steps[3].commit"), never a JSON
// library message.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "triage/bisect.h"

namespace ra::triage {

struct BisectState {
  nlohmann::json inputs;   // what must match for a resume
  BisectResult result;
};

// The document written to bisect.json (schema "bisection", version 2).
nlohmann::json bisect_state_json(const BisectState& state);
void save_bisect_state(const std::string& path, const BisectState& state);

// The state in `path`, its steps, ends and original head read back; inputs as written.
BisectState load_bisect_state(const std::string& path);

}  // namespace ra::triage
