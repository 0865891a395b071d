// `shaderlab scene-sweep` (command_scene_sweep.cpp), its input side: the variations of a scene an
// instructor asks for (`--vary PATH=VALUES`, a sweep file) read and checked, and the candidate
// scenes they make from the base scene's lab.json object. It renders nothing and writes nothing;
// whether a candidate is a valid scene is the lab parser's to say (the command asks it).
//
// The grammar (docs/authoring.md, "Choosing scenes with scene-sweep"):
//   PATH    a field of a scene object: `file`, `time`, `camera.position`, `lights[0].direction`,
//           `uniforms.u_shininess`, `uniforms.u_material.color`, `repeats.step`, `thresholds.ssim_min`
//   VALUES  `A..B:N`  N values evenly spaced from A to B, both included; A and B are numbers, or
//                     arrays of as many numbers (vectors, component by component); whole numbers
//                     stay whole when every step is one
//           `V1,V2,...` a list of JSON values (`[1,0,0]`, `4`, `true`, `{"type": "point", ...}`);
//                     a bare word is a string (`scenes/torus.gltf`); `null` leaves the field out
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace shaderlab::authoring::sweep {

// Keeps lab.json's key order in the scenes the sweep prints for pasting.
using ojson = nlohmann::ordered_json;

// One variation: a field of the scene object and the values it takes in turn.
struct Variation {
    std::string path;
    std::vector<ojson> values;
};

// Parses "PATH=VALUES". False, with the reason naming what is wrong, when it is not one.
bool parseVary(const std::string& text, Variation* out, std::string* error);
// VALUES alone, for `path` (named in errors).
bool parseValues(const std::string& path, const std::string& text, std::vector<ojson>* out,
                 std::string* error);

// A candidate listed whole in a sweep file: a patch merged over the base scene (RFC 7386: a key
// set to null is left out), named by its "name" when it has one.
struct Patch {
    std::string label;
    ojson scene;
};

// A sweep file (--sweep): {"scene": NAME, "goals": [IDS], "mistakes": [NAMES], "vary": {PATH:
// VALUES or [values]}, "candidates": [patches], "about": TEXT}, every part optional.
struct SweepFile {
    std::string scene;
    std::vector<std::string> goals, mistakes;
    std::vector<Variation> vary;
    std::vector<Patch> patches;
};
bool readSweepFile(const std::string& path, SweepFile* out, std::vector<std::string>* errors);

struct Candidate {
    std::string id;  // c00 (the base scene), c01, ...
    ojson scene;     // the scene object, named by `id`
    bool base = false;
    std::string label;  // "base", a patch's label, or "" for a combination of the variations
};

// The base scene (c00), then every combination of the variations' values (the last varying
// fastest), then each patch. A candidate equal to an earlier one is left out and counted in
// `dropped`. False when a path cannot be set on the base scene, or when the variations and
// patches make more than `cap` candidates besides the base.
bool makeCandidates(const ojson& base, const std::vector<Variation>& vary, const std::vector<Patch>& patches,
                    std::size_t cap, std::vector<Candidate>* out, std::size_t* dropped, std::string* error);

// Sets `path` of `scene` to `value` (null: removes it), creating the objects on the way; an array
// index may be one past the end to append a whole element. False with the reason otherwise.
bool setPath(ojson* scene, const std::string& path, const ojson& value, std::string* error);
// The value at `path`, or null when the scene has none there.
ojson getPath(const ojson& scene, const std::string& path);

// `{ "name": "a", "lights": [{ "type": "point" }] }`: one line, spaced as lab.json is written.
std::string compactJson(const ojson& v);

}  // namespace shaderlab::authoring::sweep
