// bisect.json read back for the readers outside triage/ (see the header).
#include "rundir/bisection_document.h"

#include "rundir/manifest.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/git_ref_check.h"
#include "util/json_file.h"
#include "util/json_seal.h"

namespace ra::rundir {
namespace {

using nlohmann::json;

const char* const kRemedy = "run the bisection again (renderaudit bisect) or move the file away";

// Field readers naming the file and the key of what is wrong.
struct Reader {
  std::string path;
  static std::string name_of(const std::string& where, const std::string& key) {
    return where.empty() ? key : where + "." + key;
  }
  [[noreturn]] void bad(const std::string& key, const std::string& what) const {
    throw util::UserError(path + ": '" + key + "' " + what + "; " + kRemedy);
  }
  const json& at(const json& j, const std::string& key, const std::string& where) const {
    if (!j.is_object()) bad(where.empty() ? "(top)" : where, "must be an object");
    const auto it = j.find(key);
    if (it == j.end()) bad(name_of(where, key), "is missing");
    return *it;
  }
  std::string text(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_string()) bad(name_of(where, key), "must be a string");
    return v.get<std::string>();
  }
  // A string the document may leave out: "" when absent.
  std::string optional_text(const json& j, const std::string& key, const std::string& where) const {
    return j.is_object() && j.contains(key) ? text(j, key, where) : "";
  }
  std::int64_t integer(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_number_integer()) bad(name_of(where, key), "must be a whole number");
    return v.get<std::int64_t>();
  }
  bool flag(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_boolean()) bad(name_of(where, key), "must be true or false");
    return v.get<bool>();
  }
  const json& list(const json& j, const std::string& key, const std::string& where) const {
    const json& v = at(j, key, where);
    if (!v.is_array()) bad(name_of(where, key), "must be a list");
    return v;
  }
};

BisectionCulprit read_culprit(const Reader& rd, const json& j, const std::string& where,
                              std::size_t selected) {
  BisectionCulprit c;
  c.commit = rd.text(j, "commit", where);
  if (const std::string problem = util::commit_hash_problem(c.commit); !problem.empty())
    rd.bad(where + ".commit", problem);
  c.subject = rd.text(j, "subject", where);
  c.date = rd.text(j, "date", where);
  const json& primitives = rd.list(j, "primitives", where);
  if (primitives.size() > selected)
    rd.bad(where + ".primitives", "lists " + std::to_string(primitives.size()) +
                                      " primitives, more than the " + std::to_string(selected) +
                                      " selected");
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const std::string at = where + ".primitives[" + std::to_string(i) + "]";
    c.primitives.push_back({rd.text(primitives[i], "primitive", at),
                            rd.integer(primitives[i], "pixels_before", at),
                            rd.integer(primitives[i], "pixels_after", at)});
  }
  return c;
}

// The fields of a document whose header and seal were checked.
BisectionDocument read_fields(const json& j, const std::string& path, int version) {
  const Reader rd{path};
  BisectionDocument d;
  d.path = path;
  d.version = version;
  const json& inputs = rd.at(j, "inputs", "");
  if (!inputs.is_object()) rd.bad("inputs", "must be an object");
  d.run = rd.optional_text(inputs, "run", "inputs");
  d.platform = rd.optional_text(inputs, "platform", "inputs");
  d.selected = rd.list(j, "selection", "").size();
  d.complete = rd.flag(j, "complete", "");
  const json& culprits = rd.list(j, "culprits", "");
  for (std::size_t i = 0; i < culprits.size(); ++i)
    d.culprits.push_back(
        read_culprit(rd, culprits[i], "culprits[" + std::to_string(i) + "]", d.selected));
  return d;
}

// The parsed file, or nullopt where it cannot be read or is not JSON (`why` then says so).
std::optional<json> parsed(const std::string& path, std::string* why) {
  try {
    return util::parse_json_document(util::read_file(path), path);
  } catch (const std::exception& e) {
    *why = e.what();
    return std::nullopt;
  }
}

// The document in `j` checked for its seal and read; a broken seal is a UserError.
BisectionDocument sealed_fields(const json& j, const std::string& path, int version) {
  if (const std::string problem = bisection_seal_problem(j, version); !problem.empty())
    throw util::UserError(path + ": " + problem + "; " + kRemedy);
  return read_fields(j, path, version);
}

}  // namespace

int bisection_version(const json& doc) {
  for (const int version : {kBisectionDocumentVersion, kUnsealedBisectionVersion})
    if (has_document_header(doc, kBisectionDocument, version)) return version;
  return 0;
}

std::string bisection_seal_problem(const json& doc, int version) {
  return version == kBisectionDocumentVersion ? util::seal_problem(doc) : "";
}

BisectionDocument read_bisection_document(const std::string& path) {
  std::string why;
  const std::optional<json> j = parsed(path, &why);
  if (!j) throw util::UserError(path + ": cannot read the bisection (" + why + ")");
  const int version = bisection_version(*j);
  if (version == 0)
    throw util::UserError(path + ": expected schema renderaudit-" +
                          std::string(kBisectionDocument) + " version " +
                          std::to_string(kBisectionDocumentVersion) + " or " +
                          std::to_string(kUnsealedBisectionVersion) +
                          " (a bisection of another renderaudit: " + kRemedy + ")");
  return sealed_fields(*j, path, version);
}

std::optional<BisectionDocument> read_bisection_document_if_any(const std::string& path) {
  std::string why;
  const std::optional<json> j = parsed(path, &why);
  if (!j) return std::nullopt;
  const int version = bisection_version(*j);
  if (version == 0) return std::nullopt;
  return sealed_fields(*j, path, version);
}

}  // namespace ra::rundir
