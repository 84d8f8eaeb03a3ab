// Picking the EGL device: auto takes a GPU when EGL lists one (llvmpipe otherwise), software
// is Mesa's surfaceless platform, a number is an EGL device, anything else is a clear error.
#include <aquarelle/core/gl_context.h>
#include <gtest/gtest.h>

namespace aq {
namespace {

TEST(GlDevice, SoftwareAndAutoGiveACoreContext) {
  for (const char* device : {"software", "auto"}) {
    auto context = create_headless_context(GlBackend::kEgl, device);
    ASSERT_TRUE(context.ok()) << device << ": " << context.message();
    EXPECT_NE((*context)->description().find("4.5"), std::string::npos)
        << (*context)->description();
  }
}

TEST(GlDevice, AutoPrefersAHardwareDevice) {
  bool hardware = false;
  for (const std::string& d : egl_device_descriptions()) {
    hardware = hardware || d.find("(hardware)") != std::string::npos;
  }
  auto context = create_headless_context(GlBackend::kEgl, "auto");
  ASSERT_TRUE(context.ok()) << context.message();
  const bool software_renderer =
      (*context)->description().find("llvmpipe") != std::string::npos ||
      (*context)->description().find("softpipe") != std::string::npos;
  EXPECT_EQ(software_renderer, !hardware) << (*context)->description();
}

TEST(GlDevice, EveryListedDeviceCanBeChosenByIndex) {
  const std::vector<std::string> devices = egl_device_descriptions();
  for (size_t i = 0; i < devices.size(); ++i) {
    EXPECT_EQ(devices[i].rfind(std::to_string(i) + ": ", 0), 0u) << devices[i];
    auto context = create_headless_context(GlBackend::kEgl, std::to_string(i));
    EXPECT_TRUE(context.ok()) << devices[i] << ": " << context.message();
  }
}

TEST(GlDevice, AnUnknownDeviceIsRefusedWithTheList) {
  for (const char* device : {"99", "-1", "gpu", "1x"}) {
    auto context = create_headless_context(GlBackend::kAuto, device);
    ASSERT_FALSE(context.ok()) << device;
    EXPECT_NE(context.message().find("is not auto, software or the index"), std::string::npos)
        << context.message();
    for (const std::string& listed : egl_device_descriptions()) {
      EXPECT_NE(context.message().find(listed), std::string::npos) << context.message();
    }
  }
}

}  // namespace
}  // namespace aq
