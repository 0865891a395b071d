// The typed form of a lab's `lab.json` (schema 2; documented field by field in
// docs/lab-format.md, and as a JSON Schema in docs/lab.schema.json).
// parseLabSpec() reads and validates; every message names the file and the JSON path of the
// field at fault ("labs/01-phong/lab.json: passes[0].state.cull: expected one of \"back\",
// \"front\", \"none\", got \"sideways\""). The framework executes a LabSpec and never looks at a
// lab's id.
#pragma once

#include <cstdint>
#include <glm/glm.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace shaderlab {

// A uniform value as lab.json gives it. Its GLSL type comes from the program that receives it
// (a JSON 3 sets an int, a float or a uint, whatever the shader declares), so it stays JSON
// until the program is linked; `path` names it in messages ("passes[0].uniforms.u_levels").
struct UniformSetting {
    std::string name;
    nlohmann::json value;
    std::string path;
};
using UniformList = std::vector<UniformSetting>;

enum class TargetFormat { RGBA8, SRGB8, RGBA16F, RGBA32F };
enum class TargetType { Texture2D, Cube };
enum class DepthMode { None, Buffer, Texture };
enum class TextureFilter { Nearest, Linear, Mipmap };
enum class TextureWrap { ClampToEdge, Repeat, MirroredRepeat };
enum class CullMode { None, Back, Front };
enum class PolygonMode { Fill, Line, Point };
enum class BlendMode { None, Alpha, Additive, Premultiplied };
enum class DepthFunc { Never, Less, Equal, LessEqual, Greater, NotEqual, GreaterEqual, Always };
enum class DrawKind { Scene, Fullscreen, Procedural };
enum class Primitive { Points, Lines, LineStrip, Triangles, TriangleStrip };
// How a graded image is compared: as displayed (clamped to 0..1, 8 bits) or with values above 1
// kept (high dynamic range, for intermediate float passes such as a bloom's bright pass).
enum class CompareMode { Display, Hdr };
enum class Projection { Perspective, Orthographic };

bool isFloatFormat(TargetFormat f);

// A render target: colour attachments of one format and size, and optionally depth.
struct TargetSpec {
    std::string name;
    TargetFormat format = TargetFormat::RGBA32F;
    TargetType type = TargetType::Texture2D;
    int width = 0, height = 0;  // pixels: `size`, or `scale` times the lab resolution (parser)
    float scale = 1.0f;
    std::vector<std::string> attachments{"color"};  // colour attachment names, location order
    DepthMode depth = DepthMode::Buffer;
    TextureFilter filter = TextureFilter::Linear;  // how passes sample it unless an input says
    TextureWrap wrap = TextureWrap::ClampToEdge;
    std::string path;  // where lab.json declares it
};

// A texture made by the framework instead of read from a file.
struct GeneratedTexture {
    std::string pattern;  // "checker" | "gradient" | "noise" | "constant"
    int width = 1, height = 1, depth = 1;
    std::vector<glm::vec4> colors;  // checker: two; gradient: two or more stops; constant: one
    int cells = 8;                  // checker squares per side
    std::uint32_t seed = 1;         // noise
};

enum class InputSource { Target, File, Cube, Generated };

// One sampler of a pass and what feeds it. Its texture type (1D, 2D, 3D, cube, shadow) comes from
// the sampler type the program declares, checked against the source when the program is linked.
struct PassInput {
    std::string sampler;  // GLSL uniform name
    InputSource source = InputSource::Target;
    std::string target;                   // Target: target name
    std::string attachment;               // Target: colour attachment name or "depth"
    std::string file;                     // File: path (lab folder, or shared/...)
    std::vector<std::string> cube_files;  // Cube: +x, -x, +y, -y, +z, -z
    int layers = 0;                       // File as a sampler3D: slices stacked top to bottom
    GeneratedTexture generated;
    std::optional<TextureFilter> filter;  // default: the target's, or linear
    std::optional<TextureWrap> wrap;      // default: the target's, or clamp
    bool srgb = false;                    // files and generated textures: decode sRGB when sampling
    std::string path;
};

