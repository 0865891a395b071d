// A reference file with a student's functions swapped in; see glsl_compose.h.
#include "shaderlab/glsl/glsl_compose.h"

#include <algorithm>
#include <map>
#include <set>

#include "shaderlab/glsl/glsl_outline.h"

namespace shaderlab::glsl {

namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

bool isInterface(const Declaration& d) {
    return (d.kind == DeclKind::Variable || d.kind == DeclKind::Block) &&
           (d.storage == "uniform" || d.storage == "in" || d.storage == "out" || d.storage == "buffer" ||
            d.storage == "attribute" || d.storage == "varying");
}

bool isPlainGlobal(const Declaration& d) {
    return d.kind == DeclKind::Variable && (d.storage.empty() || d.storage == "shared");
}

bool sameSignature(const Declaration& a, const Declaration& b) {
    return a.return_type == b.return_type && a.parameter_types == b.parameter_types;
}

std::string typesOf(const Declaration& d) {
    std::string out;
    for (const std::string& p : d.parameter_types) out += (out.empty() ? "" : ", ") + p;
    return "(" + out + ")";
}

// Whether `name` is written by function `f` (assigned, incremented, or an element or member of
// it assigned).
bool writes(std::string_view text, const Outline& o, const Declaration& f, const std::string& name) {
    auto op = [&](std::size_t k) {
        return k <= f.last && o.tokens[k].kind == TokenKind::Operator ? tokenText(text, o.tokens[k])
                                                                      : std::string_view();
    };
    for (std::size_t k = f.body_first; k <= f.last; ++k) {
        if (o.tokens[k].kind != TokenKind::Identifier || tokenText(text, o.tokens[k]) != name) continue;
        if (k > 0 && (op(k - 1) == "." || op(k - 1) == "++" || op(k - 1) == "--")) {
            if (op(k - 1) != ".") return true;
            continue;
        }
        std::size_t j = k + 1;
        // Skip `[...]` and `.member` after the name.
        while (j <= f.last) {
            if (op(j) == "[") {
                int depth = 0;
                for (; j <= f.last; ++j) {
                    if (op(j) == "[") ++depth;
                    if (op(j) == "]" && --depth == 0) break;
                }
                ++j;
            } else if (op(j) == "." && j + 1 <= f.last) {
                j += 2;
            } else {
                break;
            }
        }
        const std::string_view next = op(j);
        if (next == "=" || next == "+=" || next == "-=" || next == "*=" || next == "/=" || next == "%=" ||
            next == "&=" || next == "|=" || next == "^=" || next == "<<=" || next == ">>=" || next == "++" ||
            next == "--")
            return true;
    }
    return false;
}

class Composer {
  public:
    explicit Composer(const ComposeInput& in)
        : in_(in), ref_(outlineGlsl(in.reference)), stu_(outlineGlsl(in.student)) {}

    Composed run() {
        Composed out;
        if (!ref_.error.empty())
            return fail("the reference's " + in_.file + " cannot be read: " + ref_.error);
        if (!stu_.error.empty()) return fail(in_.file + ": " + stu_.error);
        for (const Declaration& d : stu_.declarations)
            if (d.kind == DeclKind::Directive && (d.directive == "if" || d.directive == "ifdef" ||
                                                  d.directive == "ifndef" || d.directive == "elif"))
                return fail(in_.file + " has #" + d.directive +
                            " blocks, so its functions cannot be taken alone");
        if (!pairTakenFunctions(&out.note)) return fail(out.note);
        takeChangedCallers(&out.callers);
        if (startersOnly()) {
            Composed c = fail(starterNote());
            c.starter_untouched = true;
            return c;
        }
        std::string why;
        if (!close(&why)) return fail(why);
        nameImports();
        out.ok = true;
        out.text = assemble();
        for (const Declaration* d : imports_)
            for (const std::string& n : d->names) out.imported.push_back(renamed(n));
        return out;
    }

  private:
    Composed fail(const std::string& note) const {
        Composed c;
        c.note = note;
        return c;
    }

