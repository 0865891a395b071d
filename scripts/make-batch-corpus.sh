#!/usr/bin/env bash
# Generates a folder of submissions to try `shaderlab batch` on, as a course would receive them:
# folders and LMS-style zips (nested top folders, names with spaces and accents), a mix of
# correct, wrong and hostile work. Used to measure throughput (docs/instructors.md).
#
# Usage: scripts/make-batch-corpus.sh OUT_DIR [COUNT=100] [LAB...]   (default labs: all)
#
# Of COUNT submissions, about:
#   50% correct: exact copies of reference_solutions (they grade once, then are reused);
#   10% correct, each with its own comment added (every one graded on its own);
#   20% wrong: the untouched starter code (identical across students: "not_attempted"), or a
#       wrong colour;
#   20% hostile: an endless loop, binary garbage, a symlink to /etc/passwd, a zip-slip, a zip
#       bomb, an empty zip, a file that is not a zip.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="${1:?usage: make-batch-corpus.sh OUT_DIR [COUNT] [LAB...]}"
count="${2:-100}"
shift $(($# >= 2 ? 2 : $#))
mkdir -p "$out"
python3 - "$root" "$out" "$count" "$@" <<'PY'
import json, os, re, sys, zipfile

root, out, count = sys.argv[1], sys.argv[2], int(sys.argv[3])
labs = sys.argv[4:] or sorted(d for d in os.listdir(os.path.join(root, "labs"))
                               if os.path.isfile(os.path.join(root, "labs", d, "lab.json")))
ref = os.path.join(root, "reference_solutions")

def student_files(lab):
    with open(os.path.join(root, "labs", lab, "lab.json")) as f:
        return json.load(f)["student_files"]

def tree(kind, n):
    """{relative path: bytes} of one submission."""
    t = {}
    for lab in labs:
        files = student_files(lab) if kind == "starter" else sorted(os.listdir(os.path.join(ref, lab)))
        for f in files:
            folder = os.path.join(root, "labs", lab) if kind == "starter" else os.path.join(ref, lab)
            data = open(os.path.join(folder, f), "rb").read()
            out_var = re.search(rb"out\s+vec4\s+(\w+)\s*;", data)
            if kind == "unique":
                data += b"\n// submitted by student %d\n" % n
            elif kind == "wrong" and f.endswith(".frag") and out_var:
                end = data.rindex(b"}")
                data = data[:end] + b"    %s.rgb *= 0.5;\n" % out_var.group(1) + data[end:]
            elif kind == "loop" and f.endswith(".frag") and b"void main()" in data:
                data = data.replace(b"void main()", b"void main_original()", 1) + (
                    b"\nuniform float u_never;\nvoid main() { float x = 0.0; while (u_never < 1.0) { x += 1.0; } "
                    b"main_original(); }\n")
            elif kind == "garbage":
                data = bytes((i * 7919 + n) % 256 for i in range(4096))
            t[os.path.join(lab, f)] = data
    return t

def write_folder(path, t):
    for rel, data in t.items():
        p = os.path.join(path, rel)
        os.makedirs(os.path.dirname(p), exist_ok=True)
        with open(p, "wb") as f:
            f.write(data)

def write_zip(path, t, prefix=""):
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as z:
        for rel, data in t.items():
            z.writestr(prefix + rel, data)

names = ["Zoë Ångström", "José María", "Li Wei", "anne-marie o'neil", "Ølaf", "Ana Luísa"]
for n in range(count):
    student = "%s %03d" % (names[n % len(names)], n) if n % 5 == 0 else "student%03d" % n
    r = n % 20
    base = os.path.join(out, student)
    if r < 10:
        t = tree("correct", n)
    elif r < 12:
        t = tree("unique", n)
    elif r < 14:
        t = tree("starter", n)
    elif r < 16:
        t = tree("wrong", n)
    elif r == 16:
        t = tree("loop", n)
    elif r == 17:
        t = tree("garbage", n)
    elif r == 18:
        # Hostile archives, in turn.
        kind = (n // 20) % 4
        with zipfile.ZipFile(base + ".zip", "w", zipfile.ZIP_DEFLATED) as z:
            if kind == 0:
                z.writestr("../../escaped.txt", b"zip-slip")
            elif kind == 1:
                z.writestr("bomb.bin", b"\0" * (64 << 20))
            elif kind == 3:
                info = zipfile.ZipInfo(labs[0] + "/" + student_files(labs[0])[0])
                info.external_attr = (0o120777 << 16)
                z.writestr(info, "/etc/passwd")
        if kind == 2:
            open(base + ".zip", "wb").close()
        continue
    else:
        with open(base + ".zip", "wb") as f:
            f.write(b"PK\x03\x04 this is not really a zip " * 20)
        continue
    # Half of the well-formed ones arrive as LMS zips: a top folder per student, then the work.
    if n % 2 == 0:
        write_zip(base + ".zip", t, prefix="%s/submission/" % student)
    else:
        write_folder(base, t)
    if r == 17 and n % 2 == 1:
        os.symlink("/etc/passwd", os.path.join(base, "stolen.txt"))
print("%d submissions in %s (labs: %s)" % (count, out, " ".join(labs)))
PY
