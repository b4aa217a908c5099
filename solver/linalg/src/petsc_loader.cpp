#include "petsc_loader.h"

#include <throng/core/errors.h>

#include <dlfcn.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace throng::linalg::petsc {
namespace {

// Where to look, in order: beside the running executable (throng-main and the plugin are kept together), then
// where this build made it (the tests and benchmarks, which live in other folders of the build).
std::vector<std::filesystem::path> candidates() {
  std::vector<std::filesystem::path> paths;
  std::error_code error;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) paths.push_back(self.parent_path() / plugin_file);
#ifdef THRONG_PETSC_PLUGIN_PATH
  // Once: for throng-main in the build, both are the same file.
  const std::filesystem::path built = THRONG_PETSC_PLUGIN_PATH;
  if (paths.empty() ||
      std::filesystem::weakly_canonical(paths[0], error) != std::filesystem::weakly_canonical(built, error)) {
    paths.push_back(built);
  }
#endif
  return paths;
}

}  // namespace

const Plugin& load_plugin(const std::vector<std::filesystem::path>& paths) {
  std::string tried;
  for (const std::filesystem::path& path : paths) {
    // RTLD_GLOBAL: PETSc's libraries as the program's own would be, for what they look up among loaded symbols.
    void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (handle == nullptr) {
      const char* error = ::dlerror();
      std::string why = error != nullptr ? error : "cannot be loaded";
      // dlopen's message names the file when it is the file that fails (not a library it needs): once is enough.
      if (why.rfind(path.string() + ": ", 0) == 0) why.erase(0, path.string().size() + 2);
      tried += (tried.empty() ? "" : "; ") + path.string() + ": " + why;
      continue;
    }
    const auto entry = reinterpret_cast<ThrongPetscPluginEntry>(::dlsym(handle, "throng_petsc_plugin"));
    const Plugin* plugin = entry != nullptr ? entry() : nullptr;
    if (plugin == nullptr || std::strcmp(plugin->token, THRONG_PETSC_PLUGIN_TOKEN) != 0 ||
        plugin->options_size != sizeof(SolverOptions)) {
      tried += (tried.empty() ? "" : "; ") + path.string() + ": not this build's plugin";
      continue;  // left loaded: unloading a library that may have started threads or handlers is not safe
    }
    return *plugin;
  }
  throw ConfigError(std::string("solver backend 'petsc': its plugin ") + plugin_file + " cannot be loaded (" + tried +
                    "); keep it beside throng-main, or use backend: eigen");
}

const Plugin& loaded_plugin() {
  static const Plugin& plugin = load_plugin(candidates());  // a failure is not kept: the next call tries again
  return plugin;
}

}  // namespace throng::linalg::petsc
