// The one rule every writer of Aquarelle follows (the command line's -o and --layer side
// files, the Python module, `bench --csv/--plot`): never write onto a file the evaluation reads
// (the graph, its images and meshes, the materials and textures those name, the colour config
// and its LUTs), however it is spelled (relative, `./`, a symbolic or hard link), and never
// onto something that is not a regular file (a FIFO blocks the writer, a device or folder is
// not an image).
#pragma once

#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>
#include <aquarelle/core/result.h>

#include <string>
#include <vector>

namespace aq {

class ColorConfig;

// A file that evaluating a graph reads, and what it is for messages ("the graph file",
// "the input file", "a texture named by materials.mtl").
struct ReadFile {
  std::string path;
  std::string role;
};

// Every file evaluating `graph` reads: the graph file, each path parameter resolved from the
// graph's folder as the evaluator resolves it, what those files name in turn (an OBJ's mtllib
// files and their map_* textures, a glTF's buffers and images) and, when given, the colour
// config and its LUT files. Over-inclusive on purpose: a name that might be read is kept.
std::vector<ReadFile> files_read_by(const Graph& graph, const Registry& registry,
                                    const ColorConfig* color = nullptr);

// Ok when `path` may be written by `option` ("-o", "--csv"...): it is none of `reads` and,
// when it exists, is a regular file. The error names the option, the path and what it is.
Status check_may_write(const std::string& option, const std::string& path,
                       const std::vector<ReadFile>& reads);

// The same with no graph: only the special-file refusal (Python's write_image).
Status check_may_write(const std::string& option, const std::string& path);

}  // namespace aq