    // Each reference definition of a taken function beside the student's with the same signature.
    bool pairTakenFunctions(std::string* why) {
        for (const std::string& name : in_.take) {
            std::vector<const Declaration*> refs;
            for (const Declaration* d : declarationsNamed(ref_, name))
                if (d->kind == DeclKind::Function) refs.push_back(d);
            if (refs.empty()) {
                *why = "the reference's " + in_.file + " has no function `" + name + "` (a fault of the lab)";
                return false;
            }
            for (const Declaration* r : refs) {
                const Declaration* mine = nullptr;
                const Declaration* other = nullptr;
                for (const Declaration* d : declarationsNamed(stu_, name)) {
                    if (d->kind != DeclKind::Function) continue;
                    if (sameSignature(*d, *r)) mine = d;
                    other = other ? other : d;
                }
                if (!mine) {
                    *why = other ? "`" + name + "` in " + in_.file + " takes " + typesOf(*other) +
                                       " and returns " + other->return_type + ", but the lab asks for `" +
                                       r->head + "`"
                                 : in_.file + " has no function `" + r->head + "`";
                    return false;
                }
                taken_.push_back({r, mine});
            }
        }
        return true;
    }

    // Code no goal asks for but the student changed (a `main` the starter gives, say) goes with
    // the taken functions it calls, so that breaking given code costs the goal it feeds instead of
    // nothing. A `main` that calls no goal's function (the work written into it) goes with
    // whatever is taken from the file. Only a function the reference has with the same signature
    // can be swapped.
    void takeChangedCallers(std::vector<std::string>* names) {
        for (const Declaration& d : stu_.declarations) {
            if (d.kind != DeclKind::Function || d.names.empty()) continue;
            const std::string& name = d.names[0];
            if (contains(in_.take, name) || contains(in_.keep, name) || isTakenDecl(&d)) continue;
            const Declaration* r = nullptr;
            bool same = false;
            for (const Declaration* x : declarationsNamed(ref_, name)) {
                if (x->kind != DeclKind::Function) continue;
                if (sameSignature(*x, d)) r = x;
                same = same || canonicalText(in_.reference, ref_, *x) == canonicalText(in_.student, stu_, d);
            }
            if (!r || same) continue;
            const auto calls = [&](const std::vector<std::string>& functions) {
                return std::any_of(d.uses.begin(), d.uses.end(),
                                   [&](const std::string& u) { return contains(functions, u); });
            };
            if (!calls(in_.take) && (name != "main" || calls(in_.keep))) continue;
            taken_.push_back({r, &d});
            names->push_back(name);
        }
    }

    // True when every taken function is the starter's, where the starter differs from the
    // reference: the student's work for it is elsewhere (inlined in main, say).
    bool startersOnly() const {
        if (in_.starter.empty()) return false;
        const Outline starter = outlineGlsl(in_.starter);
        bool any_work = false;
        for (const auto& [r, mine] : taken_) {
            const Declaration* s = nullptr;
            for (const Declaration* d : declarationsNamed(starter, r->names[0]))
                if (d->kind == DeclKind::Function && sameSignature(*d, *r)) s = d;
            if (!s) return false;
            const std::string starter_text = canonicalText(in_.starter, starter, *s);
            if (starter_text == canonicalText(in_.reference, ref_, *r)) continue;  // nothing to do there
            any_work = true;
            if (canonicalText(in_.student, stu_, *mine) != starter_text) return false;
        }
        return any_work;
    }

    // Whether the starter gives the reference's function `r` as it is: no work to do there.
    bool givenComplete(const Outline& starter, const Declaration& r) const {
        for (const Declaration* d : declarationsNamed(starter, r.names[0]))
            if (d->kind == DeclKind::Function && sameSignature(*d, r) &&
                canonicalText(in_.starter, starter, *d) == canonicalText(in_.reference, ref_, r))
                return true;
        return false;
    }

    // Names the taken functions that had work to do (startersOnly), not those the starter gives whole.
    std::string starterNote() const {
        const Outline starter = outlineGlsl(in_.starter);
        std::string names;
        for (const auto& [r, mine] : taken_)
            if (!givenComplete(starter, *r) && names.find("`" + r->names[0] + "`") == std::string::npos)
                names += (names.empty() ? "`" : ", `") + r->names[0] + "`";
        const bool several = names.find(',') != std::string::npos;
        return names + " in " + in_.file + (several ? " are" : " is") + " still as the starter had " +
               (several ? "them" : "it");
    }

