// A frame does not depend on how the range was cut (issue 21): a farm renders chunks of a
// range on different machines, so frame N rendered alone, inside the whole range or inside a
// chunk must be the same image bit for bit. Everything that carries state from one frame to
// the next (node caches, the reuse of static nodes' outputs, the shadow map's cache of still
// meshes, the pigment canvas, the texture pool) could break it. Each animated graph is
// rendered three ways by the command line, as a farm would run it, and every frame compared.
#include <gtest/gtest.h>

#include <aquarelle/core/color.h>
#include <aquarelle/core/image_io.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "app/cli_support.h"
#include "support/harness.h"

namespace aq::test {
namespace {

// Frames render in order, so frame 20 inside 1-48 has seen exactly what it sees inside 1-24:
// the whole range stops at the chunk's end to keep the test short.
constexpr const char* kSize = "96x54";
constexpr int kWholeFirst = 1, kWholeLast = 24;
constexpr int kChunkFirst = 17, kChunkLast = 24;
constexpr int kAlone = 20;

std::string frame_file(const std::filesystem::path& dir, int frame) {
  char name[32];
  std::snprintf(name, sizeof(name), "%04d.exr", frame);
  return (dir / name).string();
}

// A graph of graphs/ and the options it is rendered with.
struct Case {
  std::string graph, options, label;
};

void PrintTo(const Case& c, std::ostream* out) { *out << c.graph << c.options; }

// The caustic grid decides the cost of caustics.json (a 256 grid takes about a second a frame on
// llvmpipe); a coarser one animates the same way and keeps the test short.
std::string extra_options(const std::string& graph) {
  return graph == "caustics.json" ? " --set caustics.grid=64" : "";
}

// Methods a graph does not use by default but a user can pick: each carries its own state
// between frames. The layered node's `fast` method (layered.json's default) once drew its first
// frame without one of its inputs (a texture made between binding and drawing unbound it), so
// frame 20 after 19 differed from frame 20 alone; its `exact` method reads back per frame.
std::vector<Case> method_variants() {
  return {{"layered.json", " --set 'layered.method=\"exact\"'", "layered_exact"}};
}

void render(const Case& c, const std::filesystem::path& dir, const std::string& frames) {
  std::filesystem::create_directories(dir);
  auto run =
      aquarelle("render " + source_path("graphs/" + c.graph) + " -q --float --size " + kSize +
                c.options + " --frames " + frames + " -o " + (dir / "####.exr").string());
  ASSERT_EQ(run.exit_code, 0) << run.output;
}

// Bit for bit: the float pixels compared as bytes (NaN == NaN, -0 != +0).
void expect_same_frame(const std::string& a, const std::string& b, const std::string& what) {
  auto config = ColorConfig::load();
  ASSERT_TRUE(config.ok()) << config.message();
  auto first = read_image(a, *config);
  auto second = read_image(b, *config);
  ASSERT_TRUE(first.ok()) << first.message();
  ASSERT_TRUE(second.ok()) << second.message();
  ASSERT_EQ(first->pixels.size(), second->pixels.size()) << what;
  size_t differing = 0;
  for (size_t i = 0; i < first->pixels.size(); ++i) {
    if (std::memcmp(&first->pixels[i], &second->pixels[i], sizeof(float)) != 0) ++differing;
  }
  EXPECT_EQ(differing, 0u) << what << ": " << differing << " of " << first->pixels.size()
                           << " channel values differ (" << a << " vs " << b << ")";
}

class ChunkInvariance : public ::testing::TestWithParam<Case> {};

TEST_P(ChunkInvariance, FrameIsTheSameAloneInAChunkAndInTheWholeRange) {
  const Case& c = GetParam();
  const std::string graph = c.label;
  auto dir = scratch_dir("chunk_invariance_" + graph);
  render(c, dir / "whole", std::to_string(kWholeFirst) + "-" + std::to_string(kWholeLast));
  render(c, dir / "chunk", std::to_string(kChunkFirst) + "-" + std::to_string(kChunkLast));
  render(c, dir / "alone", std::to_string(kAlone));
  if (HasFatalFailure()) return;
  for (int frame = kChunkFirst; frame <= kChunkLast; ++frame) {
    expect_same_frame(frame_file(dir / "whole", frame), frame_file(dir / "chunk", frame),
                      graph + " frame " + std::to_string(frame) + ", whole range vs chunk");
  }
  expect_same_frame(frame_file(dir / "whole", kAlone), frame_file(dir / "alone", kAlone),
                    graph + " frame " + std::to_string(kAlone) + ", whole range vs alone");
  // Frames differ over time: otherwise the comparison above would prove nothing about state.
  auto config = ColorConfig::load();
  auto early = read_image(frame_file(dir / "whole", kChunkFirst), *config);
  auto late = read_image(frame_file(dir / "whole", kChunkLast), *config);
  ASSERT_TRUE(early.ok() && late.ok());
  EXPECT_GT(max_abs_diff(*early, *late), 0.0) << graph << " does not animate";
}

// Every animated graph of graphs/ (settings.frames longer than one frame), found when the test
// starts so a new graph is covered without an edit here.
std::vector<std::string> animated_graphs() {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(source_path("graphs"))) {
    if (entry.path().extension() != ".json") continue;
    std::ifstream in(entry.path());
    const auto graph = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
    const auto frames = graph.is_object() ? graph.value("settings", nlohmann::json::object())
                                                .value("frames", nlohmann::json::array())
                                          : nlohmann::json::array();
    if (frames.is_array() && frames.size() == 2 && frames[1].is_number() && frames[0].is_number() &&
        frames[1].get<int>() > frames[0].get<int>()) {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

// The animated graphs as they are, then the method variants of those that are animated.
std::vector<Case> cases() {
  std::vector<Case> all;
  const auto names = animated_graphs();
  for (const std::string& name : names) {
    all.push_back({name, extra_options(name), name.substr(0, name.find('.'))});
  }
  for (const Case& variant : method_variants()) {
    if (std::find(names.begin(), names.end(), variant.graph) != names.end()) {
      all.push_back(variant);
    }
  }
  return all;
}

TEST(ChunkInvarianceCoverage, FindsTheFlagshipAndTheOtherAnimatedGraphs) {
  const auto names = animated_graphs();
  for (const char* graph : {"underwater.json", "art_directed.json", "windmill.json"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), graph), names.end()) << graph;
  }
  const auto all = cases();
  for (const Case& variant : method_variants()) {
    EXPECT_NE(std::find_if(all.begin(), all.end(),
                           [&](const Case& c) { return c.label == variant.label; }),
              all.end())
        << variant.label << ": " << variant.graph << " is not animated any more";
  }
}

INSTANTIATE_TEST_SUITE_P(AnimatedGraphs, ChunkInvariance, ::testing::ValuesIn(cases()),
                         [](const auto& info) { return info.param.label; });

}  // namespace
}  // namespace aq::test
