"""`shaderlab similarity` on built classes: the time for a synthetic class (500 students x 11 labs by
default) and the precision on a corpus of copies and independent solutions.
  /usr/bin/python3 bench/similarity_class.py build/framework/shaderlab [--students 500] [--seed 1]
      [--keep DIR] [--skip-time] [--skip-precision] [--args "--kgram 10 --window 6"]

The synthetic class: each student's lab is one of the lab's solutions in the course (the reference,
or a corpus case, alternative or mistake, laid over the reference), disguised as a student who
copies would (the names they declared renamed, functions in another order, comments and layout
their own) and with a few statements of their own added, so that no two documents are alike.
Timing figures are wall-clock times of the whole command (reading, fingerprinting, writing the
report), printed, never asserted.

The precision corpus: per lab, the reference and every corpus alternative (its own files, the
starter for the rest) are independent solutions; each gets a disguised copy, and an edited copy
(disguised, and two statements added and one removed). It counts the copies flagged and the
pairs of independent solutions flagged. The alternatives that are the reference with a line or a
function changed (framework/similarity/tests/similarity_corpus_test.cpp, kEditsOfTheReference) are
counted apart: flagging them is right."""
import argparse
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE = os.path.normpath(os.path.join(HERE, ".."))
LABS = os.path.join(SOURCE, "labs")
EDITS_OF_THE_REFERENCE = {
    "04-render-to-texture/alt-fragcoord-pattern",
    "09-procedural-antialiasing/gradient-length",
    "09-procedural-antialiasing/triangle-wave",
    "10-particles/texture-at-texel-centres",
    "11-shadow-mapping/light-space-in-vertex-shader",
}
DECLARED = re.compile(r"\b(?:float|int|uint|bool|[biud]?vec[234]|d?mat[234](?:x[234])?|void)\s+([A-Za-z_]\w*)")
COMMENT = re.compile(r"//[^\n]*|/\*.*?\*/", re.S)


def lab_ids():
    return sorted(d for d in os.listdir(LABS) if os.path.isfile(os.path.join(LABS, d, "lab.json")))


def student_files(lab):
    with open(os.path.join(LABS, lab, "lab.json")) as f:
        return json.load(f)["student_files"]


def cases(lab, kinds):
    path = os.path.join(SOURCE, "tests", "corpus", lab, "cases.json")
    with open(path) as f:
        return [c["name"] for c in json.load(f)["cases"] if c["kind"] in kinds and "delete" not in c]


def read(path):
    with open(path, encoding="utf-8", errors="replace") as f:
        return f.read()


def solution(lab, layers):
    """{file: text} of a lab, each student file from the first of the folders `layers` that has it."""
    out = {}
    for name in student_files(lab):
        for d in layers:
            if os.path.isfile(os.path.join(d, name)):
                out[name] = read(os.path.join(d, name))
                break
    return out


def starter_names(lab):
    names = set()
    for name in student_files(lab):
        path = os.path.join(LABS, lab, name)
        if os.path.isfile(path):
            names.update(re.findall(r"[A-Za-z_]\w*", read(path)))
    return names


def disguise(text, rng, keep, own_statements=0, drop_statements=0):
    """What a student who copies does: the names they declared renamed (not the starter's: the
    program would stop working), the functions in a shuffled order, the comments replaced, a
    layout of their own; then `own_statements` dead statements added inside functions and
    `drop_statements` statements removed."""
    text = COMMENT.sub("", text)
    names = {n for n in DECLARED.findall(text) if n not in keep and n != "main"}
    style = rng.choice(["my_{}", "{}Value", "t_{}_", "x{}"])
    for i, n in enumerate(sorted(names)):
        text = re.sub(r"\b%s\b" % re.escape(n), style.format(i if style == "x{}" else n[::-1]), text)
    pieces, cur, depth = [], [], 0
    for line in text.split("\n"):
        cur.append(line)
        depth += line.count("{") - line.count("}")
        if depth == 0 and "}" in line:
            pieces.append(cur)
            cur = []
    head = cur if not pieces else []
    functions = pieces
    rng.shuffle(functions)
    lines = [l for f in functions for l in f + ["// part"]] + (cur if pieces else head)
    statements = [i for i, l in enumerate(lines) if l.strip().endswith(";") and l.startswith((" ", "\t"))]
    for _ in range(min(drop_statements, len(statements))):
        lines[rng.choice(statements)] = ""
    for k in range(own_statements):
        if statements:
            at = rng.choice(statements)
            lines[at] = lines[at] + " float own%d_%d = %.3f;" % (k, rng.randrange(1000), rng.random())
    indent = " " * rng.choice([2, 3, 4, 8])
    out = []
    for l in lines:
        s = l.strip()
        if s or rng.random() < 0.3:
            out.append(indent * (1 if l.startswith((" ", "\t")) else 0) + s)
    return "/* lab work */\n" + "\n".join(out) + "\n"


