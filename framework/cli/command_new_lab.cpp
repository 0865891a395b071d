// `shaderlab new-lab ID [--like LAB]`: the folders and files of a new lab, so that an instructor
// starts from something that parses, renders and passes `shaderlab lab-check` but for its corpus:
// labs/ID/ (lab.json, a README with the sections every lab README has and its goals and scenes
// tables generated from lab.json, the starter shaders), reference_solutions/ID/ (the starter's
// student files, to solve), tests/corpus/ID/cases.json (no cases yet) and the lab's row in the
// course index (labs/README.md). With --like LAB, lab.json, the lab's files and the README's
// headings are LAB's, with the id and title changed. Refuses, writing nothing, an id that is not a
// name, an id taken by any of those folders, and an unknown LAB. Renders nothing: the next steps
// it prints do (goldens, corpus add-case, lab-check).
#include <unistd.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "commands.h"
#include "grader/base/atomic_file.h"
#include "shaderlab/authoring/readme_tables.h"
#include "shaderlab/base/json_messages.h"
#include "shaderlab/base/paths.h"
#include "shaderlab/lab/lab_catalog.h"
#include "shaderlab/lab/lab_spec.h"

namespace fs = std::filesystem;
using json = nlohmann::json;

namespace shaderlab::cli {

using namespace authoring;

namespace {

int refused(const std::string& why) {
    std::cerr << "shaderlab: new-lab: " << why << "\n";
    return 2;
}

bool writeText(const fs::path& path, const std::string& text, std::string* error) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    return grader::writeFileAtomically(path.string(), text, error, false);
}

// "12-normal-mapping" -> "Normal mapping": a title until the instructor gives one.
std::string titleFromId(const std::string& id) {
    std::size_t at = 0;
    while (at < id.size() && std::isdigit(static_cast<unsigned char>(id[at]))) ++at;
    if (at > 0 && at < id.size() && (id[at] == '-' || id[at] == '_')) ++at;
    std::string title = at < id.size() ? id.substr(at) : id;
    for (char& c : title)
        if (c == '-' || c == '_') c = ' ';
    title[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(title[0])));
    return title;
}

// "# Lab 12: Normal mapping" for a numbered id, else "# Normal mapping".
std::string readmeTitle(const std::string& id, const std::string& title) {
    std::size_t digits = 0;
    while (digits < id.size() && std::isdigit(static_cast<unsigned char>(id[digits]))) ++digits;
    return digits > 0 && digits < id.size() ? "# Lab " + id.substr(0, digits) + ": " + title : "# " + title;
}

std::string quoted(const std::string& s) { return json(s).dump(); }

// A lab that parses and renders: one graded pass of the course's usual lighting inputs, two
// scenes, two goals, each judged on the student's own work for it (a function, and main as the
// glue: docs/grading.md, "Goal isolation").
std::string scaffoldLabJson(const std::string& id, const std::string& title) {
    return R"({
  "$schema": "../../docs/lab.schema.json",
  "schema": 2,
  "id": )" +
           quoted(id) +
           R"(,
  "title": )" +
           quoted(title) +
           R"(,
  "resolution": [256, 256],
  "student_files": ["shade.frag"],
  "goals": [
    { "id": "first_idea", "title": "TODO: the first idea a student learns, in a few words", "points": 5,
      "work": ["shade.frag:lightAt"], "scenes": ["sphere"] },
    { "id": "second_idea", "title": "TODO: a second idea: the parts put together", "points": 5,
      "work": ["shade.frag:main"], "scenes": ["teapot"] }
  ],
  "passes": [
    {
      "name": "shade",
      "program": { "vertex": "shade.vert", "fragment": "shade.frag" },
      "draw": "scene",
      "state": { "clear_color": [0.05, 0.05, 0.08, 1.0] },
      "uniforms": { "u_ambient": 0.15 },
      "graded": true
    }
  ],
  "scenes": [
    { "name": "sphere", "file": "scenes/sphere.gltf" },
    { "name": "teapot", "file": "scenes/teapot.gltf" }
  ]
}
)";
}

