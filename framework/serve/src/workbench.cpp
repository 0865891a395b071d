// The workbench's threads: the folder watch, and the render thread that asks the render server
// for the debug view on the page (when one is on), the student's picture of the view on the page,
// the reference's, and the lab's grade, in that order of urgency (of each kind only the newest
// request waits: three quick saves give one more picture, not three).
#include <cstdio>
#include <filesystem>

#include "grader/metrics/heatmap.h"
#include "shaderlab/grading/grading.h"
#include "shaderlab/live/render_outcome.h"
#include "shaderlab/render/debug_view.h"
#include "workbench_detail.h"

namespace fs = std::filesystem;

namespace shaderlab::serve {

namespace {

std::int64_t wallNowNs() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::system_clock::now().time_since_epoch())
        .count();
}

std::string imageKey(const PassImage& p) { return p.pass + "." + p.attachment; }

}  // namespace

std::unique_ptr<Workbench> Workbench::create(const WorkbenchOptions& options, std::string* error) {
    auto impl = std::make_unique<Impl>();
    impl->opt = options;
    impl->service = viewer::RenderService::start(options.spec, options.backend, error);
    if (!impl->service) return nullptr;
    impl->scene = options.spec.scenes.empty() ? std::string() : options.spec.scenes.front().name;
    for (const PassSpec& pass : options.spec.passes)
        for (const PassInput& in : pass.inputs)
            if (in.source == InputSource::File &&
                std::find(impl->input_files.begin(), impl->input_files.end(), in.file) ==
                    impl->input_files.end())
                impl->input_files.push_back(in.file);
    return std::unique_ptr<Workbench>(new Workbench(std::move(impl)));
}

Workbench::Workbench(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Workbench::~Workbench() { stop(); }

void Workbench::start() {
    Impl& w = *impl_;
    {
        std::lock_guard<std::mutex> lock(w.m);
        w.want_student = true;
        w.want_reference = !w.opt.reference_root.empty();
        w.want_grade = w.opt.grade;
    }
    w.render_thread = std::thread([&w] { w.renderLoop(); });
    w.watch_thread = std::thread([&w] { w.watchLoop(); });
}

void Workbench::stop() {
    Impl& w = *impl_;
    {
        std::lock_guard<std::mutex> lock(w.m);
        if (w.stopping) return;
        w.stopping = true;
        w.changed.notify_all();
        w.work.notify_all();
    }
    // A render in flight answers "crashed" at once instead of running to its limit.
    if (w.service) w.service->shutdown();
    if (w.render_thread.joinable()) w.render_thread.join();
    if (w.watch_thread.joinable()) w.watch_thread.join();
}

std::uint64_t Workbench::version() const {
    std::lock_guard<std::mutex> lock(impl_->m);
    return impl_->version;
}

std::uint64_t Workbench::waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout) {
    Impl& w = *impl_;
    std::unique_lock<std::mutex> lock(w.m);
    w.changed.wait_for(lock, timeout, [&] { return w.stopping || w.version != seen; });
    return w.version;
}

bool Workbench::setView(const std::string& scene, const CameraOrbit& orbit, DebugView debug,
                        std::string* error) {
    Impl& w = *impl_;
    bool known = false;
    for (const SceneSpec& s : w.opt.spec.scenes) known = known || s.name == scene;
    if (!known) {
        *error = "lab " + w.opt.spec.id + " has no scene '" + scene + "'";
        return false;
    }
    std::lock_guard<std::mutex> lock(w.m);
    // Turning a debug view on or off draws no new picture of the lab's.
    const bool only_debug = debug != w.debug && scene == w.scene && orbit == w.orbit;
    w.scene = scene;
    w.orbit = orbit;
    w.debug = debug;
    if (!only_debug) {
        w.want_student = true;
        w.want_reference = !w.opt.reference_root.empty();
    }
    w.want_debug = debug != DebugView::Off;
    w.work.notify_all();
    w.bump();
    return true;
}

void Workbench::Impl::watchLoop() {
    viewer::FolderWatch watch(labFolder());
    for (;;) {
        {
            std::unique_lock<std::mutex> lock(m);
            if (work.wait_for(lock, opt.poll, [this] { return stopping; })) return;
        }
        const bool saved = watch.poll();
        const std::vector<std::string> unchanged = watch.takeSavedUnchanged();
        if (!unchanged.empty()) {
            std::string names;
            for (const std::string& f : unchanged) names += (names.empty() ? "" : ", ") + f;
            say(names + " saved without a change: the picture is of these files already");
            std::lock_guard<std::mutex> lock(m);
            ++unchanged_saves;
            unchanged_files = unchanged;
            bump();
        }
        if (!saved) continue;
        std::string names;
        for (const std::string& f : watch.changedFiles()) names += (names.empty() ? "" : ", ") + f;
        say(names + " changed; rendering again");
        const std::int64_t mtime = watch.changedMtimeNs();
        std::lock_guard<std::mutex> lock(m);
        ++generation;
        pending_save_ns = mtime > 0 ? mtime : wallNowNs();
        want_student = true;
        want_grade = opt.grade;
        work.notify_all();
        bump();
    }
}