struct ProgramSpec {
    std::string vertex;    // path relative to the lab folder, or shared/... for the course's
    std::string fragment;  // shared folder (labs/shared/)
};

// Per-attachment clears are resolved by the parser: one entry per attachment of the target.
struct RenderState {
    std::vector<std::optional<glm::vec4>> clear_colors;  // nullopt: keep what is there
    bool clear_depth = true;
    bool depth_test = true;
    bool depth_write = true;
    DepthFunc depth_func = DepthFunc::Less;
    CullMode cull = CullMode::Back;
    PolygonMode polygon_mode = PolygonMode::Fill;
    float line_width = 1.0f;
    float point_size = 1.0f;  // when the vertex stage does not write gl_PointSize
    BlendMode blend = BlendMode::None;
};

// Camera fields a scene or a pass replaces; unset ones keep the file's (or the scene's).
struct CameraOverride {
    std::optional<glm::vec3> position, target, up;
    std::optional<float> fov_y_deg, z_near, z_far;
    std::optional<Projection> projection;
    std::optional<float> height;  // orthographic: visible height in world units
    std::optional<int> light;     // look from the scene's light of this index
    bool any() const;
};

struct GradingThresholds {
    float psnr_min_db = 30.0f;
    float ssim_min = 0.95f;
    float flip_mean_max = 0.05f;
    float mismatch_max = 0.01f;     // fraction of covered pixels
    float pixel_tolerance = 0.05f;  // per-channel tolerance of the shift-tolerant comparison
};

// Thresholds a scene changes for its images, on top of the lab's and the pass's.
struct ThresholdOverrides {
    std::optional<float> psnr_min_db, ssim_min, flip_mean_max, mismatch_max, pixel_tolerance;
    GradingThresholds applyTo(GradingThresholds t) const;
};

struct PassSpec {
    std::string name;
    ProgramSpec program;
    DrawKind draw = DrawKind::Scene;
    Primitive primitive = Primitive::Triangles;  // procedural draws
    int vertex_count = 0;                        // procedural draws: gl_VertexID runs 0..count-1
    std::string target;                          // name of a LabSpec::targets entry
    std::vector<PassInput> inputs;
    RenderState state;
    UniformList uniforms;
    CameraOverride camera;
    // Graded colour attachments (and "depth"), empty when the pass is not graded.
    std::vector<std::string> graded;
    CompareMode compare = CompareMode::Display;
    GradingThresholds thresholds;  // the lab's, with this pass's overrides
    int loop = -1;                 // index into LabSpec::loops, -1 outside any loop
    // Pass isolation: the pass is judged a second time on the reference's inputs (the
    // reference's images of the graded passes it reads), and its goals use that verdict.
    bool isolate = false;
    std::string path;
};

// Passes first..last (indices into LabSpec::passes) run `count` times in a row; a scene may
// change the count.
struct LoopSpec {
    std::size_t first = 0, last = 0;
    int count = 1;
    std::string declared_by;  // the pass whose `repeat` made the loop
};

struct LightSpec {
    std::string type = "point";              // "point" | "directional"
    glm::vec3 position{0.0f};                // point
    glm::vec3 direction{0.0f, -1.0f, 0.0f};  // directional: the direction light travels
    glm::vec3 color{1.0f};
    float intensity = 1.0f;
};

struct SceneSpec {
    std::string name;       // unique within the lab; names output images ("spin_t1" for times)
    std::string base_name;  // the name lab.json gives (equal to name unless `times` expanded it)
    std::string file;       // glTF path relative to the labs root; empty for labs without scene draws
    CameraOverride camera;
    std::optional<std::vector<LightSpec>> lights;  // replaces the file's lights when set
    UniformList uniforms;                          // per-scene uniform overrides
    float time = 0.0f;                             // value of u_time
    std::map<std::string, int> repeats;            // loop count overrides, by declaring pass
    ThresholdOverrides thresholds;                 // for every graded image of this scene
    std::string path;
};

