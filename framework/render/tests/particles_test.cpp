// Lab 10 (particles): the reference solution, rendered by the project's renderer, against a CPU
// integration of the same equations from the same initial state, in float and in double.
//
// The lab's step pass advances 1024 particles with semi-implicit Euler,
//     v' = v + dt (g + k (c - x)),   x' = x + dt v',
// then puts any coordinate that left the box [0, 1]^3 back on its wall and reflects and damps
// that velocity component (v_i' = -e v_i). The test reads the initial state the init pass wrote
// and the state after each scene's step count (RenderOptions::keep_all_passes), runs the same
// steps on the CPU, and checks:
//   - float32 on the CPU (same operations, same order) against the GPU: equal up to a few units
//     in the last place (llvmpipe may fuse a multiply and an add into one rounding);
//   - double against the GPU: float rounding (2^-24 relative per operation) accumulates over the
//     steps, so the difference grows with the step count but stays far below what the grader can
//     see (positions are compared to about 1/256 of the box);
//   - bounces are discontinuous: a particle that ends a step within rounding error of a wall may
//     bounce one step earlier in float than in double, and from then on the two trajectories
//     differ by about |v| dt. Such particles are found by running float and double side by side
//     and comparing each step's bounce decisions; their number is reported and bounded, and the
//     other particles must agree within the tolerance.
// The parameters are the float values the GPU receives (0.02 is 0.0199999995529651641845703125
// as a float uniform); both CPU integrations use exactly those, so the differences measured are
// rounding in the arithmetic alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "../src/input_textures.h"
#include "gl_test_support.h"
#include "grader/metrics/image.h"
#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace {

const std::string kLabDir = std::string(SHADERLAB_SOURCE_DIR) + "/labs/10-particles";
const std::string kReferenceDir = std::string(SHADERLAB_SOURCE_DIR) + "/reference_solutions/10-particles";

// The lab's parameters for one scene, as the GPU receives them (float uniforms).
template <typename T>
struct Params {
    T dt = 0, attraction = 0, restitution = 0;
    std::array<T, 3> gravity{}, attractor{};
};

template <typename T>
struct Particle {
    std::array<T, 3> x{}, v{};
};

// Which walls a step hit: bit 2i for the wall at 0 of axis i, bit 2i + 1 for the wall at 1.
using Hits = unsigned;

// One step of the reference's equations, in the reference's order of operations.
template <typename T>
Hits step(Particle<T>* p, const Params<T>& q) {
    Hits hits = 0;
    for (int i = 0; i < 3; ++i) {
        const T a = q.gravity[i] + q.attraction * (q.attractor[i] - p->x[i]);
        p->v[i] = p->v[i] + q.dt * a;
        p->x[i] = p->x[i] + q.dt * p->v[i];
        if (p->x[i] < T(0)) {
            p->x[i] = T(0);
            p->v[i] = -q.restitution * p->v[i];
            hits |= 1u << (2 * i);
        } else if (p->x[i] > T(1)) {
            p->x[i] = T(1);
            p->v[i] = -q.restitution * p->v[i];
            hits |= 1u << (2 * i + 1);
        }
    }
    return hits;
}

// A uniform's value for `scene` in `pass`: the scene's value replaces the pass's (lab-format.md).
const nlohmann::json& uniformValue(const shaderlab::PassSpec& pass, const shaderlab::SceneSpec& scene,
                                   const std::string& name) {
    for (const shaderlab::UniformSetting& u : scene.uniforms)
        if (u.name == name) return u.value;
    for (const shaderlab::UniformSetting& u : pass.uniforms)
        if (u.name == name) return u.value;
    static const nlohmann::json kMissing;
    ADD_FAILURE() << "lab.json sets no " << name << " for pass " << pass.name;
    return kMissing;
}

float uniformFloat(const shaderlab::PassSpec& pass, const shaderlab::SceneSpec& scene,
                   const std::string& name) {
    const nlohmann::json& j = uniformValue(pass, scene, name);
    return j.is_number() ? j.get<float>() : 0.0f;
}

std::array<float, 3> uniformVec3(const shaderlab::PassSpec& pass, const shaderlab::SceneSpec& scene,
                                 const std::string& name) {
    const nlohmann::json& j = uniformValue(pass, scene, name);
    std::array<float, 3> out{};
    if (j.is_array() && j.size() == 3)
        for (std::size_t i = 0; i < 3; ++i) out[i] = j[i].get<float>();
    return out;
}

template <typename T>
Params<T> stepParams(const shaderlab::PassSpec& pass, const shaderlab::SceneSpec& scene) {
    Params<T> q;
    q.dt = static_cast<T>(uniformFloat(pass, scene, "u_dt"));
    q.attraction = static_cast<T>(uniformFloat(pass, scene, "u_attraction"));
    q.restitution = static_cast<T>(uniformFloat(pass, scene, "u_restitution"));
    const std::array<float, 3> g = uniformVec3(pass, scene, "u_gravity");
    const std::array<float, 3> c = uniformVec3(pass, scene, "u_attractor");
    for (int i = 0; i < 3; ++i) {
        q.gravity[i] = static_cast<T>(g[i]);
        q.attractor[i] = static_cast<T>(c[i]);
    }
    return q;
}