def write_lab(root, student, lab, files):
    for name, text in files.items():
        path = os.path.join(root, student, lab, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(text)


EXTRA_ARGS = []  # --args: passed to every run


def run(binary, subs, out, extra=()):
    t0 = time.monotonic()
    p = subprocess.run([binary, "similarity", subs, "--out", out, "--labs", LABS, *EXTRA_ARGS, *extra],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    seconds = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit("similarity failed (%d):\n%s" % (p.returncode, p.stdout))
    with open(os.path.join(out, "pairs.json")) as f:
        return seconds, json.load(f), p.stdout


def synthetic_class(binary, work, students, rng):
    subs = os.path.join(work, "class")
    t0 = time.monotonic()
    for lab in lab_ids():
        reference = os.path.join(SOURCE, "reference_solutions", lab)
        sources = [solution(lab, [reference])]
        for name in cases(lab, ("alternative", "mistake")):
            sources.append(solution(lab, [os.path.join(SOURCE, "tests", "corpus", lab, name), reference]))
        keep = starter_names(lab)
        for s in range(students):
            src = rng.choice(sources)
            files = {n: disguise(t, rng, keep, own_statements=rng.randint(1, 4)) for n, t in src.items()}
            write_lab(subs, "student-%03d" % s, lab, files)
    print("synthetic class: %d students x %d labs written in %.1f s" % (students, len(lab_ids()),
                                                                        time.monotonic() - t0))
    for jobs in ("1", "2"):
        seconds, report, _ = run(binary, subs, os.path.join(work, "class-report-j" + jobs), ["-j", jobs])
        documents = sum(l["documents"] for l in report["labs"])
        flagged = sum(l["pairs_flagged"] for l in report["labs"])
        print("shaderlab similarity -j %s: %d documents, %d flagged pairs, %.2f s wall clock" %
              (jobs, documents, flagged, seconds))


def precision_corpus(binary, work, rng):
    subs = os.path.join(work, "corpus")
    independent = {}  # lab -> [student]
    copies = []  # (lab, original, copy, kind)
    for lab in lab_ids():
        reference = os.path.join(SOURCE, "reference_solutions", lab)
        starter = os.path.join(LABS, lab)
        keep = starter_names(lab)
        originals = {"reference": solution(lab, [reference])}
        for name in cases(lab, ("alternative",)):
            originals["alt-" + name] = solution(lab, [os.path.join(SOURCE, "tests", "corpus", lab, name), starter])
        independent[lab] = sorted(originals)
        for student, files in originals.items():
            write_lab(subs, student, lab, files)
            for kind, own, drop in (("disguised", 0, 0), ("edited", 2, 1)):
                copy = "%s-copy-of-%s" % (kind, student)
                write_lab(subs, copy, lab, {n: disguise(t, rng, keep, own, drop) for n, t in files.items()})
                copies.append((lab, student, copy, kind))
    seconds, report, _ = run(binary, subs, os.path.join(work, "corpus-report"))
    flagged = {(p["lab"], frozenset((p["a"]["student"], p["b"]["student"]))): p for p in report["pairs"]}

    def pair(lab, x, y):
        return flagged.get((lab, frozenset((x, y))))

    for kind in ("disguised", "edited"):
        mine = [c for c in copies if c[3] == kind]
        hits = [c for c in mine if (pair(c[0], c[1], c[2]) or {}).get("flagged")]
        lowest = min((pair(*c[:3])["score"] for c in hits), default=0)
        print("%s copies flagged: %d of %d (lowest flagged score %.2f)" % (kind, len(hits), len(mine), lowest))
        for c in mine:
            if c not in hits:
                p = pair(*c[:3])
                print("  not flagged: %s %s (%s)" % (c[0], c[1], "score %.2f, %d shared" % (p["score"], p["shared"])
                                                      if p else "too little of its own to list"))
    indep_pairs, indep_flagged, edits, edits_flagged, highest = 0, [], 0, 0, (0, "")
    for lab, students in independent.items():
        for i, x in enumerate(students):
            for y in students[i + 1:]:
                p = pair(lab, x, y)
                is_edit = any("%s/%s" % (lab, s[4:]) in EDITS_OF_THE_REFERENCE for s in (x, y) if s != "reference")
                if is_edit:
                    edits += 1
                    edits_flagged += bool(p and p["flagged"])
                    continue
                indep_pairs += 1
                if p and p["score"] > highest[0]:
                    highest = (p["score"], "%s: %s and %s" % (lab, x, y))
                if p and p["flagged"]:
                    indep_flagged.append("%s: %s and %s (%.2f)" % (lab, x, y, p["score"]))
    print("independent pairs flagged: %d of %d (highest score %.2f, %s)%s" %
          (len(indep_flagged), indep_pairs, highest[0], highest[1], "".join("\n  " + s for s in indep_flagged)))
    print("pairs involving an edit of the reference: %d of %d flagged" % (edits_flagged, edits))
    print("(corpus run: %.2f s wall clock)" % seconds)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("binary")
    ap.add_argument("--students", type=int, default=500)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--keep", help="build the classes in DIR and keep them")
    ap.add_argument("--skip-time", action="store_true")
    ap.add_argument("--skip-precision", action="store_true")
    ap.add_argument("--args", default="", help="more options for `shaderlab similarity`, e.g. \"--kgram 10\"")
    args = ap.parse_args()
    EXTRA_ARGS.extend(args.args.split())
    work = args.keep or tempfile.mkdtemp(prefix="shaderlab-similarity-bench-")
    os.makedirs(work, exist_ok=True)
    rng = random.Random(args.seed)
    try:
        if not args.skip_precision:
            precision_corpus(os.path.abspath(args.binary), work, rng)
        if not args.skip_time:
            synthetic_class(os.path.abspath(args.binary), work, args.students, rng)
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
