// The seal of a JSON state file (bisect.json): the fingerprint of everything else the document
// holds, written into it, so that a damaged copy (a flipped digit, a lost entry, a file cut short
// and mended by hand) is found before a single value of it is trusted, as a shard's seal finds a
// damaged records file. FNV-1a 64 of the compact text (nlohmann's dump(): keys sorted, numbers
// as they read back) of the document without its "seal" member, as 16 hex digits. Not a defence
// against deliberate tampering: every value read is still checked on its own.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace ra::util {

// The seal of `doc` (an object), leaving its "seal" member out.
std::string json_seal(const nlohmann::json& doc);

// `doc` with "seal" set to json_seal(doc).
nlohmann::json sealed(nlohmann::json doc);

// Empty when `doc` holds a "seal" equal to json_seal(doc); else what is wrong, in words ("'seal'
// is missing", "'seal' does not match the content: the file was changed after it was written").
std::string seal_problem(const nlohmann::json& doc);

}  // namespace ra::util
