// Loading a driver build by absolute path, and listing what a process loaded (see the header).
#include "platforms/driver_loading.h"

#include <dlfcn.h>
#include <elf.h>
#include <fcntl.h>
#include <link.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <set>

#include "rundir/build_record.h"
#include "util/errors.h"
#include "util/fnv1a.h"

namespace fs = std::filesystem;

namespace ra::platforms {
namespace {

// The library a back end asks for by soname; the build must hold it.
std::string root_soname(const rundir::PlatformSpec& spec) {
  if (spec.backend == rundir::Backend::kVulkan) return "libvulkan_lvp.so";  // lavapipe
  return spec.backend == rundir::Backend::kOsmesa ? "libOSMesa.so.8" : "libEGL_mesa.so.0";
}

bool read_at(int fd, uint64_t offset, void* out, size_t n) {
  return ::pread(fd, out, n, off_t(offset)) == ssize_t(n);
}

// Files of a library folder by soname (symlinks resolved, one path per soname).
std::map<std::string, std::pair<std::string, ElfDependencies>> index_libraries(
    const std::string& lib_dir) {
  std::map<std::string, std::pair<std::string, ElfDependencies>> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(lib_dir, ec)) {
    const std::string name = e.path().filename().string();
    if (name.find(".so") == std::string::npos || !e.is_regular_file(ec)) continue;
    ElfDependencies deps = read_elf_dependencies(e.path().string());
    if (deps.soname.empty()) continue;
    const std::string path = fs::weakly_canonical(e.path(), ec).string();
    const std::string soname = deps.soname;  // before deps is moved
    out.emplace(soname, std::pair{path, std::move(deps)});
  }
  return out;
}

// What this process loaded for drawing, once: "" (the installed driver) or a library folder.
struct ProcessDriver {
  bool chosen = false;
  std::string lib_dir;
  std::string who;  // the platform that chose it, for messages
};
ProcessDriver& process_driver() {
  static ProcessDriver d;
  return d;
}

bool is_driver_library(const std::string& path) {
  const std::string base = fs::path(path).filename().string();
  for (const char* prefix : {"libOSMesa", "libEGL", "libGL", "libOpenGL", "libglapi", "libgallium",
                             "libLLVM", "libdrm", "libgbm", "libvulkan", "libnvidia", "libGLX"})
    if (base.rfind(prefix, 0) == 0) return true;
  return base.find("_dri.so") != std::string::npos || base.find("dri_gbm") != std::string::npos;
}

std::string fingerprint_file(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return "";
  util::Fnv1a64 h;
  std::vector<char> buf(1 << 20);
  for (ssize_t n; (n = ::read(fd, buf.data(), buf.size())) > 0;) h.add(buf.data(), size_t(n));
  ::close(fd);
  return util::hex64(h.value);
}

}  // namespace

ElfDependencies read_elf_dependencies(const std::string& path) {
  ElfDependencies out;
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return out;
  Elf64_Ehdr eh;
  std::vector<Elf64_Shdr> sh;
  const bool elf = read_at(fd, 0, &eh, sizeof eh) && std::memcmp(eh.e_ident, ELFMAG, SELFMAG) == 0 &&
                   eh.e_ident[EI_CLASS] == ELFCLASS64 && eh.e_shentsize == sizeof(Elf64_Shdr);
  if (elf) {
    sh.resize(eh.e_shnum);
    if (!read_at(fd, eh.e_shoff, sh.data(), sh.size() * sizeof(Elf64_Shdr))) sh.clear();
  }
  for (const Elf64_Shdr& s : sh) {
    if (s.sh_type != SHT_DYNAMIC || s.sh_link >= sh.size()) continue;
    std::vector<Elf64_Dyn> dyn(s.sh_size / sizeof(Elf64_Dyn));
    std::string strtab(sh[s.sh_link].sh_size, '\0');
    if (!read_at(fd, s.sh_offset, dyn.data(), dyn.size() * sizeof(Elf64_Dyn)) ||
        !read_at(fd, sh[s.sh_link].sh_offset, strtab.data(), strtab.size()))
      break;
    const auto str = [&](uint64_t at) {
      return at < strtab.size() ? std::string(strtab.c_str() + at) : std::string();
    };
    for (const Elf64_Dyn& d : dyn) {
      if (d.d_tag == DT_NEEDED) out.needed.push_back(str(d.d_un.d_val));
      if (d.d_tag == DT_SONAME) out.soname = str(d.d_un.d_val);
    }
    break;
  }
  ::close(fd);
  return out;
}

