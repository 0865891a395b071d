#!/usr/bin/env python3
"""A class as it really arrives, with everything in it planted, for the tests of `shaderlab batch`,
`class` and `similarity` (tests/planted_class/planted_class_test.py; docs/instructors.md).

Usage: make_planted_class.py OUT_DIR

Writes OUT_DIR/submissions/ (31 submissions: folders, and a zip with a wrapper folder and an
accented name) and OUT_DIR/truth.json, which says what was planted where:
  - the assignment is three labs of the course's twelve: 01-phong, 02-toon, 11-shadow-mapping;
  - correct work written in several ways (the reference and the corpus's alternative solutions);
  - four shared mistakes (tests/corpus: gouraud, steps-round, no-bias, pcf-single-tap), a shader
    that never compiles, a light loop without ++i, Phong.frag for phong.frag, an empty lab
    folder, two Blinn-Phong solutions written apart (below), three disguised copies (names,
    comments and layout changed), and a pair that hands in only the starter code.

truth.json, per student and lab: the expected status, the goals a mistake fails (the corpus's
"fails"), and, for the similarity report, each student file's origin ("reference", a corpus
case, a solution of its own). Two lab documents are
  - "copy": one was planted as a copy of the other, or every file has the same origin;
  - "independent": no file of one shares an origin with a file of the other (a corpus mistake is
    an edit of the reference: its origin is the reference's);
  - neither otherwise (the same vertex shader, say): the report may or may not flag them.
"""
import json
import os
import re
import shutil
import sys
import zipfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LABS = ["01-phong", "02-toon", "11-shadow-mapping"]

# Corpus alternatives that are the reference with a line changed (similarity_corpus_test.cpp):
# their origin is the reference's.
EDITS_OF_THE_REFERENCE = {("11-shadow-mapping", "light-space-in-vertex-shader")}

# Two Blinn-Phong solutions written apart (blinn-a/, blinn-b/), each as a student fills in the
# starter's TODOs in the starter's order with the README's formulas: the same mistake (the half
# vector instead of the mirror direction), two hands, one template. Short solutions of a lab that
# dictates its formulas share much by that alone: the similarity report must not call these two a
# copy (issue 33: two such solutions shared 21 of 26 fingerprints; these, alone, 21 of 27).
HERE = os.path.dirname(os.path.abspath(__file__))


def read(path):
    with open(path, "rb") as f:
        return f.read().decode("utf-8")


def student_files(lab):
    with open(os.path.join(ROOT, "labs", lab, "lab.json")) as f:
        return json.load(f)["student_files"]


def corpus_case(lab, name):
    with open(os.path.join(ROOT, "tests/corpus", lab, "cases.json")) as f:
        for c in json.load(f)["cases"]:
            if c["name"] == name:
                return c
    raise KeyError(lab + "/" + name)


def lab_files(lab, source):
    """{file: (text, origin)} of one lab handed in as `source` says."""
    files = student_files(lab)
    starter = {f: (read(os.path.join(ROOT, "labs", lab, f)), "starter") for f in files}
    reference = {f: (read(os.path.join(ROOT, "reference_solutions", lab, f)), "reference")
                 for f in files}
    kind, _, name = source.partition(":")
    if kind == "starter":
        return starter
    if kind == "reference":
        return reference
    if kind in ("alt", "mistake", "broken"):
        out = dict(reference)
        case_dir = os.path.join(ROOT, "tests/corpus", lab, name)
        own = "reference" if kind != "alt" or (lab, name) in EDITS_OF_THE_REFERENCE else "alt:" + name
        for f in files:
            if os.path.exists(os.path.join(case_dir, f)):
                out[f] = (read(os.path.join(case_dir, f)), own)
        return out
    if kind == "blinn":
        # Each with a vertex shader of its own too (two of the corpus's alternatives).
        out = lab_files(lab, "alt:" + ("equivalent-mvp-order" if name == "a" else "normal-matrix-in-shader"))
        out["phong.frag"] = (read(os.path.join(HERE, "blinn-" + name, "phong.frag")), "blinn-" + name)
        return out
    if kind == "loop":
        # The light loop without its ++i: i stays 0, the loop never ends (the loop guard stops it).
        out = dict(reference)
        text = out["phong.frag"][0]
        looped = text.replace("for (int i = 0; i < u_light_count; ++i)", "for (int i = 0; i < u_light_count;)")
        assert looped != text
        out["phong.frag"] = (looped, "reference")
        return out
    raise ValueError(source)


