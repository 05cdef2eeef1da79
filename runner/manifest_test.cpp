// Tests of runner/manifest.h's write_manifest on a full disk: the manifest on disk must never stay
// "running" when the final write fails.
#include "runner/manifest.h"

#include <gtest/gtest.h>
#include <sys/mount.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "util/atomic_file.h"

namespace ra {
namespace {

TEST(Manifest, OnAFullDiskTheManifestSaysFailedInPlace) {
  const auto dir = std::filesystem::temp_directory_path() / ("ra_manifest_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  if (::mount("tmpfs", dir.c_str(), "tmpfs", 0, "size=256k") != 0)
    GTEST_SKIP() << "cannot mount a tmpfs here (not root?): " << std::strerror(errno);
  const std::string path = (dir / "manifest.json").string();
  nlohmann::json m = {{"schema_version", kManifestSchemaVersion},
                      {"status", "running"},
                      {"experiment", {{"name", "x"}, {"hash", "abc"}}},
                      {"invocations", nlohmann::json::array({{{"started", "t"}}})}};
  write_manifest(path, m);
  {  // fill the disk
    std::ofstream fill(dir / "fill", std::ios::binary);
    const std::string block(4096, 'x');
    while (fill.write(block.data(), block.size())) {
    }
  }
  m["status"] = "complete";
  m["drivers"] = std::string(20000, 'd');  // larger than the file that is there
  try {
    write_manifest(path, m);
    ADD_FAILURE() << "writing on a full disk succeeded";
  } catch (const std::runtime_error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("No space left on device"), std::string::npos) << msg;
    EXPECT_NE(msg.find("bytes free on the file system of " + dir.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("now says \"failed\""), std::string::npos) << msg;
  }
  const nlohmann::json on_disk = nlohmann::json::parse(read_file(path));
  EXPECT_EQ(on_disk["status"], "failed");
  // What fits of the reason is kept (here the whole manifest was small: its start).
  EXPECT_EQ(on_disk.value("reason", "").rfind("cannot write the manifest: cannot write", 0), 0u)
      << on_disk.dump();
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  ::umount(dir.c_str());
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace ra
