// A screen's long work (planning a program, measuring, decomposing a
// drawing) off the GUI thread, on Qt's thread pool: one run at a time; a
// progress (done of total) and a cancel flag shared with the work; on the
// GUI thread, `on_progress` every interval while it runs and `on_done` with
// the result when it ends. Destroying the task cancels the work and waits
// for it — the work must watch `cancel` where it can stop. Declare it after
// whatever its callbacks touch: it goes first.
#pragma once

#include <QFutureWatcher>
#include <QTimer>
#include <QtConcurrent/QtConcurrent>

#include <atomic>
#include <chrono>
#include <functional>
#include <memory>

#include "hmi/page_support.h"

namespace lcnc::hmi {

struct TaskProgress {
  std::atomic<int> done{0};
  std::atomic<int> total{0};  // the work may set it once it knows (−1: not yet)
  std::atomic<bool> cancel{false};
};

template <typename T>
class BackgroundTask {
 public:
  using Work = std::function<T(TaskProgress&)>;

  BackgroundTask(QObject* context, std::function<void(const TaskProgress&)> on_progress,
                 std::function<void(const T&)> on_done,
                 std::chrono::milliseconds interval = std::chrono::milliseconds(100))
      : on_progress_(std::move(on_progress)), on_done_(std::move(on_done)) {
    QObject::connect(&watcher_, &QFutureWatcher<T>::finished, context, [this] {
      timer_.stop();
      running_ = false;
      on_done_(watcher_.result());
    });
    timer_.setInterval(static_cast<int>(interval.count()));
    QObject::connect(&timer_, &QTimer::timeout, context, [this] {
      if (progress_ && on_progress_) on_progress_(*progress_);
    });
  }
  ~BackgroundTask() {
    cancel();
    watcher_.waitForFinished();
  }
  BackgroundTask(const BackgroundTask&) = delete;
  BackgroundTask& operator=(const BackgroundTask&) = delete;

  // Starts `work` with a fresh progress of `total`; false while a run is on.
  bool start(Work work, int total = 0) {
    if (running_) return false;
    progress_ = std::make_shared<TaskProgress>();
    progress_->total = total;
    running_ = true;
    timer_.start();
    watcher_.setFuture(QtConcurrent::run([w = std::move(work), p = progress_] { return w(*p); }));
    return true;
  }
  void cancel() noexcept {
    if (progress_) progress_->cancel = true;
  }
  [[nodiscard]] bool running() const noexcept { return running_; }
  // Spins the event loop until the run has ended and on_done has run.
  bool wait(int timeout_ms) { return wait_while(running_, timeout_ms); }

 private:
  std::function<void(const TaskProgress&)> on_progress_;
  std::function<void(const T&)> on_done_;
  bool running_ = false;
  std::shared_ptr<TaskProgress> progress_;
  QFutureWatcher<T> watcher_;
  QTimer timer_;
};

}  // namespace lcnc::hmi
