// Shared by the tests/bad_input suite (issue 17): small hostile files made at test time,
// FIFOs, the scene -> gbuffer graph that loads a mesh file, and the command line with a
// time limit (a hang fails the test instead of stalling CI).
#pragma once

#include <aquarelle/core/image.h>
#include <aquarelle/core/result.h>
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test::bad_input {

namespace fs = std::filesystem;

inline void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

inline std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

inline fs::path make_fifo(const fs::path& path) {
  fs::remove(path);
  EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0) << path;
  return path;
}

inline uint32_t crc32(const std::string& bytes) {
  uint32_t crc = 0xFFFFFFFFu;
  for (unsigned char byte : bytes) {
    crc ^= byte;
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xEDB88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

inline std::string big_endian(uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
          static_cast<char>(v)};
}

inline std::string png_chunk(const std::string& type, const std::string& data) {
  return big_endian(static_cast<uint32_t>(data.size())) + type + data +
         big_endian(crc32(type + data));
}

inline std::string base64(const std::string& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out += table[(v >> s) & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += table[(v >> 18) & 63];
    out += table[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

// One triangle's positions as little-endian floats (36 bytes).
inline std::string triangle_bytes() {
  const float p[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  return std::string(reinterpret_cast<const char*>(p), sizeof(p));
}

// A glTF whose node 0 holds the triangle, under a chain of `depth` nodes.
inline std::string gltf_chain(int depth, const std::string& buffer_uri) {
  nlohmann::json nodes = nlohmann::json::array();
  for (int i = 0; i < depth; ++i) {
    nlohmann::json node = nlohmann::json::object();
    if (i + 1 < depth) node["children"] = {i + 1};
    if (i + 1 == depth) node["mesh"] = 0;
    nodes.push_back(node);
  }
  nlohmann::json gltf = {{"asset", {{"version", "2.0"}}},
                         {"scene", 0},
                         {"scenes", {{{"nodes", {0}}}}},
                         {"nodes", nodes},
                         {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
                         {"buffers", {{{"byteLength", 36}, {"uri", buffer_uri}}}},
                         {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}}}},
                         {"accessors",
                          {{{"bufferView", 0},
                            {"componentType", 5126},
                            {"count", 3},
                            {"type", "VEC3"},
                            {"min", {-1, -1, 0}},
                            {"max", {1, 1, 0}}}}}};
  return gltf.dump();
}

inline std::string data_uri(const std::string& bytes) {
  return "data:application/octet-stream;base64," + base64(bytes);
}

// scene(file PATH) -> gbuffer; the albedo shows what was loaded.
inline std::string mesh_graph(const std::string& path) {
  nlohmann::json graph = {
      {"aquarelle", 1},
      {"settings", {{"width", 64}, {"height", 64}, {"frames", {1, 1}}, {"precision", "float"}}},
      {"nodes",
       {{"model",
         {{"type", "scene"},
          {"params",
           {{"preset", "file"},
            {"path", path},
            {"camera_position", {0, 0, 3}},
            {"camera_target", {0, 0, 0}}}}}},
        {"gbuf", {{"type", "gbuffer"}, {"inputs", {{"scene", "model.scene"}}}}}}},
      {"output", "gbuf.albedo"}};
  return graph.dump(2);
}

inline Result<ImageF> load_mesh(const fs::path& path) {
  RenderOptions options;
  options.output = "gbuf.albedo";
  return render_graph(mesh_graph(path.string()), options);
}

// The fraction of pixels something was drawn on (albedo alpha or colour non-zero).
inline double covered(const ImageF& image) {
  size_t hits = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      if (image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2) > 0) ++hits;
    }
  }
  return static_cast<double>(hits) / (static_cast<double>(image.width) * image.height);
}

// The plugin path with the hostile test nodes (test_bad_format, test_slow) and the build's.
inline std::string hostile_plugin_path() {
  return std::string(AQ_BUILD_DIR) + "/test_plugins_hostile:" + AQ_PLUGIN_BUILD_DIR;
}

// `aquarelle ARGS` with a time limit: a hang ends as exit code 124 instead of stalling.
inline CommandResult aquarelle_within(int seconds, const std::string& arguments,
                                      const std::string& environment = "") {
  return run_command("timeout -s KILL " + std::to_string(seconds) + " env " + environment + " " +
                     AQ_APP_PATH + " " + arguments);
}

// `aquarelle ARGS` run as its own child, with what it cost: the peak resident memory of it and
// its descendants (wait4's rusage) and the wall time. A hang ends as exit code 137.
struct MeasuredRun {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
  long peak_kib = 0;
  double seconds = 0;
};

inline MeasuredRun aquarelle_measured(int seconds, const std::string& arguments,
                                      const std::string& environment = "") {
  const std::string command = "exec timeout -s KILL " + std::to_string(seconds) + " env " +
                              environment + " " + AQ_APP_PATH + " " + arguments;
  MeasuredRun run;
  int out[2];
  if (::pipe(out) != 0) return run;
  const auto start = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child == 0) {
    ::dup2(out[1], 1);
    ::dup2(out[1], 2);
    ::close(out[0]);
    ::close(out[1]);
    ::execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(out[1]);
  char buffer[4096];
  for (ssize_t n; (n = ::read(out[0], buffer, sizeof(buffer))) > 0;) run.output.append(buffer, n);
  ::close(out[0]);
  int status = 0;
  struct rusage usage {};
  if (child > 0 && ::wait4(child, &status, 0, &usage) == child) {
    run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    run.peak_kib = usage.ru_maxrss;
  }
  run.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

// The number of lines of a message (a refusal is one line).
inline int line_count(const std::string& text) {
  int lines = 0;
  for (char c : text) lines += c == '\n';
  return lines + (!text.empty() && text.back() != '\n');
}

}  // namespace aq::test::bad_input