// A piece of the student's work a goal is about: a function in a student file, or the whole file.
struct GoalWork {
    std::string file;
    std::string function;  // empty: the whole file
};

// What a lab teaches, and what earns its points: a goal is met when every graded image of its
// scenes and passes passes.
struct GoalSpec {
    std::string id;
    std::string title;
    float points = 1.0f;
    std::vector<std::string> scenes;  // expanded scene names
    std::vector<std::string> passes;  // graded pass names
    // Goals this one rests on (ids): when one of them is not met, this one is not met either, and
    // the report says so instead of giving it a verdict of its own (docs/lab-format.md, "goals").
    std::vector<std::string> depends_on;
    // Judged on the student's pipeline as it is, even where its passes are isolated (an error
    // that adds up pass after pass, like a blur pyramid's, shows only there).
    bool pipeline = false;
    // The student's work the goal is about. When its checks fail on the student's whole shaders,
    // it is judged again on renders of the reference solution with only this work taken from the
    // student (docs/grading.md, "Goal isolation"); such a goal rests on no other (no depends_on).
    std::vector<GoalWork> work;
    bool implicit = false;  // made by the parser for a lab without goals (one per scene)
};

struct GradingSpec {
    float points = 10.0f;  // the lab's maximum score: the sum of its goals' points
    GradingThresholds thresholds;
    // `corpus --margins` flags a corpus verdict that holds by less than this factor (advice only).
    float margin_factor = 2.0f;
};

struct LabSpec {
    int schema = 2;
    std::string id;  // equals the lab folder's name, e.g. "01-phong"
    std::string title;
    std::string lab_dir;                     // absolute path of the lab folder (filled by the parser)
    std::string labs_root;                   // its parent, where scene paths are resolved
    int width = 256, height = 256;           // lab resolution
    std::vector<std::string> student_files;  // files a submission provides, e.g. phong.vert
    std::vector<TargetSpec> targets;
    std::vector<PassSpec> passes;
    std::vector<LoopSpec> loops;
    std::vector<SceneSpec> scenes;
    std::vector<GoalSpec> goals;
    GradingSpec grading;

    const TargetSpec* findTarget(const std::string& name) const;
    const PassSpec* findPass(const std::string& name) const;
};

struct LabSpecResult {
    bool ok = false;
    std::vector<std::string> errors;  // every problem found, not just the first
    LabSpec spec;
};

// Reads `<lab_dir>/lab.json` and validates it: first against the JSON Schema (field types,
// ranges, names, unknown keys), then what a schema cannot say (references between passes,
// targets, scenes and goals; cycles; files on disk; the id matching the folder).
LabSpecResult parseLabSpec(const std::string& lab_dir);
// Same, from text already in memory; `origin` names it in messages and `lab_dir` resolves paths.
LabSpecResult parseLabSpecText(const std::string& json_text, const std::string& origin,
                               const std::string& lab_dir);

// The JSON Schema of lab.json (docs/lab.schema.json, compiled in).
const std::string& labSchemaText();

// The course's shared folder for a labs root: <labs_root>/shared. Paths in lab.json that start
// with "shared/" name files there.
std::string sharedFolder(const std::string& labs_root);
// Where a lab file named in lab.json lives: <labs_root>/<path> for shared/..., else
// <lab_dir>/<path>.
std::string labFilePath(const LabSpec& spec, const std::string& path);

// Pass isolation (PassSpec::isolate): the graded image that stands in for what input `in` of
// pass `reader` reads when the reader is run on the reference's inputs. That is the image of the
// last pass before the reader that drew the input's target, when that pass grades the attachment
// read and is outside the reader's repeat group. Null when the reader reads its own work there.
struct StandInSource {
    const PassSpec* pass = nullptr;
    std::string attachment;  // the graded attachment read
};
StandInSource standInSource(const LabSpec& spec, std::size_t reader, const PassInput& in);

}  // namespace shaderlab