def disguise(text):
    """What a student who copies does: the comments gone and new ones written, the variables renamed
    (the lab's interface, u_/v_/a_/o_ names, functions and built-ins kept, so that it still compiles
    and draws the same), a layout of their own."""
    text = re.sub(r"/\*.*?\*/", "", text, flags=re.S)
    text = re.sub(r"//[^\n]*", "", text)
    types = r"(?:float|int|uint|bool|vec[234]|ivec[234]|bvec[234]|mat[234])"
    names = []
    for m in re.finditer(r"\b" + types + r"\s+([A-Za-z_][A-Za-z0-9_]*)\s*([=;,)\[])", text):
        name = m.group(1)
        # Functions keep their names: another file of the lab (shared code, the lab's own) calls them.
        if re.match(r"(u|v|a|o|gl)_|SL_|main$", name) or name in names:
            continue
        names.append(name)
    for k, name in enumerate(names):
        # Not after a '.': a variable named z is not the swizzle .z.
        text = re.sub(r"(?<![.\w])%s\b" % re.escape(name), "my%s%d" % (name.capitalize()[:3], k), text)
    lines = []
    depth = 0
    for raw in text.split("\n"):
        line = raw.strip()
        if not line:
            continue
        if line.startswith("}"):
            depth -= 1
        lines.append("  " * max(depth, 0) + re.sub(r"\s*,\s*", " , ", line))
        depth += line.count("{") - line.count("}") + (1 if line.startswith("}") else 0)
    # The #version line must stay first.
    return lines[0] + "\n// my solution, written myself\n" + "\n".join(lines[1:]) + "\n"


# Who hands in what. Each student: {lab: source}, a lab left out is not handed in. Sources:
# "reference", "alt:<corpus case>", "mistake:<case>", "broken:<case>", "starter", "loop",
# "blinn:a|b", "copy:<student>" (a disguised copy of that student's lab), "empty" (an empty folder).
ROSTER = [
    ("ada", {"01-phong": "reference", "02-toon": "reference", "11-shadow-mapping": "reference"}),
    ("ben", {"01-phong": "alt:reflect-builtin", "02-toon": "alt:steps-if-chain",
             "11-shadow-mapping": "alt:bias-constant"}),
    ("chloe", {"01-phong": "alt:light-kind-branch", "02-toon": "alt:ramp-eye-space",
               "11-shadow-mapping": "alt:pcf-unrolled-offsets"}),
    ("dmitri", {"01-phong": "alt:view-space-lighting", "02-toon": "alt:ramp-eye-space",
                "11-shadow-mapping": "alt:texelfetch-basic"}),
    ("eve", {"01-phong": "mistake:gouraud", "02-toon": "reference", "11-shadow-mapping": "reference"}),
    ("farid", {"01-phong": "mistake:gouraud", "02-toon": "alt:ramp-texel-fetch",
               "11-shadow-mapping": "alt:bias-one-minus-ndotl"}),
    ("gita", {"01-phong": "mistake:gouraud", "02-toon": "mistake:steps-round",
              "11-shadow-mapping": "reference"}),
    ("hugo", {"01-phong": "reference", "02-toon": "mistake:steps-round", "11-shadow-mapping": "mistake:no-bias"}),
    ("ines", {"01-phong": "alt:reflect-builtin", "02-toon": "mistake:steps-round",
              "11-shadow-mapping": "mistake:no-bias"}),
    ("jules", {"01-phong": "broken:compile-error", "02-toon": "reference", "11-shadow-mapping": "mistake:no-bias"}),
    ("kim", {"01-phong": "loop", "02-toon": "alt:steps-if-chain", "11-shadow-mapping": "reference"}),
    ("lea", {"01-phong": "reference", "02-toon": "reference", "11-shadow-mapping": "mistake:pcf-single-tap"}),
    ("max", {"01-phong": "reference", "02-toon": "empty", "11-shadow-mapping": "reference"}),
    # nina copies quinn's Blinn-Phong solution: a copy of one of two solutions that only a template
    # joins must not pull the other into the copy's cluster.
    ("nina", {"01-phong": "copy:quinn", "02-toon": "mistake:steps-round",
              "11-shadow-mapping": "mistake:pcf-single-tap"}),
    ("omar", {"01-phong": "alt:light-kind-branch", "02-toon": "copy:chloe", "11-shadow-mapping": "mistake:no-bias"}),
    ("paula", {"01-phong": "reference", "02-toon": "reference", "11-shadow-mapping": "copy:dmitri"}),
    ("quinn", {"01-phong": "blinn:a", "02-toon": "alt:ramp-sampler2d", "11-shadow-mapping": "reference"}),
    ("rosa", {"01-phong": "blinn:b", "02-toon": "alt:ramp-eye-space",
              "11-shadow-mapping": "alt:pcf-unrolled-offsets"}),
    ("sam", {"01-phong": "starter", "02-toon": "starter", "11-shadow-mapping": "starter"}),
    ("tara", {"01-phong": "starter", "02-toon": "starter", "11-shadow-mapping": "starter"}),
    ("ugo", {"01-phong": "reference", "02-toon": "alt:ramp-texel-fetch", "11-shadow-mapping": "mistake:pcf-single-tap"}),
    ("vera", {"01-phong": "alt:view-space-lighting", "02-toon": "reference", "11-shadow-mapping": "reference"}),
    ("wim", {"01-phong": "reference", "02-toon": "alt:steps-if-chain", "11-shadow-mapping": "alt:bias-constant"}),
    ("xena", {"01-phong": "alt:light-kind-branch", "02-toon": "reference",
              "11-shadow-mapping": "alt:texelfetch-basic"}),
    ("yusuf", {"01-phong": "reference", "02-toon": "alt:ramp-sampler2d", "11-shadow-mapping": "reference"}),
    ("zoe", {"01-phong": "alt:reflect-builtin", "02-toon": "reference", "11-shadow-mapping": "alt:bias-constant"}),
    ("amir", {"01-phong": "reference", "02-toon": "reference", "11-shadow-mapping": "alt:pcf-textureproj"}),
    ("bea", {"01-phong": "alt:view-space-lighting", "02-toon": "alt:ramp-texel-fetch",
             "11-shadow-mapping": "reference"}),
    ("carl", {"01-phong": "reference", "02-toon": "alt:ramp-eye-space", "11-shadow-mapping": "reference"}),
    ("dana", {"01-phong": "alt:light-kind-branch", "02-toon": "reference", "11-shadow-mapping": "reference"}),
    # Handed in as a zip holding a wrapper folder, under an accented name (an LMS export).
    ("Zoë Ångström", {"01-phong": "reference", "02-toon": "alt:ramp-sampler2d",
                       "11-shadow-mapping": "alt:pcf-textureproj"}),
]
ZIPPED = {"Zoë Ångström": "Assignment 1"}  # student -> the wrapper folder inside the zip
CASE_RENAMED = {"lea": ("01-phong", "phong.frag", "Phong.frag")}  # Phong.frag for phong.frag
# The starter saved again by an editor on Windows: CRLF line endings, a trailing space here and there.
RESAVED = {"tara"}


