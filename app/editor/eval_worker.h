// Evaluation off the UI thread: a worker thread with its own GL context, sharing objects with
// the window's, runs the Evaluator, so the UI keeps drawing (≥ 30 frames a second) while a
// slow graph evaluates or plays.
//
//   UI thread                           worker thread (shared GL context)
//   submit(request) ──► pending slot ──► Evaluator::evaluate ─► copy of the result into a
//   (latest wins)                         texture of its own ─► glFinish ─► finished slot
//   take_finished() ◄───────────────────────────────────────────────────────┘
//
// The copy belongs to the receiver: the evaluator's own textures (its pool and cache) are
// touched only by the worker. Requests that arrive while one runs replace each other, so the
// worker always goes on with the newest edit.
#pragma once

#include <aquarelle/core/evaluator.h>
#include <aquarelle/core/graph.h>
#include <aquarelle/core/registry.h>

#include <chrono>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace aq::editor {

struct EvalRequest {
  Graph graph;
  EvalOptions options;
  std::optional<PortRef> output;
  uint64_t tag = 0;  // the submitter's name for what it asked
};

struct EvalFinished {
  uint64_t tag = 0;
  uint32_t texture = 0;  // GL texture (shared), the receiver's to delete; 0 on error
  aq_image image{};      // image.texture == texture
  std::string error;     // "" on success
  double ms = 0;         // wall time of the evaluation
  std::vector<NodeTiming> timings;
  std::map<std::string, int> run_counts;  // per node, since the worker started
};

class EvalWorker {
 public:
  // `attach` makes a context that shares objects with the window's current on the calling
  // thread (it runs on the worker) and returns false when it cannot; `detach` releases it.
  EvalWorker(const Registry& registry, std::function<bool()> attach, std::function<void()> detach,
             void* (*get_proc_address)(const char*));
  // Inline: no thread; submit() evaluates at once on `context` (current on the caller's thread).
  // For tests with one headless context, and where no second context can be had.
  EvalWorker(const Registry& registry, GlContext& context);
  ~EvalWorker();
  EvalWorker(const EvalWorker&) = delete;
  EvalWorker& operator=(const EvalWorker&) = delete;

  void submit(EvalRequest request);
  std::optional<EvalFinished> take_finished();
  // A request waits or runs.
  bool busy() const;
  // Seconds the running evaluation has taken so far (0 when none runs).
  double running_seconds() const;
  // Run on the worker before its next evaluation.
  void clear_caches();
  void set_shader_hot_reload(bool enabled);
  // Why the worker could not start ("" when it runs).
  std::string start_error() const;

 private:
  void run();
  EvalFinished evaluate(Evaluator& evaluator, const EvalRequest& request);

  const Registry& registry_;
  std::function<bool()> attach_;
  std::function<void()> detach_;
  void* (*get_proc_address_)(const char*);

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::optional<EvalRequest> pending_;
  std::optional<EvalFinished> finished_;
  bool running_ = false;
  std::chrono::steady_clock::time_point started_{};
  bool stop_ = false;
  bool clear_ = false;
  std::optional<bool> hot_reload_;
  std::string start_error_;
  std::thread thread_;
  std::unique_ptr<Evaluator> inline_evaluator_;  // inline mode only
};

}  // namespace aq::editor