// The state images of one pass: particle id is texel (id % w, id / w) in GL's rows, bottom row
// first; PassImage rows are top row first.
struct State {
    int width = 0, height = 0;
    std::vector<Particle<float>> particles;
};

State readState(const shaderlab::SceneRender& scene, const std::string& pass) {
    const grader::Image* position = nullptr;
    const grader::Image* velocity = nullptr;
    for (const shaderlab::PassImage& p : scene.passes) {
        if (p.pass != pass) continue;
        if (p.attachment == "position") position = &p.color;
        if (p.attachment == "velocity") velocity = &p.color;
    }
    State s;
    if (!position || !velocity) {
        ADD_FAILURE() << scene.scene << ": no position and velocity images of pass " << pass;
        return s;
    }
    s.width = position->width;
    s.height = position->height;
    for (int gl_row = 0; gl_row < s.height; ++gl_row)
        for (int x = 0; x < s.width; ++x) {
            const int row = s.height - 1 - gl_row;
            Particle<float> p;
            for (int i = 0; i < 3; ++i) {
                p.x[i] = position->at(x, row, i);
                p.v[i] = velocity->at(x, row, i);
            }
            s.particles.push_back(p);
        }
    return s;
}

template <typename A, typename B>
double maxDifference(const std::array<A, 3>& a, const std::array<B, 3>& b) {
    double d = 0.0;
    for (int i = 0; i < 3; ++i)
        d = std::max(d, std::fabs(static_cast<double>(a[i]) - static_cast<double>(b[i])));
    return d;
}

class Particles : public ::testing::Test {
  protected:
    void SetUp() override {
        std::string err;
        if (!shaderlab::testing::sharedContext(shaderlab::Backend::OSMesa, &err)) FAIL() << err;
        const shaderlab::LabSpecResult parsed = shaderlab::parseLabSpec(kLabDir);
        std::string errors;
        for (const std::string& e : parsed.errors) errors += "\n" + e;
        ASSERT_TRUE(parsed.ok) << errors;
        spec_ = parsed.spec;
        init_ = spec_.findPass("init");
        step_ = spec_.findPass("step");
        ASSERT_TRUE(init_ && step_);
    }

    // Renders the reference solution's scene `name` with every pass's images kept; `steps` > 0
    // replaces the scene's step count.
    shaderlab::SceneRender render(const std::string& name, int steps = 0) {
        shaderlab::LabSpec spec = spec_;
        for (shaderlab::SceneSpec& s : spec.scenes)
            if (s.name == name && steps > 0) s.repeats["step"] = steps;
        shaderlab::RenderOptions options;
        options.keep_all_passes = true;
        options.only_scenes = {name};
        const shaderlab::LabRender r = shaderlab::renderLab(spec, kReferenceDir, options);
        EXPECT_EQ(r.status, shaderlab::RenderStatus::Ok) << r.message;
        if (r.scenes.size() != 1) {
            ADD_FAILURE() << "scene " << name << " did not render";
            return {};
        }
        return r.scenes[0];
    }

    const shaderlab::SceneSpec& scene(const std::string& name) const {
        for (const shaderlab::SceneSpec& s : spec_.scenes)
            if (s.name == name) return s;
        throw std::runtime_error("no scene " + name);
    }

    // What a comparison of the GPU's state after `steps` steps with the CPU's found.
    struct Errors {
        int steps = 0;
        double gpu_vs_float = 0.0;        // max over all particles and coordinates, box units
        double gpu_vs_double = 0.0;       // max over the particles whose bounces agree
        double velocity_vs_double = 0.0;  // the same for velocities, m/s
        int diverged = 0;                 // particles whose float and double bounce steps differ
        double diverged_error = 0.0;      // their largest |GPU - CPU double|
        int bounces = 0;                  // wall contacts, all particles (double)
    };