    std::vector<std::string> canonicalAll(std::string_view text, const Outline& o, const std::string& name,
                                          bool functions) const {
        std::vector<std::string> out;
        for (const Declaration* d : declarationsNamed(o, name)) {
            if (functions && d->kind != DeclKind::Function) continue;
            out.push_back(canonicalText(text, o, *d));
        }
        std::sort(out.begin(), out.end());
        return out;
    }

    bool isTakenDecl(const Declaration* d) const {
        return std::any_of(taken_.begin(), taken_.end(), [&](const auto& p) { return p.second == d; });
    }

    // What the taken functions use from the student's file, and what that uses in turn.
    bool close(std::string* why) {
        std::vector<const Declaration*> work;
        for (const auto& [r, mine] : taken_) work.push_back(mine);
        std::set<const Declaration*> done(work.begin(), work.end());
        std::vector<std::pair<std::string, const Declaration*>> globals;  // plain globals, and who reads them
        while (!work.empty()) {
            const Declaration* d = work.back();
            work.pop_back();
            for (const std::string& use : d->uses) {
                if (contains(in_.take, use) || contains(in_.keep, use)) continue;
                const std::vector<const Declaration*> mine = declarationsNamed(stu_, use);
                if (mine.empty()) continue;  // a local, a parameter, or the prelude's
                const Declaration& first = *mine.front();
                if (isInterface(first) && !declarationsNamed(ref_, use).empty()) {
                    swapUniform(use, first);
                    continue;
                }
                const bool function = first.kind == DeclKind::Function || first.kind == DeclKind::Prototype;
                if (canonicalAll(in_.student, stu_, use, function) ==
                    canonicalAll(in_.reference, ref_, use, function))
                    continue;  // the reference has it, token for token
                if (std::any_of(mine.begin(), mine.end(),
                                [](const Declaration* m) { return isPlainGlobal(*m); }))
                    globals.push_back({use, d});
                for (const Declaration* m : mine) {
                    if (m->kind == DeclKind::Prototype || isTakenDecl(m)) continue;
                    if (function && m->kind != DeclKind::Function) continue;
                    if (done.insert(m).second) work.push_back(m);
                }
            }
        }
        for (const Declaration& d : stu_.declarations)
            if (done.count(&d) && !isTakenDecl(&d)) imports_.push_back(&d);
        // A plain global that code outside what is taken writes (main, usually) holds a value the
        // reference's code never sets.
        for (const auto& [name, reader] : globals) {
            for (const Declaration& f : stu_.declarations) {
                if (f.kind != DeclKind::Function || done.count(&f) || !writes(in_.student, stu_, f, name))
                    continue;
                *why = "`" + reader->names[0] + "` in " + in_.file + " reads the global variable `" + name +
                       "`, which `" + f.names[0] + "` sets";
                return false;
            }
        }
        return true;
    }

    // A uniform the student's code reads, declared by the reference with another type (a
    // sampler2D where the reference has a sampler2DShadow: the lab feeds either): the student's
    // declaration stands in for the reference's, which must declare nothing else. Inputs and
    // outputs stay the reference's: the other stage must match them.
    void swapUniform(const std::string& name, const Declaration& mine) {
        const std::vector<const Declaration*> theirs = declarationsNamed(ref_, name);
        if (mine.storage != "uniform" || mine.kind != DeclKind::Variable || mine.names.size() != 1 ||
            theirs.size() != 1 || theirs[0]->kind != DeclKind::Variable || theirs[0]->names.size() != 1)
            return;
        if (canonicalText(in_.student, stu_, mine) == canonicalText(in_.reference, ref_, *theirs[0])) return;
        for (const auto& swap : uniform_swaps_)
            if (swap.first == theirs[0]) return;
        uniform_swaps_.push_back({theirs[0], &mine});
    }

    // Imported names the reference also declares get a name of their own.
    void nameImports() {
        std::set<std::string> used;
        for (const Outline* o : {&ref_, &stu_})
            for (const Token& t : o->tokens)
                if (t.kind == TokenKind::Identifier)
                    used.insert(std::string(tokenText(o == &ref_ ? in_.reference : in_.student, t)));
        for (const Declaration* d : imports_)
            for (const std::string& n : d->names) {
                if (declarationsNamed(ref_, n).empty() || renames_.count(n)) continue;
                std::string candidate = n + "_student";
                for (int k = 2; used.count(candidate); ++k) candidate = n + "_student" + std::to_string(k);
                used.insert(candidate);
                renames_[n] = candidate;
            }
    }

