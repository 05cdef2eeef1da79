// bisect.json read back for the readers outside triage/: the document `renderaudit bisect` writes
// and resumes from (triage/bisect_state.h, which keeps the reading of its full state), here its
// header and what a later reader needs of it: the inputs that say which run and platform it drew,
// whether it is complete, and its culprits with the primitives each changed. The driver upgrade
// report (report/upgrade_sentences.h) names them. Each field is checked; a damaged file is a
// UserError naming the file and the key ("culprits[0].commit"), never a JSON library message.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace ra::rundir {

// bisect.json's document name and versions: version 3 is sealed (util/json_seal.h); version 2,
// written before the seal, is still read, each field checked on its own.
inline constexpr const char* kBisectionDocument = "bisection";
inline constexpr int kBisectionDocumentVersion = 3;
inline constexpr int kUnsealedBisectionVersion = 2;

// The version of the bisection document `doc` (kBisectionDocumentVersion or
// kUnsealedBisectionVersion), or 0 when it is no bisection this renderaudit reads (another schema
// or version, not an object).
int bisection_version(const nlohmann::json& doc);

// What is wrong with the seal of `doc`, a document of `version` ("'seal' does not match the
// content: ..."), or "" when it holds; always "" for a version from before the seal.
std::string bisection_seal_problem(const nlohmann::json& doc, int version);

// A primitive a culprit changed: its label ("line 3 of view 5") and its lit pixels before and
// after the commit.
struct BisectionPrimitive {
  std::string label;
  std::int64_t pixels_before = 0, pixels_after = 0;
};

// A culprit: the first commit that drew some primitives otherwise.
struct BisectionCulprit {
  std::string commit;  // a full hash
  std::string subject, date;
  std::vector<BisectionPrimitive> primitives;  // in selection order
};

struct BisectionDocument {
  std::string path;
  int version = 0;
  std::string run;       // inputs.run: the run whose changes it followed ("" where not said)
  std::string platform;  // inputs.platform: the platform it drew with ("" where not said)
  std::size_t selected = 0;  // the primitives it followed (`selection`, counted)
  bool complete = false;     // every change attributed or found unattributable
  std::vector<BisectionCulprit> culprits;
};

// The bisection in `path`. Throws util::UserError naming the file: unreadable, not JSON, another
// schema or version, a broken seal, a field missing or mistyped (and the key), a culprit that is
// not a full commit hash or lists more primitives than were selected.
BisectionDocument read_bisection_document(const std::string& path);

// The same for a reader that looks for bisections among files: nullopt where `path` is not a
// bisection at all (unreadable, not JSON, another schema or version), which such a reader passes
// by; a bisection that is damaged is still a UserError.
std::optional<BisectionDocument> read_bisection_document_if_any(const std::string& path);

}  // namespace ra::rundir
