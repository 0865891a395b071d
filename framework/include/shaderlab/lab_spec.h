// The typed form of a lab's `lab.json` (documented field by field in docs/lab-format.md).
// parseLabSpec() reads and validates; every message names the file and the JSON path of the
// field at fault ("labs/01-phong/lab.json: passes[0].state.cull: expected one of \"back\", \"front\",
// \"none\", got \"sideways\""). The framework executes a LabSpec and never looks at a lab's id.
#pragma once

#include <glm/glm.hpp>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace shaderlab {

// A uniform value given in lab.json: a JSON number is a float, a JSON integer is still a float
// unless the spec says {"int": 3}; arrays of 2/3/4 numbers are vec2/3/4, 9/16 are mat3/mat4
// (column-major, as GLSL). {"bool": true} is a bool.
using UniformValue = std::variant<float, int, bool, glm::vec2, glm::vec3, glm::vec4, glm::mat3, glm::mat4>;
using UniformMap = std::map<std::string, UniformValue>;

enum class TargetFormat { RGBA8, RGBA16F, RGBA32F };
enum class CullMode { None, Back, Front };
enum class PolygonMode { Fill, Line };
enum class BlendMode { None, Alpha, Additive };
enum class DepthFunc { Less, LessEqual, Always };
enum class DrawKind { Scene, Fullscreen };
enum class TextureFilter { Nearest, Linear };
enum class TextureWrap { ClampToEdge, Repeat, MirroredRepeat };

struct RenderState {
    std::optional<glm::vec4> clear_color = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);  // nullopt: no clear
    bool clear_depth = true;
    bool depth_test = true;
    bool depth_write = true;
    DepthFunc depth_func = DepthFunc::Less;
    CullMode cull = CullMode::Back;
    PolygonMode polygon_mode = PolygonMode::Fill;
    float line_width = 1.0f;
    BlendMode blend = BlendMode::None;
};

// Where a pass's colour target lives. Size: explicit pixels, or a scale of the lab resolution.
struct TargetSpec {
    std::string name;  // what later passes call it; defaults to the pass name
    TargetFormat format = TargetFormat::RGBA32F;
    int width = 0, height = 0;  // 0: use scale * lab resolution
    float scale = 1.0f;
    TextureFilter filter = TextureFilter::Linear;  // how later passes sample it
    TextureWrap wrap = TextureWrap::ClampToEdge;
};

// A sampler uniform fed by an earlier pass's target or by an image file of the lab.
struct PassInput {
    std::string sampler;                  // GLSL uniform name, e.g. "u_scene"
    std::string from_pass;                // target name of an earlier pass, or empty
    std::string texture_file;             // path relative to the lab folder, or empty (exactly one is set)
    std::optional<TextureFilter> filter;  // overrides the target's filter
    std::optional<TextureWrap> wrap;
};

struct ProgramSpec {
    std::string vertex;    // path relative to the lab folder, e.g. "phong.vert"
    std::string fragment;  // e.g. "phong.frag"
};

struct PassSpec {
    std::string name;
    ProgramSpec program;
    DrawKind draw = DrawKind::Scene;
    std::vector<PassInput> inputs;
    TargetSpec target;
    RenderState state;
    UniformMap uniforms;
    // Whether the grader compares this pass's output. The last pass is always graded; earlier
    // passes of a multi-pass lab may be compared too, to name the first one that goes wrong.
    bool graded = false;
    // When set, this pass draws over another pass's target instead of owning one (its `target`
    // is then ignored): e.g. an outline pass drawn into the shaded scene.
    std::string draw_into;
};

// Camera overrides for a graded scene; unset fields keep the glTF camera's.
struct CameraOverride {
    std::optional<glm::vec3> position, target, up;
    std::optional<float> fov_y_deg, z_near, z_far;
};

struct LightSpec {
    std::string type = "point";              // "point" | "directional"
    glm::vec3 position{0.0f};                // point
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: the direction light travels
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
};

struct SceneSpec {
    std::string name;  // unique within the lab; names output images
    std::string file;  // glTF path relative to the labs root (e.g. "scenes/sphere.gltf")
    CameraOverride camera;
    std::optional<std::vector<LightSpec>> lights;  // replaces the file's lights when set
    UniformMap uniforms;                           // per-scene uniform overrides
    float time = 0.0f;                             // value of u_time
};

struct GradingSpec {
    float points = 10.0f;       // the lab's maximum score, split evenly over scenes
    float psnr_min_db = 30.0f;  // a scene passes when every threshold holds
    float ssim_min = 0.95f;
    float flip_mean_max = 0.05f;
    float mismatch_max = 0.01f;     // fraction of covered pixels
    float pixel_tolerance = 0.05f;  // per-channel tolerance of the shift-tolerant comparison
};

struct LabSpec {
    int schema = 1;
    std::string id;  // equals the lab folder's name, e.g. "01-phong"
    std::string title;
    std::string lab_dir;                     // absolute path of the lab folder (filled by the parser)
    std::string labs_root;                   // its parent, where scene paths are resolved
    int width = 256, height = 256;           // lab resolution
    std::vector<std::string> student_files;  // files a submission provides, e.g. phong.vert
    std::vector<PassSpec> passes;
    std::vector<SceneSpec> scenes;
    GradingSpec grading;
};

struct LabSpecResult {
    bool ok = false;
    std::vector<std::string> errors;  // every problem found, not just the first
    LabSpec spec;
};

// Reads `<lab_dir>/lab.json` and validates it (field types and ranges, unique pass and scene
// names, inputs referring only to earlier passes, files existing inside the lab folder, the
// id matching the folder name).
LabSpecResult parseLabSpec(const std::string& lab_dir);
// Same, from text already in memory; `origin` names it in messages and `lab_dir` resolves paths.
LabSpecResult parseLabSpecText(const std::string& json_text, const std::string& origin,
                               const std::string& lab_dir);

}  // namespace shaderlab