    std::string renamed(const std::string& n) const {
        const auto it = renames_.find(n);
        return it == renames_.end() ? n : it->second;
    }

    // The student's text of a declaration with the imported names renamed.
    std::string studentText(const Declaration& d) const {
        std::string out;
        std::size_t at = d.begin;
        for (std::size_t k = d.first; k <= d.last; ++k) {
            const Token& t = stu_.tokens[k];
            if (t.kind != TokenKind::Identifier) continue;
            if (k > 0 && stu_.tokens[k - 1].kind == TokenKind::Operator &&
                tokenText(in_.student, stu_.tokens[k - 1]) == ".")
                continue;
            const auto it = renames_.find(std::string(tokenText(in_.student, t)));
            if (it == renames_.end()) continue;
            out.append(in_.student.substr(at, t.begin - at));
            out += it->second;
            at = t.end;
        }
        out.append(in_.student.substr(at, d.end - at));
        return out;
    }

    // The reference's text with each taken function replaced by the student's, and before the
    // first of them what the student's functions need: prototypes of the functions they call that
    // are defined later, then the imported declarations in the student's order.
    std::string assemble() const {
        std::size_t at = in_.reference.size();
        for (const auto& [r, mine] : taken_) at = std::min(at, r->begin);
        // A function needs a prototype where a taken function or an import calls it before its
        // definition: an import sits at `at`, a taken function where the reference's was.
        std::set<std::string> imported_calls;
        for (const Declaration* d : imports_) imported_calls.insert(d->uses.begin(), d->uses.end());
        const auto calledBefore = [&](const Declaration& callee) {
            if (imported_calls.count(callee.names[0])) return true;
            for (const auto& [r, mine] : taken_)
                if (r->begin < callee.begin &&
                    std::find(mine->uses.begin(), mine->uses.end(), callee.names[0]) != mine->uses.end())
                    return true;
            return false;
        };
        std::string prototypes;
        std::set<std::string> declared;
        for (const Declaration& d : ref_.declarations) {
            if (d.kind != DeclKind::Function || d.begin < at || d.names[0] == "main" || !calledBefore(d))
                continue;
            const std::string head = d.head + ";";
            if (declared.insert(head).second) prototypes += head + "\n";
        }
        std::string imports;
        for (const Declaration* d : imports_) imports += studentText(*d) + "\n";
        if (!(prototypes + imports).empty() && at > 0 && in_.reference[at - 1] != '\n')
            imports.insert(imports.begin(), '\n');
        // Every change to the reference, in the order of the text: the uniforms whose declaration
        // is the student's, what the student's functions need (before the first of them), and the
        // functions taken.
        struct Change {
            std::size_t begin, end;
            std::string text;
        };
        std::vector<Change> changes;
        for (const auto& [r, mine] : uniform_swaps_)
            changes.push_back({r->begin, r->end, studentText(*mine)});
        changes.push_back({at, at, prototypes + imports});
        for (const auto& [r, mine] : taken_) changes.push_back({r->begin, r->end, studentText(*mine)});
        std::stable_sort(changes.begin(), changes.end(),
                         [](const Change& a, const Change& b) { return a.begin < b.begin; });
        std::string out;
        std::size_t from = 0;
        for (const Change& c : changes) {
            out.append(in_.reference.substr(from, c.begin - from));
            out += c.text;
            from = c.end;
        }
        out.append(in_.reference.substr(from));
        return out;
    }

    const ComposeInput& in_;
    Outline ref_, stu_;
    std::vector<std::pair<const Declaration*, const Declaration*>> taken_;  // reference's, student's
    std::vector<const Declaration*> imports_;                               // in the student's order
    std::map<std::string, std::string> renames_;
    std::vector<std::pair<const Declaration*, const Declaration*>> uniform_swaps_;  // reference's, student's
};

}  // namespace

Composed composeFunctions(const ComposeInput& in) { return Composer(in).run(); }

}  // namespace shaderlab::glsl
