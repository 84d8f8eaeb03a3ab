// Node types for editor tests that need no plugins: `source` (one image output) and `filter`
// (image and optional mask in, image out, a float `amount` in [0, 10]).
#pragma once

#include <aquarelle/core/registry.h>

#include <gtest/gtest.h>

#include <string>

namespace aq::test {

inline PortInfo image_port(const std::string& name) {
  PortInfo info;
  info.name = name;
  info.type = AQ_PORT_IMAGE;
  info.optional = name != "image";
  return info;
}

inline const Registry& fake_registry() {
  static const Registry r = [] {
    Registry out;
    std::string why;
    NodeType source;
    source.name = "source";
    source.outputs = {image_port("image")};
    EXPECT_TRUE(out.add(source, &why)) << why;
    NodeType filter;
    filter.name = "filter";
    filter.inputs = {image_port("image"), image_port("mask")};
    filter.outputs = {image_port("image")};
    ParamInfo amount;
    amount.name = "amount";
    amount.type = AQ_PARAM_FLOAT;
    amount.default_value[0] = 1.0;
    amount.min_value = 0.0;
    amount.max_value = 10.0;
    filter.params = {amount};
    EXPECT_TRUE(out.add(filter, &why)) << why;
    return out;
  }();
  return r;
}

}  // namespace aq::test