    Errors compare(const std::string& name, int steps = 0) {
        const shaderlab::SceneSpec& s = scene(name);
        Errors e;
        e.steps = steps > 0 ? steps : s.repeats.at("step");
        const shaderlab::SceneRender r = render(name, steps);
        const State initial = readState(r, "init");
        const State final = readState(r, "step");
        EXPECT_EQ(initial.particles.size(), 1024u);
        EXPECT_EQ(final.particles.size(), initial.particles.size());
        if (final.particles.size() != initial.particles.size()) return e;
        const Params<float> qf = stepParams<float>(*step_, s);
        const Params<double> qd = stepParams<double>(*step_, s);
        for (std::size_t k = 0; k < initial.particles.size(); ++k) {
            Particle<float> pf = initial.particles[k];
            Particle<double> pd;
            for (int i = 0; i < 3; ++i) {
                pd.x[i] = pf.x[i];
                pd.v[i] = pf.v[i];
            }
            bool diverged = false;
            for (int n = 0; n < e.steps; ++n) {
                const Hits hf = step(&pf, qf);
                const Hits hd = step(&pd, qd);
                diverged = diverged || hf != hd;
                for (Hits h = hd; h; h &= h - 1) ++e.bounces;
            }
            const Particle<float>& gpu = final.particles[k];
            e.gpu_vs_float = std::max(e.gpu_vs_float, maxDifference(gpu.x, pf.x));
            if (diverged) {
                ++e.diverged;
                e.diverged_error = std::max(e.diverged_error, maxDifference(gpu.x, pd.x));
                continue;
            }
            e.gpu_vs_double = std::max(e.gpu_vs_double, maxDifference(gpu.x, pd.x));
            e.velocity_vs_double = std::max(e.velocity_vs_double, maxDifference(gpu.v, pd.v));
        }
        std::printf(
            "  %-13s %5d steps  |GPU - CPU float| %.2e  |GPU - CPU double| %.2e (velocity %.2e)  "
            "%5d wall contacts; %d particles bounced at another step in float (off by %.2e)\n",
            name.c_str(), e.steps, e.gpu_vs_float, e.gpu_vs_double, e.velocity_vs_double, e.bounces,
            e.diverged, e.diverged_error);
        return e;
    }

    shaderlab::LabSpec spec_;
    const shaderlab::PassSpec* init_ = nullptr;
    const shaderlab::PassSpec* step_ = nullptr;
};

// The init pass maps the generated noise (splitmix64, the same on every machine) into the spawn
// box and the velocity range: the CPU computes the same numbers from generateTexels.
TEST_F(Particles, InitialStateIsTheGeneratedNoiseMappedIntoTheSpawnBox) {
    ASSERT_EQ(init_->inputs.size(), 2u);
    std::vector<float> noise_position, noise_velocity;
    for (const shaderlab::PassInput& in : init_->inputs) {
        ASSERT_EQ(in.source, shaderlab::InputSource::Generated) << in.sampler;
        (in.sampler == "u_noise_position" ? noise_position : noise_velocity) =
            shaderlab::generateTexels(in.generated);
    }
    for (const std::string name : {"drift", "fountain"}) {
        const shaderlab::SceneSpec& s = scene(name);
        const State initial = readState(render(name, 1), "init");
        ASSERT_EQ(initial.particles.size() * 4, noise_position.size());
        const std::array<float, 3> lo = uniformVec3(*init_, s, "u_spawn_min");
        const std::array<float, 3> hi = uniformVec3(*init_, s, "u_spawn_max");
        const std::array<float, 3> mean = uniformVec3(*init_, s, "u_velocity_mean");
        const std::array<float, 3> spread = uniformVec3(*init_, s, "u_velocity_spread");
        double worst = 0.0;
        for (std::size_t k = 0; k < initial.particles.size(); ++k) {
            std::array<float, 3> x{}, v{};
            for (int i = 0; i < 3; ++i) {
                x[i] = lo[i] + noise_position[4 * k + i] * (hi[i] - lo[i]);
                v[i] = mean[i] + (2.0f * noise_velocity[4 * k + i] - 1.0f) * spread[i];
            }
            worst = std::max(
                {worst, maxDifference(initial.particles[k].x, x), maxDifference(initial.particles[k].v, v)});
        }
        EXPECT_LT(worst, 1e-6) << name;
    }
}

// Every graded scene: the reference's state after the scene's step count against the CPU.
TEST_F(Particles, ReferenceMatchesADoublePrecisionIntegration) {
    std::printf(
        "  scene          steps  errors in box units (the box is 1 wide; the grader sees about 4e-3)\n");
    for (const shaderlab::SceneSpec& s : spec_.scenes) {
        const Errors e = compare(s.name);
        // Same precision, same order of operations: a few units in the last place, except where
        // a fused multiply-add moved a bounce by one step (none in these scenes).
        EXPECT_LT(e.gpu_vs_float, 1e-5) << s.name;
        // Rounding in float: 2^-24 relative per operation, accumulated over at most 300 steps.
        EXPECT_LT(e.gpu_vs_double, 1e-4) << s.name;
        EXPECT_LT(e.velocity_vs_double, 1e-3) << s.name;
        // Discontinuities: a bounce one step early or late. At most 1 % of the particles.
        EXPECT_LE(e.diverged, 10) << s.name;
    }
}

// Longer runs show how the float error grows: linearly with the step count for the bounded
// orbits of symplectic Euler (a phase error), and reset by the walls in the box.
TEST_F(Particles, FloatDriftGrowsSlowlyWithTheStepCount) {
    for (const char* name : {"orbits", "rattle"}) {
        for (int steps : {1, 10, 100, 1000, 3000}) {
            const Errors e = compare(name, steps);
            EXPECT_LT(e.gpu_vs_double, 1e-7 * steps + 1e-5) << name << " after " << steps << " steps";
            EXPECT_LE(e.diverged, 20) << name << " after " << steps << " steps";
        }
    }
}

}  // namespace
