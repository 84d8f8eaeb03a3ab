// A plugin whose node description is invalid (two inputs with the same name, a default out of
// its range): the loader must refuse it with the reason.
#include <aquarelle/plugin.hpp>

namespace {
constexpr aq_port_desc kIn[] = {aq::image_port("image", "a"), aq::image_port("image", "b")};
constexpr aq_port_desc kOut[] = {aq::image_port("image", "output")};
constexpr aq_param_desc kParams[] = {aq::float_param("gain", 5.0, 0.0, 1.0, "out of range")};
struct Nothing {
  int process(aq::Context&) { return AQ_OK; }
};
}  // namespace

AQ_NODE(kNode, Nothing, "test_bad_description", "Test", "invalid", 0, kIn, kOut, kParams);
AQ_PLUGIN("bad_description", "1.0", &kNode)
