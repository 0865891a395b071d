// IsolatedRenderQueue: several labs rendered by one child must give what a child of their own
// gives each (status, renderer, every pixel, the progress events), and a child that dies must
// cost only the lab it died in, and only when that lab was the child's first.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "shaderlab/base/sanitizer.h"
#include "shaderlab/gl/gl_context.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/isolated_render.h"

namespace shaderlab {
namespace {

const std::string kRoot = SHADERLAB_SOURCE_DIR;

Backend autoBackend() {
    Backend b = Backend::OSMesa;
    parseBackend("auto", &b);
    return b;
}

LabSpec lab(const std::string& id) {
    const LabSpecResult r = parseLabSpec(kRoot + "/labs/" + id);
    EXPECT_TRUE(r.ok) << id;
    return r.spec;
}

// What a render tells: "done <scene> <ms>" without its milliseconds.
struct Recorded {
    std::vector<std::string> events;
};

RenderOptions recording(Recorded* r) {
    RenderOptions options;
    options.containment_root = kRoot + "/reference_solutions";
    options.progress = [r](const std::string& e) {
        r->events.push_back(e.rfind("done ", 0) == 0 ? e.substr(0, e.rfind(' ')) : e);
    };
    return options;
}

void expectSameRender(const IsolatedRender& a, const IsolatedRender& b, const std::string& what) {
    SCOPED_TRACE(what);
    EXPECT_EQ(isolatedStatusName(a.status), std::string(isolatedStatusName(b.status))) << a.message;
    EXPECT_EQ(a.renderer, b.renderer);
    ASSERT_EQ(a.render.scenes.size(), b.render.scenes.size());
    for (std::size_t s = 0; s < a.render.scenes.size(); ++s) {
        const SceneRender& x = a.render.scenes[s];
        const SceneRender& y = b.render.scenes[s];
        EXPECT_EQ(x.scene, y.scene);
        ASSERT_EQ(x.passes.size(), y.passes.size()) << x.scene;
        for (std::size_t p = 0; p < x.passes.size(); ++p) {
            EXPECT_EQ(x.passes[p].pass, y.passes[p].pass);
            EXPECT_EQ(x.passes[p].color.width, y.passes[p].color.width);
            EXPECT_EQ(x.passes[p].color.height, y.passes[p].color.height);
            // Bit for bit: NaN payloads and -0 included.
            ASSERT_EQ(x.passes[p].color.pixels.size(), y.passes[p].color.pixels.size());
            EXPECT_EQ(0, std::memcmp(x.passes[p].color.pixels.data(), y.passes[p].color.pixels.data(),
                                     x.passes[p].color.pixels.size() * sizeof(float)))
                << x.scene << " " << x.passes[p].pass;
            EXPECT_EQ(x.passes[p].coverage, y.passes[p].coverage) << x.scene << " " << x.passes[p].pass;
        }
    }
}

// Kills the render children this thread started (the queue's child), once.
void killMyChildren() {
    std::ifstream in("/proc/self/task/" + std::to_string(syscall(SYS_gettid)) + "/children");
    for (long pid = 0; in >> pid;) kill(static_cast<pid_t>(pid), SIGKILL);
}

// Threads of this process: a GL context made by another test of this binary leaves the driver's
// threads behind, and a child forked from such a process may hang in the driver (the grader
// never holds a context, isolated_render.h). ctest runs every test in a process of its own.
int threadsOfThisProcess() {
    std::ifstream in("/proc/self/status");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("Threads:", 0) == 0) return std::stoi(line.substr(8));
    return 0;
}

class Queue : public ::testing::Test {
  protected:
    void SetUp() override {
        if (threadsOfThisProcess() > 1)
            GTEST_SKIP() << "another test left driver threads in this process; run this test alone "
                            "(as ctest does)";
    }

    const LabSpec phong = lab("01-phong");
    const LabSpec aa = lab("09-procedural-antialiasing");
    const Backend backend = autoBackend();
    const IsolationLimits limits;

