// Study kinds of experiment files and study.json: round trip, and located errors.
#include "rundir/study_dir.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "util/errors.h"

namespace ra::rundir {
namespace {

namespace fs = std::filesystem;

struct TempFolder {
  fs::path path;
  TempFolder() {
    path = fs::temp_directory_path() / ("ra-study-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempFolder() { fs::remove_all(path); }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream((path / name).string()) << text;
    return (path / name).string();
  }
};

TEST(StudyDir, KindFollowsTheTopLevelTable) {
  TempFolder t;
  EXPECT_EQ(experiment_study_kind(t.write("a.toml", "seed = 1\n[views]\norientations = 2\n")),
            StudyKind::kAudit);
  EXPECT_EQ(experiment_study_kind(t.write("t.toml", "[timing]\nrepetitions = 3\n")), StudyKind::kTiming);
  EXPECT_EQ(experiment_study_kind(t.write("l.toml", "name = \"x\"\n[lod]\ntau = [1]\n")), StudyKind::kLod);
  EXPECT_EQ(experiment_study_kind(t.write("r.toml", "[regulation]\n")), StudyKind::kRegulation);
}

TEST(StudyDir, TwoStudiesInOneFileAreLocated) {
  TempFolder t;
  const std::string path = t.write("two.toml", "[lod]\ntau = [1]\n[regulation]\nx = 1\n");
  try {
    experiment_study_kind(path);
    FAIL() << "no error";
  } catch (const util::UserError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind(path + ":3:1: a file declares one study; this one has [lod] and [regulation]", 0),
              0u)
        << what;
  }
  const std::string broken = t.write("broken.toml", "[lod\n");
  try {
    experiment_study_kind(broken);
    FAIL() << "no error";
  } catch (const util::UserError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(broken + ":1:", 0), 0u) << e.what();
  }
  EXPECT_THROW(experiment_study_kind((t.path / "missing.toml").string()), util::UserError);
}

TEST(StudyDir, InfoRoundTripsAndBadFilesAreNamed) {
  TempFolder t;
  EXPECT_FALSE(read_study_info(t.path.string()).has_value());
  StudyInfo in;
  in.kind = StudyKind::kRegulation;
  in.name = "reg";
  in.title = "A \"title\"";
  in.subtitle = "sub";
  in.document = "regulation.md";
  in.analysed = true;
  write_study_info(t.path.string(), in);
  const std::optional<StudyInfo> out = read_study_info(t.path.string());
  ASSERT_TRUE(out.has_value());
  EXPECT_EQ(out->kind, StudyKind::kRegulation);
  EXPECT_EQ(out->name, "reg");
  EXPECT_EQ(out->title, "A \"title\"");
  EXPECT_EQ(out->subtitle, "sub");
  EXPECT_EQ(out->document, "regulation.md");
  EXPECT_TRUE(out->analysed);

  t.write("study.json", "{\"kind\": \"castle\", \"name\": \"x\", \"title\": \"y\"}");
  try {
    read_study_info(t.path.string());
    FAIL() << "no error";
  } catch (const util::UserError& e) {
    EXPECT_NE(std::string(e.what()).find("unknown study kind 'castle'"), std::string::npos) << e.what();
  }
  t.write("study.json", "{\"kind\": \"lod\"");
  EXPECT_THROW(read_study_info(t.path.string()), util::UserError);
}

}  // namespace
}  // namespace ra::rundir
