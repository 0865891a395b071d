// Mutants of a reference solution's file: the small changes a student's mistakes look like, each
// applied alone to one place in the body of a function, for `shaderlab mutants` (coverage by
// mutation, docs/authoring.md "Mutants"): a mutant that changes what the code computes yet passes
// every goal shows an idea that no scene witnesses, unless it is declared equivalent in the lab's
// corpus with the reason.
//
// The operators (R. A. DeMillo, R. J. Lipton, F. G. Sayward, "Hints on Test Data Selection",
// IEEE Computer 11(4), 1978, for the idea; these are the shapes shader mistakes take):
//   constant        a number changed: 0 -> 1, an integer n -> n + 1, any other value doubled
//   operator        + and -, * and /, < and <=, > and >=, == and !=, && and ||, += and -=, *= and /=
//   swizzle         .x -> .y (y -> z, z -> x, w -> x; rgba alike), .xyz -> .zyx (reversed)
//   sign            a unary minus dropped
//   call            normalize(x), max(x, ...), min(x, ...), clamp(x, ...) -> (x)
//   term-dropped    a + b -> a (a term of a sum or difference left out)
//   term-doubled    a + b -> a + b + b
//   distribute      a * (b + c) -> a * b + c
//   into-loop       the statement before a for loop moved to the start of its body
//   out-of-loop     the last statement of a for loop's body moved after the loop
// It mutates text; whether a mutant compiles is the driver's to say (one that does not is no
// mutant of what the code computes, and is left out by the caller).
#pragma once

#include <set>
#include <string>
#include <vector>

namespace shaderlab::authoring {

struct Mutant {
    // Stable while the function is unchanged: "<file>:<function>:<operator>#<k>", k counting that
    // operator's places in the function from 1.
    std::string id;
    std::string file, function, op;
    int line = 0;        // of the change, in the original file
    std::string change;  // "`max(dot(n, l), 0.0)` -> `(dot(n, l))`", cut to a line
    std::string text;    // the whole mutated file
};

// Every mutant of `text` (the file `file`) in the bodies of its functions, in the order of the
// text; two mutants that give the same file are one (the first).
std::vector<Mutant> mutateFile(const std::string& file, const std::string& text);

// The functions of `reference` that the starter `starter` gives as they are (the same head and
// body, token for token): code the course provides, not the student's work, so not mutated.
std::set<std::string> providedFunctions(const std::string& reference, const std::string& starter);

// The lines of `reference` (numbered from 1) inside a function that also holds that line in the
// starter (comments and spacing aside): statements the course gives, such as a debug view in a main
// the student completes. A mistake is not made by changing them in place (moving one into or out of
// a loop is: that is mutated still).
std::set<int> providedLines(const std::string& reference, const std::string& starter);

}  // namespace shaderlab::authoring