void Workbench::Impl::renderLoop() {
    for (;;) {
        enum { kDebug, kStudent, kReference, kGrade } job;
        std::string job_scene;
        CameraOrbit job_orbit;
        DebugView job_debug = DebugView::Off;
        std::uint64_t job_generation = 0;
        std::int64_t save_ns = 0;
        {
            std::unique_lock<std::mutex> lock(m);
            work.wait(lock, [this] {
                return stopping || want_debug || want_student || want_reference || want_grade;
            });
            if (stopping) return;
            job_scene = scene;
            job_orbit = orbit;
            job_debug = debug;
            job_generation = generation;
            if (want_debug) {
                job = kDebug;
                want_debug = false;
                busy = std::string("drawing the ") + debugViewName(debug) + " view, scene " + scene;
            } else if (want_student) {
                job = kStudent;
                want_student = false;
                save_ns = pending_save_ns;
                pending_save_ns = 0;
                busy = "rendering your shaders, scene " + scene;
            } else if (want_reference) {
                job = kReference;
                want_reference = false;
                busy = "rendering the reference, scene " + scene;
            } else {
                job = kGrade;
                want_grade = false;
                busy = "grading the lab as `check` does";
            }
            busy_since = Clock::now();
            bump();
        }
        if (job == kDebug) renderDebug(job_scene, job_orbit, job_debug);
        if (job == kStudent) renderStudent(job_scene, job_orbit, job_generation, save_ns);
        if (job == kReference) renderReference(job_scene, job_orbit);
        if (job == kGrade) gradeLab(job_generation);
        std::lock_guard<std::mutex> lock(m);
        busy.clear();
        bump();
    }
}

void Workbench::Impl::renderStudent(const std::string& scene_name, const CameraOrbit& view_orbit,
                                    std::uint64_t files_generation, std::int64_t save_ns) {
    viewer::RenderRequest request;
    request.shader_dir = labFolder();
    request.containment_root = opt.submission_root;
    request.scene = scene_name;
    request.orbit = view_orbit;
    request.timeout_s = opt.view_timeout_s;
    IsolatedRender r = service->render(request);
    if (r.status == IsolatedStatus::Ok && !r.render.scenes.empty() && r.render.scenes[0].error.empty()) {
        auto student = std::make_shared<const IsolatedRender>(std::move(r));
        std::shared_ptr<Snapshot> snap = buildSnapshot(student, scene_name, view_orbit);
        snap->generation = files_generation;
        if (save_ns) snap->latency_ms = static_cast<double>(wallNowNs() - save_ns) / 1e6;
        {
            std::lock_guard<std::mutex> lock(m);
            snap->seq = next_seq++;
            previous = snapshot;
            snapshot = snap;
            if (failure && failure->generation <= files_generation) failure.reset();
            bump();
        }
        sayPicture(*snap, *student);
        judge(snap);
        {
            std::lock_guard<std::mutex> lock(m);
            bump();
        }
        sayVerdict(*snap);
        return;
    }
    RenderFailureInfo info;
    if (r.status == IsolatedStatus::Ok) {  // the scene's file did not load: the lab's fault
        info.title = "The scene did not load";
        info.text = r.render.scenes.empty() ? r.message : r.render.scenes[0].error;
    } else {
        const viewer::RenderFailure f = viewer::describeFailure(opt.spec, r);
        info.title = f.title;
        info.text = f.text;
    }
    if (r.status == IsolatedStatus::Timeout) info.title += ", scene " + scene_name;
    info.scene = scene_name;
    info.generation = files_generation;
    info.endless_loop = r.limit == "loop";
    info.diagnostics = diagnosticsJson(r.render.diagnostics, labFolder(), true);
    sayFailure(info, r);
    std::lock_guard<std::mutex> lock(m);
    failure = std::move(info);
    bump();
}

