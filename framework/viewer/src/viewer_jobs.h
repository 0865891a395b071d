// The viewer's two background threads: renders and grades asked of the render server
// (RenderQueue), and judgements of the pictures that came back (Worker). Of each kind of job only
// the newest one waits: a student saving three times quickly gets the third picture and the third
// grade. Private to the viewer.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "shaderlab/live/render_service.h"

namespace shaderlab::viewer {

// kDebug: a debug view of the scene's vertex data (RenderRequest::debug_view).
enum JobKind { kStudent = 0, kReference = 1, kGrade = 2, kDebug = 3 };
constexpr int kJobKinds = 4;

struct Job {
    JobKind kind = kStudent;
    RenderRequest request;         // kStudent, kReference, kDebug
    GradeRequest grade;            // kGrade
    std::uint64_t generation = 0;  // the files' version (student renders and grades)
    std::int64_t save_ns = 0;      // when the change that asked for it was saved (0: none)
};

struct Finished {
    Job job;
    IsolatedRender result;    // kStudent, kReference, kDebug
    grader::Report report;    // kGrade: one lab, when graded
    std::string grade_error;  // kGrade: why there is no report
};

// Renders and grades from a thread of its own, so the window never waits on a shader. A debug view
// goes first (it is asked for only while it is on screen, and draws in milliseconds), then the
// student's picture (what the student is waiting for), then the reference's, then the grade of the
// whole lab, as the workbench orders them.
class RenderQueue {
  public:
    RenderQueue(RenderService* service, std::function<void()> wake)
        : service_(service), wake_(std::move(wake)) {
        thread_ = std::thread([this] { loop(); });
    }
    ~RenderQueue() {
        {
            std::lock_guard<std::mutex> lock(m_);
            stop_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    void submit(Job job) {
        {
            std::lock_guard<std::mutex> lock(m_);
            pending_[job.kind] = std::move(job);
        }
        cv_.notify_all();
    }
    std::vector<Finished> take() {
        std::lock_guard<std::mutex> lock(m_);
        std::vector<Finished> out;
        out.swap(done_);
        return out;
    }
    // What is running now ("rendering ...", "grading ...") and for how long ("" when idle).
    std::string running(double* seconds) {
        std::lock_guard<std::mutex> lock(m_);
        if (!running_) return {};
        *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
        return running_what_;
    }

  private:
    void loop() {
        for (;;) {
            Job job;
            {
                std::unique_lock<std::mutex> lock(m_);
                cv_.wait(lock, [this] {
                    return stop_ || pending_[0] || pending_[1] || pending_[2] || pending_[3];
                });
                if (stop_) return;
                std::optional<Job>& next = pending_[kDebug]       ? pending_[kDebug]
                                           : pending_[kStudent]   ? pending_[kStudent]
                                           : pending_[kReference] ? pending_[kReference]
                                                                  : pending_[kGrade];
                job = std::move(*next);
                next.reset();
                running_ = true;
                started_ = std::chrono::steady_clock::now();
                running_what_ =
                    job.kind == kGrade   ? "grading the lab as `check` does"
                    : job.kind == kDebug ? std::string("drawing the vertex data, scene ") + job.request.scene
                    : job.kind == kStudent ? "rendering your shaders, scene " + job.request.scene
                                           : "rendering the reference, scene " + job.request.scene;
            }
            Finished f;
            if (job.kind == kGrade) {
                if (!service_->grade(job.grade, &f.report, &f.grade_error) || f.report.labs.empty())
                    f.grade_error = "the lab could not be graded: " +
                                    (f.grade_error.empty() ? std::string("no result") : f.grade_error);
            } else {
                f.result = service_->render(job.request);
            }
            f.job = std::move(job);
            {
                std::lock_guard<std::mutex> lock(m_);
                running_ = false;
                done_.push_back(std::move(f));
            }
            wake_();
        }
    }

    RenderService* service_;
    std::function<void()> wake_;
    std::thread thread_;
    std::mutex m_;
    std::condition_variable cv_;
    std::optional<Job> pending_[kJobKinds];
    std::vector<Finished> done_;
    bool stop_ = false;
    bool running_ = false;
    std::chrono::steady_clock::time_point started_;
    std::string running_what_;
};

// Judging runs on its own thread too (FLIP and SSIM take tens of milliseconds an image): the
// frame that receives a picture must not stall. Of each slot only the newest job waits.
class Worker {
  public:
    Worker() : thread_([this] { loop(); }) {}
    ~Worker() {
        {
            std::lock_guard<std::mutex> lock(m_);
            stop_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    void submit(int slot, std::function<void()> job) {
        {
            std::lock_guard<std::mutex> lock(m_);
            pending_[slot] = std::move(job);
        }
        cv_.notify_all();
    }

  private:
    void loop() {
        for (;;) {
            std::function<void()> job;
            {
                std::unique_lock<std::mutex> lock(m_);
                cv_.wait(lock, [this] { return stop_ || pending_[0] || pending_[1]; });
                if (stop_) return;
                std::function<void()>& next = pending_[0] ? pending_[0] : pending_[1];
                job = std::move(next);
                next = nullptr;
            }
            job();
        }
    }

    std::mutex m_;
    std::condition_variable cv_;
    std::function<void()> pending_[2];
    bool stop_ = false;
    std::thread thread_;  // last: started once the rest is built
};

}  // namespace shaderlab::viewer