    IsolatedLabJob job(const LabSpec& spec, Recorded* r) const {
        return {&spec, kRoot + "/reference_solutions/" + spec.id, recording(r)};
    }
    IsolatedRender alone(const LabSpec& spec, Recorded* r) const {
        return renderLabIsolated(spec, kRoot + "/reference_solutions/" + spec.id, backend, limits,
                                 recording(r));
    }
};

// How long a test waits for a child to finish labs on its own (AddressSanitizer is much slower).
constexpr std::chrono::seconds kBusy(SHADERLAB_ASAN ? 30 : 5);

TEST_F(Queue, HandsBackEachLabAsAChildOfItsOwnWould) {
    Recorded q0, q1, q2, a0, a1;
    IsolatedRenderQueue queue({job(phong, &q0), job(aa, &q1), job(phong, &q2)}, backend, limits);
    queue.start();
    std::vector<IsolatedRender> got;
    int called = 0;
    got.push_back(queue.next([&] { ++called; }));
    // The grader busy elsewhere: the child finishes the other labs and ends meanwhile; what it
    // handed back is still taken, with no second child.
    std::this_thread::sleep_for(kBusy);
    for (int i = 1; i < 3; ++i) got.push_back(queue.next([&] { ++called; }));
    EXPECT_EQ(called, 3);
    EXPECT_EQ(queue.childrenStarted(), 1u);
    EXPECT_EQ(queue.handedBack(), 3u);
    const IsolatedRender none = queue.next();
    EXPECT_EQ(none.status, IsolatedStatus::RenderError);
    EXPECT_NE(none.message.find("no lab left"), std::string::npos);

    const IsolatedRender phong_alone = alone(phong, &a0), aa_alone = alone(aa, &a1);
    ASSERT_EQ(phong_alone.status, IsolatedStatus::Ok) << phong_alone.message;
    ASSERT_FALSE(phong_alone.render.scenes.empty());
    expectSameRender(got[0], phong_alone, "01-phong first");
    expectSameRender(got[1], aa_alone, "09 second");
    expectSameRender(got[2], phong_alone, "01-phong again, third");
    // Each lab heard its own events, and only those.
    EXPECT_EQ(q0.events, a0.events);
    EXPECT_EQ(q1.events, a1.events);
    EXPECT_EQ(q2.events, a0.events);
    EXPECT_GT(got[1].wall_ms, 0.0);
    EXPECT_LE(got[1].compile_ms, got[1].wall_ms);
}

TEST_F(Queue, AChildThatDiesInALaterLabIsStartedAgainForIt) {
    Recorded q0, q1, a1;
    IsolatedLabJob second = job(phong, &q1);
    bool killed = false;
    const auto record = second.options.progress;
    second.options.progress = [&, record](const std::string& e) {
        record(e);
        if (!killed) killMyChildren();
        killed = true;
    };
    IsolatedRenderQueue queue({job(aa, &q0), second}, backend, limits);
    const IsolatedRender first = queue.next();
    EXPECT_EQ(first.status, IsolatedStatus::Ok) << first.message;
    const IsolatedRender again = queue.next();
    ASSERT_TRUE(killed);
    EXPECT_EQ(queue.childrenStarted(), 2u);
    // Not charged: rendered again in a child of its own, from its first event on.
    const IsolatedRender phong_alone = alone(phong, &a1);
    expectSameRender(again, phong_alone, "01-phong after its child was killed");
    ASSERT_FALSE(a1.events.empty());
    ASSERT_GT(q1.events.size(), a1.events.size());
    EXPECT_EQ(q1.events[0], a1.events[0]);
    EXPECT_EQ(
        std::vector<std::string>(q1.events.end() - static_cast<long>(a1.events.size()), q1.events.end()),
        a1.events);
}

TEST_F(Queue, AChildThatDiesInItsFirstLabChargesThatLabAndTheNextGetsAFreshOne) {
    Recorded q0, q1, a1;
    IsolatedLabJob first = job(phong, &q0);
    // Once: were the lab rendered again, it would pass.
    bool done = false;
    first.options.progress = [&done](const std::string&) {
        if (!done) killMyChildren();
        done = true;
    };
    IsolatedRenderQueue queue({first, job(aa, &q1)}, backend, limits);
    const IsolatedRender killed = queue.next();
    EXPECT_EQ(killed.status, IsolatedStatus::Crashed);
    EXPECT_NE(killed.message.find("died of signal 9"), std::string::npos) << killed.message;
    EXPECT_TRUE(killed.render.scenes.empty());
    EXPECT_EQ(queue.childrenStarted(), 1u);
    const IsolatedRender next = queue.next();
    expectSameRender(next, alone(aa, &a1), "09 after the first lab's child was killed");
    EXPECT_EQ(q1.events, a1.events);
}

// A later lab drawn while the grader is busy elsewhere is unwatched; if it went past its draw
// clock it is charged as a child of its own would have been stopped, by the child's own clock.
TEST_F(Queue, ALaterLabThatRanPastItsClockUnwatchedCountsAsStopped) {
    const LabSpec post = lab("05-post-processing");
    IsolationLimits tight;
    tight.timeout_s = 0.05;  // far less than the lab's drawing takes
    Recorded r0, r1;
    const IsolatedLabJob missing{&phong, kRoot + "/no-such-folder/01-phong", recording(&r0)};
    IsolatedRenderQueue queue({missing, job(post, &r1)}, backend, tight);
    const IsolatedRender none = queue.next();
    EXPECT_EQ(none.status, IsolatedStatus::Missing) << none.message;
    std::this_thread::sleep_for(kBusy);
    const IsolatedRender late = queue.next();
    EXPECT_EQ(late.status, IsolatedStatus::Timeout) << late.message;
    EXPECT_EQ(late.limit, "draw_timeout");
    EXPECT_NE(late.message.find("counts as stopped at the limit"), std::string::npos) << late.message;
    EXPECT_TRUE(late.render.scenes.empty());
    EXPECT_EQ(queue.childrenStarted(), 1u);
    // Watched, the same lab is stopped by the grader itself.
    Recorded r2;
    const IsolatedRender watched =
        renderLabIsolated(post, kRoot + "/reference_solutions/" + post.id, backend, tight, recording(&r2));
    EXPECT_EQ(watched.status, IsolatedStatus::Timeout) << watched.message;
    EXPECT_EQ(watched.limit, "draw_timeout");
    EXPECT_NE(watched.message.find("the process was killed"), std::string::npos) << watched.message;
}

}  // namespace
}  // namespace shaderlab
