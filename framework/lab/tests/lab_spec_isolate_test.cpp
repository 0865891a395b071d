// Pass isolation (lab.json "isolate", docs/lab-format.md): which passes may be judged on the
// reference's inputs, which image stands in for each input, and the refusals, named by field.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "lab_spec_fixture.h"
#include "shaderlab/lab/lab_spec.h"

namespace {

using namespace lab_spec_test;
using shaderlab::LabSpecResult;
using shaderlab::PassInput;
using shaderlab::PassSpec;
using shaderlab::StandInSource;
using shaderlab::standInSource;
using PassIsolation = LabSpecFixture;

// The base lab with its blur graded once (no repeat) and the final pass reading it.
json chain() {
    json spec = json::parse(kBaseSpec);
    spec["passes"][3].erase("repeat");
    spec["passes"][3]["graded"] = true;
    spec["passes"][3]["inputs"] = {{"u_image", "gbuf.albedo"}};
    spec["scenes"][1].erase("repeats");
    spec["goals"][1]["passes"] = {"blur", "final"};
    return spec;
}

TEST_F(PassIsolation, AGradedPassReadingGradedImagesIsKeptWithItsStandIns) {
    json spec = chain();
    spec["passes"][3]["isolate"] = true;  // blur reads shade's albedo
    spec["passes"][4]["isolate"] = true;  // final reads blur's image and shade's normal
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    EXPECT_TRUE(r.spec.passes[3].isolate);
    EXPECT_FALSE(r.spec.passes[2].isolate);
    const PassSpec& final_pass = r.spec.passes[4];
    for (const PassInput& in : final_pass.inputs) {
        const StandInSource source = standInSource(r.spec, 4, in);
        ASSERT_NE(source.pass, nullptr) << in.sampler;
        EXPECT_EQ(source.pass->name, in.sampler == "u_image" ? "blur" : "shade") << in.sampler;
        EXPECT_EQ(source.attachment, in.sampler == "u_image" ? "color" : "normal") << in.sampler;
    }
}

TEST_F(PassIsolation, AnUngradedImageOrADepthHasNoStandIn) {
    json spec = chain();
    spec["passes"][2]["graded"] = json::array({"albedo"});  // normal not graded
    const LabSpecResult r = parseJson(spec);
    ASSERT_TRUE(r.ok) << allErrors(r);
    for (const PassInput& in : r.spec.passes[4].inputs) {
        if (in.sampler == "u_normal") {
            EXPECT_EQ(standInSource(r.spec, 4, in).pass, nullptr);
        }
    }
    for (const PassInput& in : r.spec.passes[2].inputs)  // the shadow map's depth
        EXPECT_EQ(standInSource(r.spec, 2, in).pass, nullptr) << in.sampler;
}

TEST_F(PassIsolation, AnUngradedPassIsRefused) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][1]["isolate"] = true;  // sky: not graded
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[1].isolate", "only a graded pass"));
}

TEST_F(PassIsolation, APassInARepeatGroupIsRefused) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][3]["graded"] = true;
    spec["passes"][3]["isolate"] = true;  // blur repeats 4 times
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[3].isolate", "repeat group"));
}

TEST_F(PassIsolation, APassThatReadsNoGradedImageIsRefused) {
    json spec = json::parse(kBaseSpec);
    spec["passes"][2]["isolate"] = true;  // shade reads the ungraded shadow map and sky
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[2].isolate", "nothing of the reference's to give it"));
}

TEST_F(PassIsolation, IsABooleanInTheSchema) {
    json spec = chain();
    spec["passes"][3]["isolate"] = "yes";
    const LabSpecResult r = parseJson(spec);
    EXPECT_FALSE(r.ok);
    EXPECT_TRUE(hasError(r, "passes[3].isolate", ""));
}

}  // namespace