std::string scaffoldVertex(const std::string& id) {
    return "#version 330 core\n// " + id +
           R"(, vertex stage (given: not a student file). The world-space position and normal
// for the fragment stage.

layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;

uniform mat4 u_model;
uniform mat4 u_view;
uniform mat4 u_projection;
uniform mat3 u_normal_matrix;  // transpose(inverse(mat3(u_model))), provided by the framework

out vec3 v_world_position;
out vec3 v_world_normal;

void main() {
    vec4 world = u_model * vec4(a_position, 1.0);
    v_world_position = world.xyz;
    v_world_normal = u_normal_matrix * a_normal;
    gl_Position = u_projection * u_view * world;
}
)";
}

std::string scaffoldFragment(const std::string& id) {
    return "#version 330 core\n// " + id + ", fragment stage: the student's file. Read labs/" + id +
           R"(/README.md first.
// (For the instructor: declare every input the README tells students to use, mark what they
// write with TODO(student), and solve it in reference_solutions/)" +
           id + R"(/.)

in vec3 v_world_position;
in vec3 v_world_normal;

uniform vec3 u_camera_position;                // eye position, world space
uniform int u_light_count;                     // how many entries below are in use
uniform vec4 u_light_position[SL_MAX_LIGHTS];  // w = 1: point light at xyz; w = 0: xyz points toward the light
uniform vec3 u_light_color[SL_MAX_LIGHTS];     // colour times intensity
uniform vec4 u_base_color;                     // the material's colour
uniform float u_ambient;                       // lab.json sets it

out vec4 o_color;

// What light i adds at this fragment. (For the instructor: one function per idea, each named in
// its goal's "work", so that each goal is judged on the student's own work for it.)
vec3 lightAt(int i, vec3 n) {
    // TODO(student)
    return vec3(0.0);
}

void main() {
    vec3 n = normalize(v_world_normal);
    vec3 color = u_ambient * u_base_color.rgb;
    for (int i = 0; i < u_light_count; ++i) {
        color += lightAt(i, n);
    }
    o_color = vec4(color, 1.0);
}
)";
}

// Where the top-level string value of `key` starts and ends (quotes included) in a JSON object's
// text; false when the object has no such string member.
bool topLevelString(const std::string& text, const std::string& key, std::size_t* begin, std::size_t* end) {
    auto stringEnd = [&](std::size_t open) {  // the index of the quote closing the string at `open`
        std::size_t i = open + 1;
        while (i < text.size() && text[i] != '"') i += text[i] == '\\' ? 2 : 1;
        return i;
    };
    int depth = 0;
    for (std::size_t i = 0; i < text.size(); ++i) {
        const char ch = text[i];
        if (ch == '"') {
            const std::size_t close = stringEnd(i);
            if (depth == 1 && text.compare(i + 1, close - i - 1, key) == 0 && close - i - 1 == key.size()) {
                const std::size_t colon = text.find_first_not_of(" \t\r\n", close + 1);
                if (colon != std::string::npos && text[colon] == ':') {
                    const std::size_t value = text.find_first_not_of(" \t\r\n", colon + 1);
                    if (value == std::string::npos || text[value] != '"') return false;
                    *begin = value;
                    *end = stringEnd(value) + 1;
                    return *end <= text.size();
                }
            }
            i = close;
        } else if (ch == '{' || ch == '[') {
            ++depth;
        } else if (ch == '}' || ch == ']') {
            --depth;
        }
    }
    return false;
}

// LAB's lab.json as it is written, with its id and title the new lab's.
bool likeLabJson(const std::string& text, const std::string& id, const std::string& title, std::string* out) {
    std::size_t id_begin = 0, id_end = 0, title_begin = 0, title_end = 0;
    if (!topLevelString(text, "id", &id_begin, &id_end)) return false;
    *out = text;
    if (topLevelString(text, "title", &title_begin, &title_end)) {
        // Replace the later one first, so the earlier one's offsets hold.
        if (title_begin > id_begin) out->replace(title_begin, title_end - title_begin, quoted(title));
        out->replace(id_begin, id_end - id_begin, quoted(id));
        if (title_begin < id_begin) out->replace(title_begin, title_end - title_begin, quoted(title));
        return true;
    }
    const std::size_t line = text.rfind('\n', id_begin);
    const std::size_t key = text.find_first_not_of(" \t", line == std::string::npos ? 0 : line + 1);
    const std::string indent = line == std::string::npos ? "  " : text.substr(line + 1, key - line - 1);
    out->replace(id_begin, id_end - id_begin, quoted(id) + ",\n" + indent + "\"title\": " + quoted(title));
    return true;
}