def expected(lab, source):
    """(status, goals failed) as planted."""
    kind, _, name = source.partition(":")
    if kind == "starter":
        return "not_attempted", []
    if kind == "empty":
        return "missing", []
    if kind == "loop":
        return "timeout", []
    if kind == "blinn":
        return "failed", ["phong_lobe"]
    if kind in ("mistake", "broken"):
        case = corpus_case(lab, name)
        return case.get("status", "failed"), case.get("fails", [])
    return "passed", []


def main():
    out = sys.argv[1]
    subs = os.path.join(out, "submissions")
    shutil.rmtree(subs, ignore_errors=True)
    os.makedirs(subs)
    roster = dict(ROSTER)
    documents = {}  # (student, lab) -> {file: (text, origin)}
    truth = {"labs": LABS, "students": {}, "copies": []}

    def document(student, lab):
        key = (student, lab)
        if key not in documents:
            source = roster[student][lab]
            if source.startswith("copy:"):
                original = source.split(":", 1)[1]
                documents[key] = {f: (disguise(t), o) for f, (t, o) in document(original, lab).items()}
                truth["copies"].append({"lab": lab, "students": sorted([student, original])})
            elif source == "empty":
                documents[key] = {}
            else:
                documents[key] = lab_files(lab, source)
        return documents[key]

    for student, labs in ROSTER:
        entry = {}
        wrapper = ZIPPED.get(student, "")
        tree = {}
        for lab, source in labs.items():
            files = document(student, lab)
            original = roster[source.split(":", 1)[1]][lab] if source.startswith("copy:") else source
            status, fails = expected(lab, original)
            entry[lab] = {"source": source, "status": status, "fails": fails,
                          "origins": {f: o for f, (t, o) in files.items()}}
            for f, (text, _) in files.items():
                name = f
                if CASE_RENAMED.get(student, (None,))[:2] == (lab, f):
                    name = CASE_RENAMED[student][2]
                    entry[lab]["case_renamed"] = {"expects": f, "found": name}
                if student in RESAVED:
                    text = text.replace(";\n", "; \n").replace("\n", "\r\n")
                tree[os.path.join(wrapper, lab, name)] = text
            if not files:
                tree[os.path.join(wrapper, lab) + "/"] = None  # an empty folder
        truth["students"][student] = entry
        if wrapper:
            with zipfile.ZipFile(os.path.join(subs, student + ".zip"), "w", zipfile.ZIP_DEFLATED) as z:
                for rel, text in sorted(tree.items()):
                    z.writestr(rel, "" if text is None else text)
        else:
            for rel, text in tree.items():
                path = os.path.join(subs, student, rel)
                if text is None:
                    os.makedirs(path, exist_ok=True)
                    continue
                os.makedirs(os.path.dirname(path), exist_ok=True)
                with open(path, "w", encoding="utf-8", newline="") as f:
                    f.write(text)
    truth["copies"].sort(key=lambda c: (c["lab"], c["students"]))
    with open(os.path.join(out, "truth.json"), "w", encoding="utf-8") as f:
        json.dump(truth, f, indent=2, ensure_ascii=False)
        f.write("\n")
    print("planted class: %d submissions in %s" % (len(ROSTER), subs))


if __name__ == "__main__":
    main()
