// Private to the core: what a loaded ColorConfig holds, shared by color.cpp,
// display_transform.cpp and image_io.cpp without exposing OpenColorIO in public headers.
#pragma once

#include <OpenColorIO/OpenColorIO.h>

#include <string>

namespace aq {

namespace OCIO = OCIO_NAMESPACE;

struct ColorConfigData {
  OCIO::ConstConfigRcPtr config;
  std::string path;
  std::string working_space;
};

}  // namespace aq