// The "##" and "###" headings of a README, outside code blocks.
std::vector<std::string> readmeHeadings(const std::string& readme) {
    std::vector<std::string> headings;
    bool fenced = false;
    std::size_t at = 0;
    while (at < readme.size()) {
        std::size_t nl = readme.find('\n', at);
        if (nl == std::string::npos) nl = readme.size();
        const std::string line = readme.substr(at, nl - at);
        if (line.rfind("```", 0) == 0) fenced = !fenced;
        if (!fenced && (line.rfind("## ", 0) == 0 || line.rfind("### ", 0) == 0)) headings.push_back(line);
        at = nl + 1;
    }
    return headings;
}

std::string codeList(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "`" : ", `") + n + "`";
    return out;
}

// What a section of the skeleton asks the instructor to write (docs/authoring.md, step 3).
std::string sectionBody(const std::string& heading, const LabSpec& spec) {
    if (heading == "## The idea")
        return "TODO: the idea, with its formulas and where they come from (a paper, a book, a "
               "specification).\n";
    if (heading == "## What to implement")
        return "TODO: what to write in which file: " + codeList(spec.student_files) + ".\n";
    if (heading == "## Pitfalls")
        return "- TODO: each known mistake in plain words (they are the corpus's mistakes).\n";
    if (heading == "## Learning goals")
        return "Each goal, the work it is judged on, its points and where it is seen (written from lab.json: "
               "after "
               "changing it, run `shaderlab lab-check " +
               spec.id + " --fix`):\n\n" + generatedBlock("goals", spec);
    if (heading == "## How it is graded")
        return "TODO: how the scenes isolate each goal, which passes are judged on the reference's inputs, "
               "and any threshold that differs from the course defaults, with the reason.\n\n" +
               generatedBlock("scenes", spec);
    if (heading == "## Try it")
        return "    build/framework/shaderlab render labs --lab " + spec.id + " --out out/mine\n" +
               "    build/framework/shaderlab check " + spec.id + "\n";
    return "TODO.\n";
}

// The README: the course's sections (or LAB's headings), the goals and scenes tables generated.
std::string scaffoldReadme(const LabSpec& spec, const std::string& like_readme) {
    std::vector<std::string> headings =
        like_readme.empty()
            ? std::vector<std::string>{"## The idea",       "## What to implement", "## Pitfalls",
                                       "## Learning goals", "## How it is graded",  "## Try it"}
            : readmeHeadings(like_readme);
    for (const char* needed : {"## Learning goals", "## How it is graded"}) {
        if (std::find(headings.begin(), headings.end(), needed) != headings.end()) continue;
        const auto try_it = std::find(headings.begin(), headings.end(), "## Try it");
        headings.insert(try_it, needed);
    }
    std::vector<std::string> given;  // the lab's own program files, which students do not edit
    for (const PassSpec& p : spec.passes)
        for (const std::string& f : {p.program.vertex, p.program.fragment})
            if (f.rfind("shared/", 0) != 0 &&
                std::find(spec.student_files.begin(), spec.student_files.end(), f) ==
                    spec.student_files.end() &&
                std::find(given.begin(), given.end(), f) == given.end())
                given.push_back(f);
    std::string out = readmeTitle(spec.id, spec.title) +
                      "\n\nTODO: one paragraph: what the student makes, and why it matters.\n\n"
                      "Files to edit (look for `TODO(student)`): " +
                      codeList(spec.student_files) + ".";
    if (!given.empty())
        out += " " + codeList(given) + (given.size() == 1 ? " is" : " are") +
               " given and not yours to change: the grader always uses the lab's copy.";
    out += "\n\n![TODO: what the expected picture shows](golden/" + spec.scenes.front().name + ".png)\n";
    for (const std::string& h : headings) out += "\n" + h + "\n\n" + sectionBody(h, spec);
    return out;
}

// The course folders new-lab writes into.
struct NewLabPlaces {
    std::string labs_root;
    fs::path lab, reference, corpus, index;
};

// Refuses an id that is not a name or is taken; the reason, "" when it may be made.
std::string refuseId(const NewLabArgs& args, const NewLabPlaces& places) {
    std::error_code ec;
    if (!isPlainName(args.id) || args.id.size() > 64)
        return "ID \"" + args.id +
               "\" must be 1 to 64 letters, digits, '_' or '-' (it names the lab's folders and images), "
               "e.g. 12-normal-mapping";
    for (const fs::path& p : {places.lab, places.reference, places.corpus})
        if (fs::exists(p, ec) || fs::is_symlink(p, ec))
            return p.string() + " exists already: " + args.id + " is taken (pick another id)";
    return "";
}