std::vector<LoadedLibrary> loaded_driver_libraries() {
  std::vector<std::string> paths;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* data) {
        auto* out = static_cast<std::vector<std::string>*>(data);
        if (info->dlpi_name && *info->dlpi_name && is_driver_library(info->dlpi_name))
          out->push_back(info->dlpi_name);
        return 0;
      },
      &paths);
  std::vector<LoadedLibrary> out;
  std::set<std::string> seen;
  for (const std::string& p : paths) {
    std::error_code ec;
    const std::string real = fs::weakly_canonical(p, ec).string();
    if (!seen.insert(real).second) continue;
    out.push_back({real, fingerprint_file(real)});
  }
  return out;
}

void load_driver_build(const rundir::PlatformSpec& spec) {
  ProcessDriver& current = process_driver();
  const std::string wanted = spec.build.empty() ? "" : rundir::build_library_dir(spec.build_dir);
  if (current.chosen) {
    if (current.lib_dir == wanted) return;
    const auto what = [](const std::string& d) {
      return d.empty() ? std::string("the installed driver") : "the build in " + d;
    };
    throw util::UserError(spec.name + ": this process already draws with " + what(current.lib_dir) +
                          " (for " + current.who +
                          "), and Mesa cannot be unloaded: one driver build "
                          "per process, so " +
                          what(wanted) + " needs a process of its own");
  }
  if (spec.build.empty()) {
    current = {true, "", spec.name};
    return;
  }
  if (spec.build_dir.empty())
    throw util::UserError(spec.name + ": driver build '" + spec.build + "' has no folder");
  const std::string root = root_soname(spec);
  const auto index = index_libraries(wanted);
  if (!index.count(root)) {
    throw util::UserError(
        spec.name + ": driver build '" + spec.build + "' (" + spec.build_dir + ") holds no " +
        root + " in " + wanted +
        "; fetch a build with `renderaudit builds fetch SUITE`, or name the folder "
        "where its packages were unpacked (dpkg-deb -x)");
  }
  // Refuse a process where the soname is already someone else's: our load would be ignored.
  if (void* h = dlopen(root.c_str(), RTLD_LAZY | RTLD_NOLOAD)) {
    link_map* map = nullptr;
    dlinfo(h, RTLD_DI_LINKMAP, &map);
    const std::string loaded = map && map->l_name ? map->l_name : "?";
    dlclose(h);
    throw util::UserError(spec.name + ": this process already loaded " + root + " from " + loaded +
                          ", so it cannot draw with driver build '" + spec.build + "'");
  }
  // Dependencies first: a library's needed soname must be loaded before it, or glibc would take
  // the system's. RTLD_LAZY: a symbol of a library the build lacks (libdrm_amdgpu of another
  // release) is resolved only if called, as Mesa's own loaders do.
  std::set<std::string> done;
  std::function<void(const std::string&)> load = [&](const std::string& soname) {
    if (!done.insert(soname).second) return;
    const auto it = index.find(soname);
    if (it == index.end()) return;  // the system's
    for (const std::string& n : it->second.second.needed) load(n);
    if (!dlopen(it->second.first.c_str(), RTLD_LAZY | RTLD_LOCAL)) {
      const char* why = dlerror();
      throw util::UserError(spec.name + ": driver build '" + spec.build + "': cannot load " +
                            it->second.first + " (" + (why ? why : "?") + ")");
    }
  };
  load(root);
  // Mesa before 24 loads its DRI driver (swrast_dri.so) by path, from LIBGL_DRIVERS_PATH when set.
  std::error_code ec;
  if (fs::is_directory(wanted + "/dri", ec)) setenv("LIBGL_DRIVERS_PATH", (wanted + "/dri").c_str(), 1);
  current = {true, wanted, spec.name};
}

}  // namespace ra::platforms
