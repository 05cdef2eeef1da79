// Study kinds and study.json (study_dir.h).
#include "rundir/study_dir.h"

#include "rundir/manifest.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rundir/run_folder.h"
#include "util/atomic_file.h"
#include "util/errors.h"
#include "util/json_file.h"
#include "util/toml_locator.h"

namespace ra::rundir {

const char* study_kind_name(StudyKind kind) {
  switch (kind) {
    case StudyKind::kAudit: return "audit";
    case StudyKind::kTiming: return "timing";
    case StudyKind::kLod: return "lod";
    case StudyKind::kRegulation: return "regulation";
  }
  return "audit";
}

StudyKind experiment_study_kind(const std::string& experiment_path) {
  const util::TomlLocator loc(experiment_path);
  const toml::table root = loc.parse(util::TomlLocator::read_text(experiment_path));
  StudyKind kind = StudyKind::kAudit;
  const toml::node* first = nullptr;
  for (const auto& [key, k] : {std::pair<const char*, StudyKind>{"timing", StudyKind::kTiming},
                               {"lod", StudyKind::kLod},
                               {"regulation", StudyKind::kRegulation}}) {
    const toml::node* n = root.get(key);
    if (!n) continue;
    if (first)
      loc.fail(n, std::string("a file declares one study; this one has [") + study_kind_name(kind) +
                      "] and [" + key + "] (allowed: one of [timing], [lod], [regulation], or none "
                      "for the primitive audit)");
    first = n;
    kind = k;
  }
  return kind;
}

void write_study_info(const std::string& dir, const StudyInfo& info) {
  nlohmann::json j = {{"kind", study_kind_name(info.kind)},
                            {"name", info.name},
                            {"title", info.title},
                            {"subtitle", info.subtitle},
                            {"document", info.document},
                            {"analysed", info.analysed}};
  j.update(document_header("study", 1, false));
  util::write_file_atomic(run_folder::study(dir), j.dump(2) + "\n");
}

std::optional<StudyInfo> read_study_info(const std::string& dir) {
  const std::string path = run_folder::study(dir);
  if (!std::filesystem::exists(path)) return std::nullopt;
  StudyInfo info;
  try {
    const nlohmann::json j = util::parse_json_document(util::read_file(path), path);
    const std::string kind = j.at("kind").get<std::string>();
    bool known = false;
    for (StudyKind k : {StudyKind::kAudit, StudyKind::kTiming, StudyKind::kLod, StudyKind::kRegulation})
      if (kind == study_kind_name(k)) {
        info.kind = k;
        known = true;
      }
    if (!known) throw util::UserError(path + ": unknown study kind '" + kind + "'");
    info.name = j.at("name").get<std::string>();
    info.title = j.at("title").get<std::string>();
    info.subtitle = j.value("subtitle", "");
    info.document = j.value("document", "");
    info.analysed = j.value("analysed", false);
  } catch (const nlohmann::json::exception& e) {
    throw util::UserError(path + ": not a study description (" + e.what() + ")");
  }
  return info;
}

}  // namespace ra::rundir