// Writes the lab's folder; on success `spec` is the new lab, parsed.
bool writeLabFolder(const NewLabArgs& args, const NewLabPlaces& places, const std::string& title,
                    LabSpecResult* parsed, std::string* error) {
    std::error_code ec;
    std::string like_readme;
    if (args.like.empty()) {
        if (!writeText(places.lab / "lab.json", scaffoldLabJson(args.id, title), error) ||
            !writeText(places.lab / "shade.vert", scaffoldVertex(args.id), error) ||
            !writeText(places.lab / "shade.frag", scaffoldFragment(args.id), error))
            return false;
    } else {
        const fs::path like = fs::path(places.labs_root) / args.like;
        std::string text;
        if (!likeLabJson(readFile((like / "lab.json").string()).text, args.id, title, &text)) {
            *error = (like / "lab.json").string() + ": no top-level \"id\" to change";
            return false;
        }
        if (!writeText(places.lab / "lab.json", text, error)) return false;
        // Its files but what is LAB's own: README, the goldens and hints rendered for it.
        for (auto it = fs::recursive_directory_iterator(like, ec);
             !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
            const fs::path rel = fs::relative(it->path(), like);
            const std::string top = rel.begin()->string();
            if (top == "lab.json" || top == "README.md" || top == "golden" || top == "hints") {
                if (it->is_directory()) it.disable_recursion_pending();
                continue;
            }
            if (!it->is_regular_file()) continue;
            fs::create_directories((places.lab / rel).parent_path(), ec);
            fs::copy_file(it->path(), places.lab / rel, ec);
            if (ec) {
                *error = (places.lab / rel).string() + ": " + ec.message();
                return false;
            }
        }
        like_readme = readFile((like / "README.md").string()).text;
    }
    *parsed = parseLabSpec(places.lab.string());
    if (!parsed->ok) {
        for (const std::string& e : parsed->errors) std::cerr << e << "\n";
        *error = "the new lab.json does not parse (above)";
        return false;
    }
    return writeText(places.lab / "README.md", scaffoldReadme(parsed->spec, like_readme), error);
}

// The reference solution (the starter's student files, to solve) and the empty corpus.
bool writeReferenceAndCorpus(const LabSpec& spec, const NewLabPlaces& places, const std::string& course,
                             std::string* error) {
    std::error_code ec;
    for (const std::string& f : spec.student_files) {
        fs::create_directories((places.reference / f).parent_path(), ec);
        fs::copy_file(places.lab / f, places.reference / f, ec);
        if (ec) {
            *error = (places.reference / f).string() + ": " + ec.message();
            return false;
        }
    }
    const fs::path schema = fs::path(course) / "docs" / "corpus.schema.json";
    fs::create_directories(places.corpus, ec);
    std::string cases = "{\n";
    if (fs::exists(schema, ec))
        cases += "  \"$schema\": " +
                 quoted(fs::relative(schema, fs::absolute(places.corpus), ec).generic_string()) + ",\n";
    cases += "  \"lab\": " + quoted(spec.id) + ",\n  \"cases\": [\n  ]\n}\n";
    return writeText(places.corpus / "cases.json", cases, error);
}

// The row in the course index; a note instead when there is no index to put it in.
bool addIndexRow(const LabSpec& spec, const NewLabPlaces& places, std::string* note, std::string* error) {
    const FileText index = readFile(places.index.string());
    if (!index.ok) {
        *note = places.index.string() + ": no course index (" + index.error + "): add the lab's row yourself";
        return true;
    }
    if (index.text.find(courseIndexLink(spec.id)) != std::string::npos) {
        *note = places.index.string() + " links " + spec.id + " already";
        return true;
    }
    std::string text;
    if (!insertCourseIndexRow(index.text, spec.id, courseIndexRow(spec), &text)) {
        *note = places.index.string() + " has no table of labs (\"| lab | ...\"): add the lab's row yourself";
        return true;
    }
    return writeText(places.index, text, error);
}

std::string shown(const fs::path& p, const std::string& course) {
    const fs::path rel = p.lexically_relative(course);
    return rel.empty() || *rel.begin() == ".." ? p.string() : rel.string();
}

