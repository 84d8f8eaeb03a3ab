// main() of every test executable (linked before GoogleTest's gtest_main, which it replaces):
// GoogleTest's usual main plus an environment that frees the harness's GL contexts after the
// last test and, under AddressSanitizer, keeps Mesa's EGL driver loaded (see below), so that
// leak checking at exit (scripts/sanitize.sh) sees only real leaks.
#include <aquarelle/core/gl_context.h>
#include <dlfcn.h>
#include <gtest/gtest.h>
#include <link.h>

#include <string>
#include <string_view>
#include <vector>

#include "support/harness.h"

namespace {

// Mesa's EGL unloads its DRI driver (swrast_dri.so: llvmpipe, and the libLLVM it pulls in)
// when a display's last context goes and the display is terminated. What the driver allocated
// once for the process (pthread_once initialisers run by eglInitialize: 128 + 2 x 56 bytes) is
// then pointed to only from the unmapped driver, so LeakSanitizer reports it at exit with
// `<unknown module>` frames that no suppression can name, once per load. Keeping the driver
// mapped until exit (RTLD_NODELETE) leaves that state reachable, as in a process that never
// terminates its display, and keeps the driver's frames named in any other report.
#if defined(__SANITIZE_ADDRESS__)
void keep_gl_drivers_loaded() {
  std::vector<std::string> drivers;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        const std::string_view name = info->dlpi_name != nullptr ? info->dlpi_name : "";
        if (name.ends_with("_dri.so") || name.find("/libLLVM") != std::string_view::npos) {
          static_cast<std::vector<std::string>*>(out)->emplace_back(name);
        }
        return 0;
      },
      &drivers);
  // Outside the iteration, which holds the loader's lock. The handles are never closed.
  for (const std::string& path : drivers) {
    dlopen(path.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
  }
}
#endif

class HarnessEnvironment : public ::testing::Environment {
 public:
  void SetUp() override {
#if defined(__SANITIZE_ADDRESS__)
    // Loads the driver through a throwaway context (eglInitialize loads it) before any test
    // makes and destroys its own.
    if (auto probe = aq::create_headless_context(aq::GlBackend::kEgl, "software"); probe.ok()) {
      keep_gl_drivers_loaded();
    }
#endif
  }
  // Before exit and its leak check; not from static destructors, where Mesa may already have
  // torn down its own state.
  void TearDown() override {
    aq::test::shutdown();
  }
};

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ::testing::AddGlobalTestEnvironment(new HarnessEnvironment());
  return RUN_ALL_TESTS();
}
