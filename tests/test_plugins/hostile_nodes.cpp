// Test node types for tests/bad_input: `test_bad_format` asks the host for an image of an
// aq_format that does not exist (999); `test_slow` spins for `seconds` inside process (a long
// node, for the signal tests), checking nothing, as a hung node would.
#include <aquarelle/plugin.hpp>

#include <chrono>
#include <thread>

namespace {

constexpr aq_port_desc kImageIn[] = {aq::optional_image_port("image", "input")};
constexpr aq_port_desc kImageOut[] = {aq::image_port("image", "output")};
constexpr aq_param_desc kSlowParams[] = {
    aq::float_param("seconds", 60.0, 0.0, 3600.0, "time spent in process")};

struct BadFormat {
  int process(aq::Context& ctx) {
    aq_image out;
    return ctx.output(0, 8, 8, 999, &out) ? AQ_OK : AQ_ERROR;
  }
};

struct Slow {
  int process(aq::Context& ctx) {
    const auto until =
        std::chrono::steady_clock::now() + std::chrono::duration<double>(ctx.param_float(0));
    while (std::chrono::steady_clock::now() < until) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    aq_image out;
    return ctx.output(0, 4, 4, ctx.working_format(), &out) ? AQ_OK : AQ_ERROR;
  }
};

}  // namespace

AQ_NODE_NO_PARAMS(kBadFormat, BadFormat, "test_bad_format", "Test", "asks for format 999", 0,
                  kImageIn, kImageOut);
AQ_NODE(kSlow, Slow, "test_slow", "Test", "spins for `seconds`", 0, kImageIn, kImageOut,
        kSlowParams);
AQ_PLUGIN("test_hostile", "1.0", &kBadFormat, &kSlow)
