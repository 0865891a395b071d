// Link logs explained: Mesa prints link problems without positions, repeated, with a stray '.'
// on the next line. This keeps each problem once, explains the common ones (an `in` with no
// matching `out`, types or interpolation that differ between the stages, a missing `main`, a
// prototype without a body) and places it at the declaration it concerns; a message it does not
// know passes through with parser jargon replaced. It reads no compile log (glsl_explain.cpp does).
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "glsl_explain_detail.h"
#include "shaderlab/base/json_messages.h"

namespace shaderlab {

using namespace glsl_detail;

namespace {

// The program's two stages, read, and their files' names for messages.
struct Program {
    const StageModel& vm;
    const StageModel& fm;
    const std::string& vfile;
    const std::string& ffile;

    // At a declaration of `name` (fragment first, then vertex); without one, the pair of files.
    void place(Diagnostic& d, const std::string& name, std::initializer_list<const char*> storages,
               bool vertex_first) const {
        const Decl* fdecl = findGlobal(fm, name, storages);
        const Decl* vdecl = findGlobal(vm, name, storages);
        const StageModel* sm = nullptr;
        const Decl* decl = nullptr;
        if (vertex_first ? vdecl != nullptr : fdecl == nullptr) {
            sm = &vm;
            decl = vdecl;
        } else {
            sm = &fm;
            decl = fdecl;
        }
        if (!decl) {
            d.file = vfile + " + " + ffile;
            return;
        }
        d.file = sm->text->files[decl->file];
        d.line = decl->line;
        d.column = decl->column;
        attachSource(d, *sm, decl->file);
    }
};

std::string lineOfDecl(const Decl* d) {
    return d ? " (line " + std::to_string(d->line) + ")" : std::string();
}

void explainTypeMismatch(Diagnostic& d, const Program& prog, const std::smatch& m) {
    const std::string name = m[2];
    prog.place(d, name, {"in", "varying"}, false);
    d.message = quote(name) + " is a " + m[3].str() + " in " + prog.vfile + " but a " + m[5].str() + " in " +
                prog.ffile;
    d.explanation =
        "A value passed from the vertex stage to the fragment stage has the same type on both "
        "sides: declare `in " +
        m[3].str() + " " + name + ";` here, or make the `out` in " + prog.vfile +
        lineOfDecl(findGlobal(prog.vm, name, {"out", "varying"})) + " a " + m[5].str() + ".";
}

void explainInterpolation(Diagnostic& d, const Program& prog, const std::smatch& m) {
    const std::string name = m[2];
    prog.place(d, name, {"in", "varying"}, false);
    const std::string a = m[3] == "no" ? "none" : m[3].str(), b = m[5] == "no" ? "none" : m[5].str();
    d.message = quote(name) + " is interpolated differently in the two stages (" + a + " in " + prog.vfile +
                ", " + b + " in " + prog.ffile + ")";
    d.explanation = "Write the same qualifier (`flat`, `smooth` or `noperspective`) on the `out` in " +
                    prog.vfile + " and the `in` in " + prog.ffile + ".";
}

// A varying the vertex stage declares but never writes, or a fragment `in` with no `out` of its
// name in the vertex stage.
void explainUnmatchedVarying(Diagnostic& d, const Program& prog, const std::smatch& m) {
    const std::string name = m[2];
    const Decl* vout = findGlobal(prog.vm, name, {"out", "varying"});
    const Decl* fin = findGlobal(prog.fm, name, {"in", "varying"});
    const std::string type = fin ? fin->type : "vec3";
    if (vout) {
        prog.place(d, name, {"out", "varying"}, true);
        d.message = "output " + quote(name) + " of " + prog.vfile + " is never written";
        d.explanation = prog.ffile + " reads it and gets an undefined value (zero here). Assign it in " +
                        prog.vfile + "'s main().";
    } else {
        prog.place(d, name, {"in", "varying"}, false);
        // The name it was meant to be: a close spelling, else the one output of that
        // type no input receives (v_normal for v_world_normal is too far to spell).
        std::vector<std::string> outs, unread;
        for (const Decl& decl : prog.vm.decls) {
            if (!decl.global || (decl.storage != "out" && decl.storage != "varying")) continue;
            outs.push_back(decl.name);
            if (decl.type == type && !findGlobal(prog.fm, decl.name, {"in", "varying"}))
                unread.push_back(decl.name);
        }
        std::string guess = closestMatch(name, outs);
        if (guess.empty() && unread.size() == 1) guess = unread.front();
        d.message = prog.ffile + " reads " + quote(name) + ", but " + prog.vfile +
                    " has no output of that name" +
                    (guess.empty() ? "" : "; did you mean " + quote(guess) + "?");
        d.explanation =
            "Each `in` of the fragment stage receives the vertex stage's `out` of the same name "
            "and type; without one it is undefined (zero here). Declare `out " +
            type + " " + name + ";` in " + prog.vfile + " and write it, or use the name " + prog.vfile +
            " already gives.";
    }
}

void explainUniformTypes(Diagnostic& d, const Program& prog, const std::smatch& m) {
    const std::string name = m[1];
    prog.place(d, name, {"uniform"}, false);
    d.message = "uniform " + quote(name) + " has different types in the two stages (" + m[2].str() + " and " +
                m[3].str() + ")";
    d.explanation = "A uniform used by both stages is one value: declare it with the same type in " +
                    prog.vfile + lineOfDecl(findGlobal(prog.vm, name, {"uniform"})) + " and " + prog.ffile +
                    lineOfDecl(findGlobal(prog.fm, name, {"uniform"})) + ".";
}

void explainLacksMain(Diagnostic& d, const Program& prog, const std::smatch& m) {
    const bool is_vertex = m[1] == "vertex";
    const StageModel& sm = is_vertex ? prog.vm : prog.fm;
    d.file = is_vertex ? prog.vfile : prog.ffile;
    std::vector<std::string> functions;
    for (const Decl& decl : sm.decls)
        if (decl.storage == "function") functions.push_back(decl.name);
    const std::string guess = closestMatch("main", functions);
    d.message = d.file + " has no `main` function";
    d.explanation = "Every stage starts at `void main()`.";
    if (const Decl* near = guess.empty() ? nullptr : findDecl(sm, guess, true)) {
        d.file = sm.text->files[near->file];
        d.line = near->line;
        d.column = near->column;
        attachSource(d, sm, near->file);
        d.explanation += " " + quote(guess) + " looks like it was meant to be it.";
    }
}

void explainUnresolved(Diagnostic& d, const Program& prog, const std::smatch& m) {
    const std::string name = m[1];
    d.message = quote(name) + " is declared but never defined";
    d.explanation = "A prototype such as `float " + name +
                    "(vec3 n);` promises a body with the same parameter types in the same stage: write "
                    "the function, or fix its parameter types to match.";
    for (const StageModel* sm : {&prog.fm, &prog.vm}) {
        const Decl* decl = findDecl(*sm, name, true);
        if (!decl || d.line) continue;
        d.file = sm->text->files[decl->file];
        d.line = decl->line;
        d.column = decl->column;
        attachSource(d, *sm, decl->file);
    }
    if (!d.line) d.file = prog.vfile + " + " + prog.ffile;
}

// One problem of the log, `msg` without its "error:" or "warning:".
void explainLinkProblem(Diagnostic& d, const Program& prog, const std::string& msg) {
    static const std::regex type_mismatch(
        R"(^(\w+) shader output `(\w+)' declared as type `(\w+)', but (\w+) shader input declared as type `(\w+)'$)");
    static const std::regex interpolation(
        R"(^(\w+) shader output `(\w+)' specifies (\w+) interpolation qualifier, but (\w+) shader input specifies (\w+) interpolation qualifier$)");
    static const std::regex not_written(R"(^(\w+) shader varying (\w+) not written by (\w+) shader$)");
    static const std::regex no_output(
        R"(^(\w+) shader input `(\w+)' has no matching output in the previous stage$)");
    static const std::regex uniform_types(R"(^uniform `(\w+)' declared as type `(\w+)' and type `(\w+)'$)");
    static const std::regex lacks_main(R"(^(\w+) shader lacks `main'$)");
    static const std::regex unresolved(R"(^unresolved reference to function `(\w+)'$)");
    std::smatch m;
    if (std::regex_match(msg, m, type_mismatch)) {
        explainTypeMismatch(d, prog, m);
    } else if (std::regex_match(msg, m, interpolation)) {
        explainInterpolation(d, prog, m);
    } else if (std::regex_match(msg, m, not_written) || std::regex_match(msg, m, no_output)) {
        explainUnmatchedVarying(d, prog, m);
    } else if (std::regex_match(msg, m, uniform_types)) {
        explainUniformTypes(d, prog, m);
    } else if (std::regex_match(msg, m, lacks_main)) {
        explainLacksMain(d, prog, m);
    } else if (std::regex_match(msg, m, unresolved)) {
        explainUnresolved(d, prog, m);
    } else {
        d.file = prog.vfile + " + " + prog.ffile;
        d.message = msg;
    }
}

}  // namespace

std::vector<Diagnostic> explainLinkLog(const std::string& log, const StageText& vertex,
                                       const StageText& fragment) {
    const StageModel vm = buildModel(vertex), fm = buildModel(fragment);
    const std::string& vfile = vertex.files.empty() ? vertex.stage : vertex.files[0];
    const std::string& ffile = fragment.files.empty() ? fragment.stage : fragment.files[0];
    std::vector<Diagnostic> out;
    std::set<std::string> seen;
    const Program prog{vm, fm, vfile, ffile};
    std::istringstream in(log);
    std::string raw;
    while (std::getline(in, raw)) {
        // Mesa ends each message with "\n." and may print it once per link step.
        std::string line = trim(raw);
        while (!line.empty() && line[0] == '.') line = trim(line.substr(1));
        if (line.empty() || !seen.insert(line).second) continue;
        Diagnostic d;
        d.driver_message = line;
        std::string msg = line;
        d.severity = "error";
        if (msg.rfind("error:", 0) == 0) {
            msg = trim(msg.substr(6));
        } else if (msg.rfind("warning:", 0) == 0) {
            d.severity = "warning";
            msg = trim(msg.substr(8));
        }
        explainLinkProblem(d, prog, msg);
        d.message = scrubJargon(d.message);
        d.explanation = scrubJargon(d.explanation);
        out.push_back(std::move(d));
    }
    return out;
}

}  // namespace shaderlab