void printNextSteps(const NewLabArgs& args, const LabSpec& spec, const NewLabPlaces& places,
                    const std::string& course, const std::string& note) {
    std::string where;  // the folders given, for the commands below to find the lab too
    if (!args.common.labs_root.empty()) where += " --labs " + places.labs_root;
    if (!args.reference_root.empty()) where += " --reference " + args.reference_root;
    if (!args.corpus_root.empty()) where += " --corpus " + args.corpus_root;
    const std::string& id = spec.id;
    std::printf("new lab %s (\"%s\")%s:\n", id.c_str(), spec.title.c_str(),
                args.like.empty() ? "" : (", like " + args.like).c_str());
    std::printf("  %s/  lab.json, README.md and the starter files\n", shown(places.lab, course).c_str());
    std::printf("  %s/  the student files, to solve\n", shown(places.reference, course).c_str());
    std::printf("  %s  no cases yet\n", shown(places.corpus / "cases.json", course).c_str());
    if (note.empty())
        std::printf("  %s  a row for %s: write what a student learns in it\n",
                    shown(places.index, course).c_str(), id.c_str());
    else
        std::printf("  note: %s\n", note.c_str());
    std::printf(
        "next (docs/authoring.md):\n"
        "  1. goals, passes and scenes in %s/lab.json; the starter files, with TODO(student) markers\n"
        "  2. the README's text; its goals and scenes tables follow lab.json: shaderlab lab-check %s "
        "--fix%s\n"
        "  3. the solution in %s/\n"
        "  4. shaderlab goldens --lab %s%s\n"
        "  5. the corpus, at least 6 mistakes and 3 alternatives, one case at a time:\n"
        "     shaderlab corpus add-case %s NAME --kind mistake --fails GOAL --about \"...\" --from DIR%s\n"
        "     then shaderlab goldens --lab %s%s again, for the mistakes' hints\n"
        "  6. shaderlab lab-check %s%s\n",
        shown(places.lab, course).c_str(), id.c_str(), where.c_str(), shown(places.reference, course).c_str(),
        id.c_str(), where.c_str(), id.c_str(), where.c_str(), id.c_str(), where.c_str(), id.c_str(),
        where.c_str());
}

}  // namespace

int runNewLab(const NewLabArgs& args) {
    NewLabPlaces places;
    if (!resolveLabsRoot(args.common, &places.labs_root)) return 2;
    const std::string course = fs::path(places.labs_root).parent_path().string();
    places.lab = fs::path(places.labs_root) / args.id;
    places.reference = (args.reference_root.empty() ? fs::path(course) / "reference_solutions"
                                                    : fs::path(args.reference_root)) /
                       args.id;
    places.corpus =
        (args.corpus_root.empty() ? fs::path(course) / "tests" / "corpus" : fs::path(args.corpus_root)) /
        args.id;
    places.index = fs::path(places.labs_root) / "README.md";
    if (const std::string why = refuseId(args, places); !why.empty()) return refused(why);
    std::error_code ec;
    if (!args.like.empty() && !fs::is_regular_file(fs::path(places.labs_root) / args.like / "lab.json", ec))
        return refused("--like " + args.like + ": there is no such lab in " + places.labs_root +
                       didYouMean(args.like, listLabIds(places.labs_root)));
    if (!args.like.empty()) {
        const LabSpecResult like = parseLabSpec((fs::path(places.labs_root) / args.like).string());
        for (const std::string& e : like.errors) std::cerr << e << "\n";
        if (!like.ok) return refused("--like " + args.like + ": its lab.json does not parse (above)");
    }
    const std::string title = args.title.empty() ? titleFromId(args.id) : args.title;

    // Written in turn; anything written goes again when a later step fails.
    auto undo = [&] {
        for (const fs::path& p : {places.lab, places.reference, places.corpus}) fs::remove_all(p, ec);
    };
    LabSpecResult parsed;
    std::string error, note;
    if (!writeLabFolder(args, places, title, &parsed, &error) ||
        !writeReferenceAndCorpus(parsed.spec, places, course, &error) ||
        !addIndexRow(parsed.spec, places, &note, &error)) {
        undo();
        return refused(error + "; nothing was written");
    }
    printNextSteps(args, parsed.spec, places, course, note);
    return 0;
}

}  // namespace shaderlab::cli
