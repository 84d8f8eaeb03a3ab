// Tests of the node type registry: node_type_from_desc copies a valid plugin description and
// refuses each kind of invalid one with a reason naming the type, the plugin and the field;
// Registry refuses duplicate type names. No GL and no plugins needed: descriptions are built
// here as static data, the way a plugin would write them.
#include <gtest/gtest.h>

#include <aquarelle/core/registry.h>

#include <string>

namespace {

void* fake_create(const aq_host*) {
  return nullptr;
}
void fake_destroy(void*) {}
int fake_process(void*, aq_process_ctx*) {
  return AQ_OK;
}

constexpr aq_port_desc kInputs[] = {
    {"image", AQ_PORT_IMAGE, 0, "colour"},
    {"depth", AQ_PORT_IMAGE, AQ_PORT_OPTIONAL, "depth"},
    {"scene", AQ_PORT_SCENE, 0, "scene"},
};
constexpr aq_port_desc kOutputs[] = {{"image", AQ_PORT_IMAGE, 0, "blurred colour"}};
constexpr aq_param_desc kParams[] = {
    {"sigma", AQ_PARAM_FLOAT, {3, 0, 0}, 0, 50, 0.1, nullptr, nullptr, "slider", "width"},
    {"taps", AQ_PARAM_INT, {5, 0, 0}, 1, 31, 1, nullptr, nullptr, nullptr, nullptr},
    {"exact", AQ_PARAM_BOOL, {1, 0, 0}, 0, 1, 1, nullptr, nullptr, nullptr, nullptr},
    {"method", AQ_PARAM_ENUM, {1, 0, 0}, 0, 0, 0, nullptr, "gaussian|strided", "combo", nullptr},
    {"label", AQ_PARAM_STRING, {0, 0, 0}, 0, 0, 0, "hello", nullptr, nullptr, nullptr},
    {"lut", AQ_PARAM_PATH, {0, 0, 0}, 0, 0, 0, nullptr, nullptr, "file", nullptr},
    {"tint", AQ_PARAM_COLOR, {0, 0.07, 0.1}, 0, 1, 0, nullptr, nullptr, "color", nullptr},
    {"offset", AQ_PARAM_VEC3, {-1, 0, 2}, -5, 5, 0, nullptr, nullptr, nullptr, nullptr},
};

aq_node_desc valid_desc() {
  aq_node_desc desc{};
  desc.struct_size = sizeof(aq_node_desc);
  desc.type_name = "blur";
  desc.category = "Filter";
  desc.description = "blurs";
  desc.flags = AQ_NODE_TIME_DEPENDENT;
  desc.inputs = kInputs;
  desc.input_count = 3;
  desc.outputs = kOutputs;
  desc.output_count = 1;
  desc.params = kParams;
  desc.param_count = 8;
  desc.create = fake_create;
  desc.destroy = fake_destroy;
  desc.process = fake_process;
  return desc;
}

// Builds the type and returns the refusal reason ("" when accepted).
std::string refusal(const aq_node_desc& desc) {
  std::string why;
  const aq::NodeType type = aq::node_type_from_desc(desc, "libblur.so", &why);
  if (type.name.empty()) {
    EXPECT_FALSE(why.empty()) << "a refused type must say why";
    return why;
  }
  EXPECT_TRUE(why.empty()) << why;
  return "";
}

// A description with one parameter replaced.
std::string refusal_with_param(const aq_param_desc& param) {
  static aq_param_desc params[1];
  params[0] = param;
  aq_node_desc desc = valid_desc();
  desc.params = params;
  desc.param_count = 1;
  return refusal(desc);
}

TEST(NodeTypeFromDesc, CopiesEverythingFromAValidDescription) {
  const aq_node_desc desc = valid_desc();
  std::string why = "stale";
  const aq::NodeType type = aq::node_type_from_desc(desc, "libblur.so", &why);
  ASSERT_EQ(type.name, "blur") << why;
  EXPECT_TRUE(why.empty());
  EXPECT_EQ(type.category, "Filter");
  EXPECT_EQ(type.plugin_file, "libblur.so");
  EXPECT_EQ(type.desc, &desc);
  EXPECT_TRUE(type.time_dependent());
  EXPECT_FALSE(type.pointwise());
  ASSERT_EQ(type.inputs.size(), 3u);
  EXPECT_FALSE(type.inputs[0].optional);
  EXPECT_TRUE(type.inputs[1].optional);
  EXPECT_EQ(type.inputs[2].type, AQ_PORT_SCENE);
  ASSERT_EQ(type.params.size(), 8u);
  EXPECT_EQ(type.params[0].max_value, 50);
  EXPECT_EQ(type.params[0].ui_hint, "slider");
  EXPECT_EQ(type.params[1].ui_hint, "");  // NULL becomes empty
  const std::vector<std::string> methods{"gaussian", "strided"};
  EXPECT_EQ(type.params[3].enum_values, methods);
  EXPECT_EQ(type.params[4].default_string, "hello");
  EXPECT_EQ(type.params[5].default_string, "");
  EXPECT_DOUBLE_EQ(type.params[6].default_value[2], 0.1);

  EXPECT_EQ(type.input_index("depth"), 1);
  EXPECT_EQ(type.input_index("nope"), -1);
  EXPECT_EQ(type.output_index("image"), 0);
  EXPECT_EQ(type.param_index("offset"), 7);
  ASSERT_NE(type.input("scene"), nullptr);
  EXPECT_EQ(type.input("scene")->name, "scene");
  EXPECT_EQ(type.output("depth"), nullptr);
  ASSERT_NE(type.param("taps"), nullptr);
  EXPECT_EQ(type.param("taps")->type, AQ_PARAM_INT);
}

TEST(NodeTypeFromDesc, RefusesBadTypeNames) {
  aq_node_desc desc = valid_desc();
  desc.type_name = nullptr;
  EXPECT_NE(refusal(desc).find("type_name is NULL"), std::string::npos);
  for (const char* name : {"", "Blur", "my-blur", "blur.x", "blur "}) {
    desc.type_name = name;
    const std::string why = refusal(desc);
    EXPECT_NE(why.find("a-z, 0-9"), std::string::npos) << name << ": " << why;
    EXPECT_NE(why.find("libblur.so"), std::string::npos) << why;
  }
}

TEST(NodeTypeFromDesc, RefusesMissingEntryPointsAndOldStructs) {
  aq_node_desc desc = valid_desc();
  desc.process = nullptr;
  EXPECT_NE(refusal(desc).find("process"), std::string::npos);
  desc = valid_desc();
  desc.create = nullptr;
  EXPECT_NE(refusal(desc).find("create"), std::string::npos);
  desc = valid_desc();
  desc.destroy = nullptr;
  EXPECT_NE(refusal(desc).find("destroy"), std::string::npos);
  desc = valid_desc();
  desc.struct_size = 8;
  EXPECT_NE(refusal(desc).find("struct_size"), std::string::npos);
  desc = valid_desc();
  desc.flags = 1u << 7;
  EXPECT_NE(refusal(desc).find("unknown flags"), std::string::npos);
}

TEST(NodeTypeFromDesc, RefusesBadPorts) {
  aq_node_desc desc = valid_desc();
  desc.inputs = nullptr;
  EXPECT_NE(refusal(desc).find("NULL"), std::string::npos);

  static const aq_port_desc duplicate[] = {{"image", AQ_PORT_IMAGE, 0, nullptr},
                                           {"image", AQ_PORT_IMAGE, 0, nullptr}};
  desc = valid_desc();
  desc.inputs = duplicate;
  desc.input_count = 2;
  EXPECT_NE(refusal(desc).find("input 'image' is declared twice"), std::string::npos);

  static const aq_port_desc bad_type[] = {{"image", 9, 0, nullptr}};
  desc = valid_desc();
  desc.outputs = bad_type;
  EXPECT_NE(refusal(desc).find("output 'image' has unknown port type 9"), std::string::npos);

  static const aq_port_desc unnamed[] = {{nullptr, AQ_PORT_IMAGE, 0, nullptr}};
  desc = valid_desc();
  desc.outputs = unnamed;
  EXPECT_NE(refusal(desc).find("output 0 has no name"), std::string::npos);

  static const aq_port_desc bad_name[] = {{"Image", AQ_PORT_IMAGE, 0, nullptr}};
  desc = valid_desc();
  desc.inputs = bad_name;
  desc.input_count = 1;
  EXPECT_NE(refusal(desc).find("'Image'"), std::string::npos);

  // The same name as input and as output is normal (image in, image out).
  desc = valid_desc();
  EXPECT_EQ(refusal(desc), "");
}

TEST(NodeTypeFromDesc, RefusesBadParameters) {
  using P = aq_param_desc;
  EXPECT_NE(refusal_with_param(P{"s", AQ_PARAM_FLOAT, {60, 0, 0}, 0, 50, 0, 0, 0, 0, 0})
                .find("parameter 's' (float): default 60 is outside [0, 50]"),
            std::string::npos);
  EXPECT_NE(
      refusal_with_param(P{"s", AQ_PARAM_FLOAT, {1, 0, 0}, 5, 2, 0, 0, 0, 0, 0}).find("min <= max"),
      std::string::npos);
  EXPECT_NE(refusal_with_param(P{"n", AQ_PARAM_INT, {2.5, 0, 0}, 0, 9, 0, 0, 0, 0, 0})
                .find("not integral"),
            std::string::npos);
  EXPECT_NE(
      refusal_with_param(P{"b", AQ_PARAM_BOOL, {2, 0, 0}, 0, 1, 0, 0, 0, 0, 0}).find("not 0 or 1"),
      std::string::npos);
  EXPECT_NE(refusal_with_param(P{"e", AQ_PARAM_ENUM, {2, 0, 0}, 0, 0, 0, 0, "a|b", 0, 0})
                .find("default index 2 is not one of 0..1"),
            std::string::npos);
  EXPECT_NE(refusal_with_param(P{"e", AQ_PARAM_ENUM, {0, 0, 0}, 0, 0, 0, 0, nullptr, 0, 0})
                .find("enum_values"),
            std::string::npos);
  EXPECT_NE(refusal_with_param(P{"e", AQ_PARAM_ENUM, {0, 0, 0}, 0, 0, 0, 0, "a||b", 0, 0})
                .find("empty name"),
            std::string::npos);
  EXPECT_NE(refusal_with_param(P{"e", AQ_PARAM_ENUM, {0, 0, 0}, 0, 0, 0, 0, "a|b|a", 0, 0})
                .find("'a' is listed twice"),
            std::string::npos);
  EXPECT_NE(refusal_with_param(P{"c", AQ_PARAM_COLOR, {0, 1.5, 0}, 0, 1, 0, 0, 0, 0, 0})
                .find("default y 1.5 is outside [0, 1]"),
            std::string::npos);
  EXPECT_NE(refusal_with_param(P{"x", 42, {0, 0, 0}, 0, 1, 0, 0, 0, 0, 0}).find("unknown type 42"),
            std::string::npos);
  EXPECT_NE(refusal_with_param(P{nullptr, AQ_PARAM_FLOAT, {0, 0, 0}, 0, 1, 0, 0, 0, 0, 0})
                .find("parameter 0 has no name"),
            std::string::npos);
  EXPECT_NE(refusal_with_param(P{"Sigma", AQ_PARAM_FLOAT, {0, 0, 0}, 0, 1, 0, 0, 0, 0, 0})
                .find("'Sigma'"),
            std::string::npos);
  EXPECT_EQ(refusal_with_param(P{"s", AQ_PARAM_STRING, {0, 0, 0}, 0, 0, 0, nullptr, 0, 0, 0}), "");

  static const aq_param_desc twice[] = {{"s", AQ_PARAM_FLOAT, {0, 0, 0}, 0, 1, 0, 0, 0, 0, 0},
                                        {"s", AQ_PARAM_INT, {0, 0, 0}, 0, 1, 0, 0, 0, 0, 0}};
  aq_node_desc desc = valid_desc();
  desc.params = twice;
  desc.param_count = 2;
  EXPECT_NE(refusal(desc).find("parameter 's' is declared twice"), std::string::npos);
}

TEST(Registry, RefusesDuplicateNamesAndListsSorted) {
  aq::Registry registry;
  std::string why;
  aq::NodeType tint;
  tint.name = "tint";
  tint.plugin_file = "libtint.so";
  aq::NodeType blur;
  blur.name = "blur";
  blur.plugin_file = "libblur.so";
  EXPECT_TRUE(registry.add(tint, &why)) << why;
  EXPECT_TRUE(registry.add(blur, &why)) << why;

  aq::NodeType another_tint = tint;
  another_tint.plugin_file = "libother.so";
  EXPECT_FALSE(registry.add(another_tint, &why));
  EXPECT_NE(why.find("'tint'"), std::string::npos) << why;
  EXPECT_NE(why.find("libother.so"), std::string::npos) << why;
  EXPECT_NE(why.find("libtint.so"), std::string::npos) << why;
  EXPECT_EQ(registry.find("tint")->plugin_file, "libtint.so");  // the first one stays

  EXPECT_FALSE(registry.add(aq::NodeType{}, &why));
  EXPECT_EQ(registry.names(), (std::vector<std::string>{"blur", "tint"}));
  EXPECT_EQ(registry.find("nope"), nullptr);
  EXPECT_EQ(registry.types().size(), 2u);
}

TEST(Registry, NamesTypes) {
  EXPECT_STREQ(aq::port_type_name(AQ_PORT_IMAGE), "image");
  EXPECT_STREQ(aq::port_type_name(AQ_PORT_SCENE), "scene");
  EXPECT_STREQ(aq::port_type_name(static_cast<aq_port_type>(0)), "unknown");
  EXPECT_STREQ(aq::param_type_name(AQ_PARAM_FLOAT), "float");
  EXPECT_STREQ(aq::param_type_name(AQ_PARAM_ENUM), "enum");
  EXPECT_STREQ(aq::param_type_name(AQ_PARAM_PATH), "path");
  EXPECT_STREQ(aq::param_type_name(AQ_PARAM_VEC3), "vec3");
  EXPECT_STREQ(aq::param_type_name(static_cast<aq_param_type>(99)), "unknown");
}

}  // namespace
