// The parts of the lab.json parser that its files share: the collected messages, what lab.json says
// of a pass before the defaults that depend on other passes are known, and the two classes that do
// the work, the Reader (step 3: lab_spec_read.cpp, lab_spec_read_inputs.cpp,
// lab_spec_read_scenes.cpp) and the Validator (step 4: lab_spec_check_*.cpp). lab_spec.cpp runs the
// steps in order. Private to the parser: nothing outside framework/lab/src includes it.
#pragma once

#include <algorithm>
#include <cstddef>
#include <filesystem>
#include <glm/glm.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "shaderlab/base/json_messages.h"
#include "shaderlab/lab/lab_spec.h"

namespace shaderlab::lab_spec_detail {

namespace fs = std::filesystem;
using json = nlohmann::json;

inline constexpr std::size_t kMaxLabJsonBytes = std::size_t{1} << 20;

inline std::string passPath(std::size_t i) { return joinIndex("passes", i); }

// Every problem found, once each, as "<origin>: <json path>: <problem>".
class Diagnostics {
  public:
    explicit Diagnostics(std::string origin) : origin_(std::move(origin)) {}
    void error(const std::string& path, const std::string& problem) {
        const std::string line =
            path.empty() ? origin_ + ": " + problem : origin_ + ": " + path + ": " + problem;
        if (std::find(errors_.begin(), errors_.end(), line) == errors_.end()) errors_.push_back(line);
    }
    bool any() const { return !errors_.empty(); }
    std::vector<std::string> take() { return std::move(errors_); }

  private:
    std::string origin_;
    std::vector<std::string> errors_;
};

// Step 1 (lab_spec_load.cpp): the text of lab.json into a DOM, or the messages saying why not.
bool loadJson(const std::string& text, Diagnostics& diag, json& out);

// Values read the same way wherever lab.json gives them (lab_spec_read.cpp).
TextureFilter readFilter(const json& v);
TextureWrap readWrap(const json& v);
glm::vec3 readVec3(const json& v);
glm::vec4 readVec4(const json& v);
void readUniforms(const json& v, const std::string& path, UniformList& out);
void readCamera(const json& v, CameraOverride& c);

// What lab.json says of a pass before defaults that depend on other passes are filled in.
struct PassDraft {
    json dom;                       // the pass after its template was merged in
    std::string template_name;      // "" without extends
    std::string target_ref;         // a target named by string, or "" for an owned target
    std::optional<TargetSpec> own;  // owned target
    std::optional<json> clear_color;
    std::optional<bool> clear_depth, depth_test, depth_write, graded_flag;
    std::vector<std::string> graded_list;
    std::optional<CompareMode> compare;
    std::optional<int> repeat_count;
    std::string repeat_from;
};

// Step 3: walks a DOM the schema accepted into the LabSpec, keeping for each pass what the
// validator needs to fill in its defaults.
class Reader {
  public:
    Reader(const json& doc, Diagnostics& diag, LabSpec& spec) : doc_(doc), diag_(diag), spec_(spec) {}

    void run();  // lab_spec_read.cpp

    std::vector<PassDraft>& drafts() { return drafts_; }

  private:
    void readPass(const json& raw, std::size_t i);  // lab_spec_read.cpp
    void readState(const json& v, const std::string& path, RenderState& s, PassDraft& d);
    PassInput readInput(const json& v, const std::string& sampler,
                        const std::string& pass_path);  // lab_spec_read_inputs.cpp
    void readGenerated(const json& g, PassInput& in);
    void readScene(const json& v, std::size_t i);  // lab_spec_read_scenes.cpp
    LightSpec readLight(const json& v, const std::string& path);

    const json& doc_;
    Diagnostics& diag_;
    LabSpec& spec_;
    std::vector<PassDraft> drafts_;
};

// Whether a path in lab.json names a file of the course's shared folder (lab_spec_check_files.cpp).
bool isSharedPath(const std::string& p);

// Step 4: what a schema cannot say, checked on the spec the Reader made, and the defaults that
// depend on other fields filled in as it goes.
class Validator {
  public:
    Validator(LabSpec& spec, std::vector<PassDraft>& drafts, Diagnostics& diag, bool check_disk)
        : spec_(spec), drafts_(drafts), diag_(diag), check_disk_(check_disk) {}

    void run();  // lab_spec.cpp: the checks, in order

  private:
    // lab_spec_check_targets.cpp: targets, their sizes and attachments, and each pass's state.
    void collectTargets();
    void resolvePassTargets();
    void resolveState(PassSpec& p, const PassDraft& d, const TargetSpec& t, bool first_writer);
    // lab_spec_check_passes.cpp: references between passes, repeat groups, reads before draws.
    int passIndex(const std::string& name) const;
    void buildLoops();
    void checkInputs();
    void checkPassReferences();
    void checkReadOrder(std::size_t i, const PassInput& in);
    void checkWork();
    // lab_spec_check_scenes.cpp
    void checkCameras();
    void checkScenes();
    // lab_spec_check_goals.cpp: what is graded, and the goals that grade it.
    void checkGraded();
    void checkIsolation(std::size_t index);
    void checkGoals();
    void addImplicitGoals();
    void checkGoalCoverage(const std::set<std::string>& covered);
    void checkGoalDependencies(const std::set<std::string>& ids);
    // lab_spec_check_goal_work.cpp: what a goal's "work" names.
    void checkGoalWork();
    // lab_spec_check_files.cpp: the lab folder and the files lab.json names.
    void checkId();
    void checkFile(const std::string& path, const std::string& file);
    void checkFiles();

    LabSpec& spec_;
    std::vector<PassDraft>& drafts_;
    Diagnostics& diag_;
    bool check_disk_;
    std::vector<std::string> graded_;  // names of the graded passes, in pass order
};

}  // namespace shaderlab::lab_spec_detail
