// aq_host::read_image: plugins read image files (textures of a mesh) through the host's image
// I/O, so they decode and colour-manage exactly as the `read` node does without linking
// OpenImageIO and OpenColorIO themselves. Internal to the core library.
#pragma once

#include <aquarelle/plugin.h>

namespace aq {

int host_read_image(void* host_data, const char* path,
                    void (*receive)(void* user, const float* rgba, int32_t width, int32_t height),
                    void* user, char* error, size_t error_size);

}  // namespace aq
