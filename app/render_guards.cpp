#include "render_guards.h"

#include <aquarelle/core/color.h>
#include <aquarelle/core/graph_io.h>
#include <aquarelle/core/image_io.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <thread>

namespace aq::app {

namespace {

// A context is created in well under a second on llvmpipe; far longer is a hung driver.
constexpr auto kProbeTimeout = std::chrono::seconds(30);

std::string driver_environment() {
  std::string text;
  for (const char* name : {"GALLIUM_DRIVER", "MESA_LOADER_DRIVER_OVERRIDE", "LIBGL_ALWAYS_SOFTWARE",
                           "EGL_PLATFORM", "__EGL_VENDOR_LIBRARY_FILENAMES"}) {
    if (const char* value = std::getenv(name); value != nullptr) {
      text += std::string(text.empty() ? "" : ", ") + name + "=" + value;
    }
  }
  return text.empty() ? "no Mesa variables are set" : "set: " + text;
}

}  // namespace

Status probe_gl_in_child(GlBackend backend, const std::string& device) {
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t child = ::fork();
  if (child < 0) return Ok{};  // cannot probe: create the context directly, as before
  if (child == 0) {
    // The parent repeats any ordinary error itself; the child stays silent.
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0) {
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
    }
    auto context = create_headless_context(backend, device);
    ::_exit(context.ok() ? 0 : 3);
  }
  const auto deadline = std::chrono::steady_clock::now() + kProbeTimeout;
  int status = 0;
  while (true) {
    const pid_t done = ::waitpid(child, &status, WNOHANG);
    if (done == child) break;
    if (done < 0 && errno != EINTR) return Ok{};
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      return make_error(std::string("creating an OpenGL context (") + backend_name(backend) +
                        " backend) hung for 30 s; the GL driver is broken (" +
                        driver_environment() + "); try --gl egl or --gl osmesa");
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return make_error(std::string("the GL driver crashed (signal ") + std::to_string(signal) +
                      ", " + strsignal(signal) + ") while creating an OpenGL context (" +
                      backend_name(backend) + " backend); check the driver environment (" +
                      driver_environment() +
                      "; e.g. GALLIUM_DRIVER must be llvmpipe or softpipe, or unset) or choose "
                      "another backend with --gl egl|osmesa");
  }
  return Ok{};
}

std::vector<ReadFile> graph_input_files(const Graph& graph, const Registry& registry) {
  auto color = ColorConfig::load();  // a broken config is reported where it is used
  return files_read_by(graph, registry, color.ok() ? &*color : nullptr);
}

Status check_frame_outputs(const std::string& frame_file, const std::string& layers_file,
                           const std::vector<ReadFile>& reads) {
  if (auto s = check_may_write("-o", frame_file, reads); !s.ok()) return s;
  if (!layers_file.empty() && layers_file != frame_file) {
    if (auto s = check_may_write("--layer's side file", layers_file, reads); !s.ok()) return s;
  }
  return Ok{};
}

namespace {

volatile std::sig_atomic_t g_stop = 0;

void write_text(const char* text) {
  ssize_t ignored = ::write(STDERR_FILENO, text, std::strlen(text));
  (void)ignored;
}

void forced_stop(int) {
  remove_temporary_in_progress();
  write_text(
      "\naquarelle render: interrupted inside a frame; complete frames are kept, run again "
      "with --resume to finish\n");
  ::_exit(130);
}

void on_stop_signal(int) {
  if (g_stop) forced_stop(0);  // a second signal: no more waiting
  g_stop = 1;
  ::alarm(kStopGraceSeconds);
}

}  // namespace

void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  action.sa_flags = SA_RESTART;  // a read interrupted by the signal must not fail as bad input
  sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, nullptr);
  ::sigaction(SIGTERM, &action, nullptr);
  struct sigaction alarm_action {};
  alarm_action.sa_handler = forced_stop;
  alarm_action.sa_flags = SA_RESTART;
  sigemptyset(&alarm_action.sa_mask);
  ::sigaction(SIGALRM, &alarm_action, nullptr);
}

bool stop_requested() {
  return g_stop != 0;
}

void cancel_forced_stop() {
  ::alarm(0);
}

}  // namespace aq::app
