// The host's own node types: `read` (an image file through OpenImageIO and OpenColorIO) and
// `image_input` (a CPU image handed to the evaluator, for tests and embedding). They need host
// libraries that plugins must not link, so they live in the core.
#pragma once

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/registry.h>

#include <filesystem>
#include <string>

namespace aq {

struct BuiltinState {
  std::string loaded_path;  // `read`: what is on the GPU now, to skip re-reading
  std::filesystem::file_time_type loaded_time{};
};

// Adds what a built-in node's result depends on beyond its parameters (file time, image data).
uint64_t builtin_key(const NodeType& type, const std::vector<aq_param_value>& params,
                     const EvalOptions& options, uint64_t key);

int run_builtin(const NodeType& type, BuiltinState& state, const aq_process_ctx& ctx,
                const EvalOptions& options, TexturePool& pool, std::vector<TextureRef>* outputs,
                std::string* error);

// Uploads a CPU image (1 to 4 channels) as an RGBA32F pool texture.
TextureRef upload_image(TexturePool& pool, const ImageF& image);

}  // namespace aq
