// One shader file composed of two versions of it: the reference solution's, with some of a
// student's functions swapped in, so that a goal is judged on the student's own work for it and the
// reference's for everything else (error carried forward; docs/grading.md, "Goal isolation").
//
// The student's functions come with what they use from the student's file: helper functions,
// constants, structs, macros, and the globals only they write. What the reference has token for
// token is the reference's; what it has under the same name but different is brought along
// renamed (`name_student`), so nothing clashes. Uniforms, inputs and outputs are the lab's
// interface: the reference's declarations stand. A function that another goal is judged on
// (`keep`) stays the reference's even where the student's code calls it. A function neither taken
// nor kept that the student changed is taken too when it calls a taken function (`callers`).
//
// It composes text; whether the result compiles is the driver's to say. It refuses, with a
// sentence for the student, what it cannot take alone: a function that is missing or has another
// signature, one still as the starter had it, one that reads a global variable `main` sets, a file
// with #if blocks or unbalanced brackets.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace shaderlab::glsl {

struct ComposeInput {
    std::string file;               // the file's name, for the notes ("phong.frag")
    std::string_view reference;     // the reference solution's text of the file
    std::string_view student;       // the student's
    std::string_view starter;       // the lab's starter; empty: not known
    std::vector<std::string> take;  // the functions taken from the student (each the reference defines)
    std::vector<std::string> keep;  // functions that stay the reference's where the student's code calls them
};

struct Composed {
    bool ok = false;
    std::string text;  // ok: the composed file
    // !ok: why the functions could not be taken alone, in words for the student.
    std::string note;
    // !ok because every function taken is still the starter's (the work may be elsewhere).
    bool starter_untouched = false;
    // The student's declarations brought along besides the functions taken, as named in `text`.
    std::vector<std::string> imported;
    // Functions no goal asks for that the student changed and that were taken with the work they
    // call (a `main` the starter gives, say): the student's code, judged with the goal.
    std::vector<std::string> callers;
};

Composed composeFunctions(const ComposeInput& in);

}  // namespace shaderlab::glsl