void Workbench::Impl::renderReference(const std::string& scene_name, const CameraOrbit& view_orbit) {
    {
        std::lock_guard<std::mutex> lock(m);
        if (reference && reference_scene == scene_name && reference_orbit == view_orbit) return;
    }
    viewer::RenderRequest request;
    request.shader_dir = (fs::path(opt.reference_root) / opt.spec.id).string();
    request.containment_root = opt.reference_root;
    request.scene = scene_name;
    request.orbit = view_orbit;
    request.timeout_s = std::max(opt.view_timeout_s, 30.0);
    auto r = std::make_shared<const IsolatedRender>(service->render(request));
    std::shared_ptr<const IsolatedRender> student;
    CameraOrbit student_orbit;
    std::string student_scene;
    std::uint64_t student_generation = 0;
    {
        std::lock_guard<std::mutex> lock(m);
        reference = r;
        reference_scene = scene_name;
        reference_orbit = view_orbit;
        reference_error = r->status == IsolatedStatus::Ok
                              ? std::string()
                              : "the reference solution did not render: " + r->message;
        // The picture on the page gets its reference now, when it shows this view.
        if (snapshot && snapshot->scene == scene_name && snapshot->orbit == view_orbit &&
            !snapshot->reference) {
            student = snapshot->student;
            student_scene = snapshot->scene;
            student_orbit = snapshot->orbit;
            student_generation = snapshot->generation;
        }
        bump();
    }
    if (!student) return;
    std::shared_ptr<Snapshot> snap = buildSnapshot(student, student_scene, student_orbit);
    snap->generation = student_generation;
    {
        std::lock_guard<std::mutex> lock(m);
        snap->seq = next_seq++;
        previous = snapshot;
        snapshot = snap;
        bump();
    }
    judge(snap);
    {
        std::lock_guard<std::mutex> lock(m);
        bump();
    }
    sayVerdict(*snap);
}

// The debug view on the page, unless the newest one drawn is of this view already. Its snapshot
// holds the one image, no reference, and the notes of what it could not show.
void Workbench::Impl::renderDebug(const std::string& scene_name, const CameraOrbit& view_orbit,
                                  DebugView view) {
    {
        std::lock_guard<std::mutex> lock(m);
        if (debug_snapshot && debug_snapshot->debug == view && debug_snapshot->scene == scene_name &&
            debug_snapshot->orbit == view_orbit)
            return;
    }
    viewer::RenderRequest request;
    request.scene = scene_name;
    request.orbit = view_orbit;
    request.timeout_s = std::max(opt.view_timeout_s, 10.0);
    request.debug_view = view;
    auto r = std::make_shared<const IsolatedRender>(service->render(request));
    if (r->status != IsolatedStatus::Ok || r->render.scenes.size() != 1 ||
        r->render.scenes[0].passes.size() != 1) {
        const std::string why = r->status == IsolatedStatus::Ok && !r->render.scenes.empty()
                                    ? "the scene did not load: " + r->render.scenes[0].error
                                    : std::string(isolatedStatusName(r->status)) + ": " + r->message;
        std::lock_guard<std::mutex> lock(m);
        debug_error = std::string("the ") + debugViewName(view) + " view was not drawn (" + why + ")";
        bump();
        return;
    }
    auto snap = std::make_shared<Snapshot>();
    snap->scene = scene_name;
    snap->orbit = view_orbit;
    snap->debug = view;
    snap->student = r;
    snap->render_ms = r->render.scenes[0].render_ms;
    ImageEntry e;
    e.student = &r->render.scenes[0].passes[0];
    snap->images.push_back(e);
    snap->final_image = 0;
    for (const Diagnostic& d : r->render.diagnostics)
        if (d.severity == "note") snap->notes.push_back(d.message);
    std::lock_guard<std::mutex> lock(m);
    snap->seq = next_seq++;
    debug_previous = debug_snapshot;
    debug_snapshot = snap;
    debug_error.clear();
    bump();
}

void Workbench::Impl::gradeLab(std::uint64_t files_generation) {
    viewer::GradeRequest request;
    request.submission_root = opt.submission_root;
    request.labs_root = opt.labs_root;
    request.reference_root = opt.reference_root;
    request.limits = opt.grade_limits;
    grader::Report report;
    std::string error;
    const bool ok = service->grade(request, &report, &error) && !report.labs.empty();
    // As report.json writes it, once: the page asks for the state often.
    nlohmann::json lab;
    if (ok) {
        sayGrade(report.labs.front());
        grader::Report one;
        one.labs.push_back(report.labs.front());
        const nlohmann::json parsed = nlohmann::json::parse(grader::reportToJson(one), nullptr, false);
        if (parsed.is_object() && parsed.contains("labs") && !parsed["labs"].empty()) lab = parsed["labs"][0];
    }
    std::lock_guard<std::mutex> lock(m);
    if (ok) {
        grade = std::move(lab);
        grade_error.clear();
    } else {
        grade_error = "the lab could not be graded: " + (error.empty() ? "no result" : error);
        say(grade_error);
    }
    grade_generation = files_generation;
    bump();
}

