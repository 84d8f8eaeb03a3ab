// The evaluation worker thread. See eval_worker.h.
#include "eval_worker.h"

#include <aquarelle/core/gl_context.h>
#include <glad/gl.h>

namespace aq::editor {

namespace {

void delete_texture(uint32_t texture) {
  if (texture != 0) glDeleteTextures(1, &texture);
}

// A texture of the same size and format holding the result, with the pool's sampling state.
uint32_t copy_of(const aq_image& image) {
  GLint internal = 0;
  glGetTextureLevelParameteriv(image.texture, 0, GL_TEXTURE_INTERNAL_FORMAT, &internal);
  GLuint copy = 0;
  glCreateTextures(GL_TEXTURE_2D, 1, &copy);
  glTextureStorage2D(copy, 1, static_cast<GLenum>(internal), image.width, image.height);
  const bool integer = image.format == AQ_FORMAT_R32UI || image.format == AQ_FORMAT_RGBA32UI;
  glTextureParameteri(copy, GL_TEXTURE_MIN_FILTER, integer ? GL_NEAREST : GL_LINEAR);
  glTextureParameteri(copy, GL_TEXTURE_MAG_FILTER, integer ? GL_NEAREST : GL_LINEAR);
  glTextureParameteri(copy, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTextureParameteri(copy, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  glCopyImageSubData(image.texture, GL_TEXTURE_2D, 0, 0, 0, 0, copy, GL_TEXTURE_2D, 0, 0, 0, 0,
                     image.width, image.height, 1);
  return copy;
}

}  // namespace

EvalWorker::EvalWorker(const Registry& registry, std::function<bool()> attach,
                       std::function<void()> detach, void* (*get_proc_address)(const char*))
    : registry_(registry),
      attach_(std::move(attach)),
      detach_(std::move(detach)),
      get_proc_address_(get_proc_address) {
  thread_ = std::thread([this] { run(); });
}

EvalWorker::EvalWorker(const Registry& registry, GlContext& context)
    : registry_(registry),
      get_proc_address_(nullptr),
      inline_evaluator_(std::make_unique<Evaluator>(context, registry)) {}

EvalWorker::~EvalWorker() {
  if (inline_evaluator_) {
    if (finished_) delete_texture(finished_->texture);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

void EvalWorker::submit(EvalRequest request) {
  if (inline_evaluator_) {
    if (clear_) inline_evaluator_->clear();
    if (hot_reload_) inline_evaluator_->set_shader_hot_reload(*hot_reload_);
    clear_ = false;
    hot_reload_.reset();
    EvalFinished done = evaluate(*inline_evaluator_, request);
    if (finished_) delete_texture(finished_->texture);
    finished_ = std::move(done);
    return;
  }
  {
    std::lock_guard lock(mutex_);
    pending_ = std::move(request);
  }
  wake_.notify_all();
}

std::optional<EvalFinished> EvalWorker::take_finished() {
  std::lock_guard lock(mutex_);
  std::optional<EvalFinished> out = std::move(finished_);
  finished_.reset();
  return out;
}

bool EvalWorker::busy() const {
  std::lock_guard lock(mutex_);
  return pending_.has_value() || running_;
}

double EvalWorker::running_seconds() const {
  std::lock_guard lock(mutex_);
  if (!running_) return 0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
}

void EvalWorker::clear_caches() {
  std::lock_guard lock(mutex_);
  clear_ = true;
}

void EvalWorker::set_shader_hot_reload(bool enabled) {
  std::lock_guard lock(mutex_);
  hot_reload_ = enabled;
}

std::string EvalWorker::start_error() const {
  std::lock_guard lock(mutex_);
  return start_error_;
}

EvalFinished EvalWorker::evaluate(Evaluator& evaluator, const EvalRequest& request) {
  EvalFinished done;
  done.tag = request.tag;
  const auto start = std::chrono::steady_clock::now();
  auto evaluated = evaluator.evaluate(request.graph, request.options, request.output);
  if (evaluated) {
    done.image = (*evaluated)->image;
    done.texture = copy_of(done.image);
    done.image.texture = done.texture;
  } else {
    done.error = evaluated.message();
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  glFinish();  // the copy is complete before the UI's context samples it
  done.timings = evaluator.last_timings();
  done.run_counts = evaluator.run_counts();
  done.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return done;
}

void EvalWorker::run() {
  if (!attach_()) {
    std::lock_guard lock(mutex_);
    start_error_ = "cannot create the evaluation thread's OpenGL context";
    // Requests are answered with the error so the viewer says why it shows nothing.
  }
  std::unique_ptr<GlContext> context;
  std::unique_ptr<Evaluator> evaluator;
  if (start_error_.empty()) {
    context = adopt_current_context(get_proc_address_);
    evaluator = std::make_unique<Evaluator>(*context, registry_);
  }
  for (;;) {
    EvalRequest request;
    {
      std::unique_lock lock(mutex_);
      wake_.wait(lock, [&] { return stop_ || pending_.has_value(); });
      if (stop_) break;
      request = std::move(*pending_);
      pending_.reset();
      running_ = true;
      started_ = std::chrono::steady_clock::now();
      if (evaluator && clear_) evaluator->clear();
      if (evaluator && hot_reload_) evaluator->set_shader_hot_reload(*hot_reload_);
      clear_ = false;
      hot_reload_.reset();
    }
    EvalFinished done;
    if (!evaluator) {
      done.tag = request.tag;
      done.error = start_error();
    } else {
      done = evaluate(*evaluator, request);
    }
    std::lock_guard lock(mutex_);
    if (finished_) delete_texture(finished_->texture);  // never taken: superseded
    finished_ = std::move(done);
    running_ = false;
  }
  std::lock_guard lock(mutex_);
  if (finished_) delete_texture(finished_->texture);
  finished_.reset();
  evaluator.reset();
  context.reset();
  if (start_error_.empty()) detach_();
}

}  // namespace aq::editor
