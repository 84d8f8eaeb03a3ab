// A plugin that claims a future ABI version: the loader must refuse it and name the version.
#include <aquarelle/plugin.hpp>

namespace {
constexpr aq_port_desc kOut[] = {aq::image_port("image", "output")};
struct Nothing {
  int process(aq::Context&) { return AQ_OK; }
};
}  // namespace

AQ_NODE_NO_PARAMS(kNode, Nothing, "test_wrong_abi", "Test", "never loads", 0, kOut, kOut);

extern "C" AQ_PLUGIN_EXPORT const aq_plugin_desc* aquarelle_plugin_entry(uint32_t) {
  static const aq_node_desc* const nodes[] = {&kNode};
  static const aq_plugin_desc desc = {AQ_ABI_VERSION + 98, sizeof(aq_plugin_desc), "wrong_abi",
                                      "1.0", nodes, 1};
  return &desc;
}