std::shared_ptr<Snapshot> Workbench::Impl::buildSnapshot(std::shared_ptr<const IsolatedRender> student,
                                                         const std::string& scene_name,
                                                         const CameraOrbit& view_orbit) {
    auto snap = std::make_shared<Snapshot>();
    snap->scene = scene_name;
    snap->orbit = view_orbit;
    snap->student = student;
    snap->render_ms = student->render.scenes[0].render_ms;
    snap->diagnostics = diagnosticsJson(student->render.diagnostics, labFolder(), false);
    if (!opt.reference_root.empty()) {
        std::lock_guard<std::mutex> lock(m);
        if (reference && reference->status == IsolatedStatus::Ok && !reference->render.scenes.empty() &&
            reference_scene == scene_name && reference_orbit == view_orbit)
            snap->reference =
                std::shared_ptr<const std::vector<PassImage>>(reference, &reference->render.scenes[0].passes);
        else if (!reference_error.empty() && reference_scene == scene_name)
            snap->reference_note = reference_error;
        else
            snap->reference_note = "the reference is rendering";
    } else if (view_orbit.any()) {
        snap->reference_note = "the stored golden images show the graded view only: go back to it to compare";
    } else {
        // Goldens are read on this thread only.
        if (!goldens.count(scene_name) && !golden_errors.count(scene_name)) {
            std::vector<PassImage> images;
            std::string error;
            if (loadGoldenScene(opt.spec, opt.spec.lab_dir, scene_name, &images, &error))
                goldens[scene_name] = std::make_shared<const std::vector<PassImage>>(std::move(images));
            else
                golden_errors[scene_name] = error;
        }
        const auto it = goldens.find(scene_name);
        if (it != goldens.end())
            snap->reference = it->second;
        else
            snap->reference_note = golden_errors[scene_name];
    }
    const std::vector<PassImage>& mine = student->render.scenes[0].passes;
    for (std::size_t i = 0; i < mine.size(); ++i) {
        ImageEntry e;
        e.student = &mine[i];
        e.pass = opt.spec.findPass(mine[i].pass);
        if (snap->reference)
            for (const PassImage& q : *snap->reference)
                if (imageKey(q) == imageKey(mine[i]) && q.color.width == mine[i].color.width &&
                    q.color.height == mine[i].color.height)
                    e.reference = &q;
        if (mine[i].graded) snap->final_image = static_cast<int>(i);
        if (e.pass) {
            for (const PassInput& in : e.pass->inputs) {
                InputEntry ie;
                ie.sampler = in.sampler;
                if (in.source == InputSource::Target) {
                    ie.from = "target";
                    ie.label = "target " + in.target + (in.attachment.empty() ? "" : "." + in.attachment);
                    // What the pass read: the latest image of that target drawn before it, or (a
                    // repeated pass reading its own group's output) the latest of all.
                    for (std::size_t j = 0; j < mine.size(); ++j) {
                        const bool same = mine[j].target == in.target &&
                                          (in.attachment.empty() || mine[j].attachment == in.attachment);
                        if (same && (j < i || ie.image < 0)) ie.image = static_cast<int>(j);
                    }
                } else if (in.source == InputSource::File) {
                    ie.from = "file";
                    ie.label = "file " + in.file;
                    const auto it = std::find(input_files.begin(), input_files.end(), in.file);
                    ie.file = static_cast<int>(it - input_files.begin());
                } else if (in.source == InputSource::Cube) {
                    ie.from = "cube";
                    ie.label = "a cube map the framework makes";
                } else {
                    ie.from = "generated";
                    ie.label = "generated " + in.generated.pattern;
                }
                e.inputs.push_back(std::move(ie));
            }
        }
        snap->images.push_back(std::move(e));
    }
    return snap;
}

// Every image that has a reference, judged as grading judges it (the thresholds of its pass and
// scene), with the heat map of its difference.
void Workbench::Impl::judge(const std::shared_ptr<Snapshot>& snap) {
    std::vector<std::shared_ptr<const Judgement>> judged(snap->images.size());
    for (std::size_t i = 0; i < snap->images.size(); ++i) {
        const ImageEntry& e = snap->images[i];
        if (!e.reference || !e.pass) continue;
        auto j = std::make_shared<Judgement>();
        j->thresholds = imageThresholds(opt.spec, snap->scene, *e.pass);
        j->hdr = e.pass->compare == CompareMode::Hdr;
        j->verdict = grader::judgeImage(e.reference->color, e.reference->coverage, e.student->color,
                                        e.student->coverage, j->thresholds,
                                        j->hdr ? grader::ImageRange::Hdr : grader::ImageRange::Display);
        grader::HeatmapConfig hc;
        hc.outline = j->verdict.mismatches.empty() ? nullptr : &j->verdict.mismatches;
        j->heat =
            grader::diffHeatmap(j->verdict.flip_map, e.student->color.width, e.student->color.height, hc);
        judged[i] = std::move(j);
    }
    std::lock_guard<std::mutex> lock(snap->m);
    snap->judged = std::move(judged);
}

}  // namespace shaderlab::serve
