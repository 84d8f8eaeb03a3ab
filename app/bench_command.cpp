// `aquarelle bench`: placeholder entry until the benchmark lands (issue 7).
#include <cstdio>

#include "commands.h"

namespace aq::app {

int run_bench(int, char**) {
  std::fprintf(stderr, "aquarelle bench: not built yet in this version\n");
  return kExitEnvironment;
}

}  // namespace aq::app
