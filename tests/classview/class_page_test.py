#!/usr/bin/python3
"""The class page (`shaderlab class`) as an instructor opens it: a real small batch (two labs, six
submissions made from the reference solutions and the corpus's mistakes, one of them a file that is
not a zip), the page written from its results, then opened from file:// in headless Chromium over the
DevTools protocol (tests/serve/cdp.py).

What is checked: the goal shares, the mistake counts, the statuses and the "re-teach first" and
"needs help" lists shown are those of class.json; class.json's counts are those the submissions were
made to have (gouraud recognised in two students, one timeout, one refused archive); every SVG plot is
drawn (non-empty boxes, bars of non-zero size); every picture loaded (naturalWidth > 0) from the
page's own folder, and nothing was fetched from anywhere else. A screenshot of the whole page is
saved as class_page.png in the build's tests folder.

Run: /usr/bin/python3 tests/classview/class_page_test.py --shaderlab build/framework/shaderlab --source .
Exits 77 (CTest's skip) where chromium or python3-websocket is missing."""
import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "serve"))

SKIP = 77
ARGS = None
LABS = ["01-phong", "02-toon"]

# Each student: lab -> what its folder is made of (None: not handed in).
#   "ref": the reference solution; "corpus:<case>": the reference with the case's files over it.
CLASS = {
    "alice": {"01-phong": "ref", "02-toon": "ref"},
    "bob": {"01-phong": "corpus:gouraud", "02-toon": "ref"},
    "carol": {"01-phong": "corpus:normals-model-matrix", "02-toon": "corpus:ramp-lambert-coordinate"},
    "dave": {"01-phong": "corpus:endless-loop", "02-toon": "ref"},
    "erin": {"01-phong": "corpus:gouraud", "02-toon": None},
}


def make_submissions(source, into):
    for student, labs in CLASS.items():
        for lab, what in labs.items():
            if what is None:
                continue
            folder = os.path.join(into, student, lab)
            shutil.copytree(os.path.join(source, "reference_solutions", lab), folder)
            if what.startswith("corpus:"):
                case = os.path.join(source, "tests", "corpus", lab, what.split(":", 1)[1])
                for name in os.listdir(case):
                    shutil.copy(os.path.join(case, name), os.path.join(folder, name))
    with open(os.path.join(into, "frank.zip"), "wb") as f:
        f.write(b"this is not a zip archive\n")


def run(cmd, timeout):
    t = time.time()
    p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout)
    return p.returncode, p.stdout, time.time() - t


class ClassPage(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        import cdp
        cls.tmp = tempfile.mkdtemp(prefix="shaderlab-class-")
        subs, results, cls.out = (os.path.join(cls.tmp, n) for n in ("submissions", "results", "class"))
        os.makedirs(subs)
        make_submissions(ARGS.source, subs)
        labs = os.path.join(ARGS.source, "labs")
        cmd = [ARGS.shaderlab, "batch", subs, "--out", results, "--labs", labs, "--timeout", "3",
               "--compile-timeout", "20"]
        for lab in LABS:
            cmd += ["--lab", lab]
        code, output, seconds = run(cmd, 300)
        print("batch of %d submissions x %d labs: %.1f s" % (len(CLASS) + 1, len(LABS), seconds))
        if code not in (0, 1):
            raise RuntimeError("shaderlab batch failed (%d):\n%s" % (code, output))
        code, output, seconds = run([ARGS.shaderlab, "class", results, "--out", cls.out, "--labs", labs], 60)
        print("shaderlab class: %.2f s\n%s" % (seconds, output))
        if code != 0:
            raise RuntimeError("shaderlab class failed (%d):\n%s" % (code, output))
        with open(os.path.join(cls.out, "class.json")) as f:
            cls.data = json.load(f)
        cls.browser = cdp.Browser(width=1280, height=900)
        cls.page = cls.browser.new_page("about:blank")
        cls.page.navigate("file://" + os.path.join(cls.out, "index.html"))
        cls.page.wait_for("document.readyState === 'complete' && document.querySelector('footer') !== null", 30,
                          "the page to load")
        cls.page.wait_for("Array.from(document.images).every(i => i.complete)", 30, "the pictures to load")

    @classmethod
    def tearDownClass(cls):
        if getattr(cls, "page", None):
            cls.save_screenshot()
            cls.page.close()
        if getattr(cls, "browser", None):
            cls.browser.close()
        shutil.rmtree(cls.tmp, ignore_errors=True)

    @classmethod
    def save_screenshot(cls):
        import base64
        size = cls.page.eval("[document.documentElement.scrollWidth, document.documentElement.scrollHeight]")
        shot = cls.page.call("Page.captureScreenshot", format="png", captureBeyondViewport=True,
                             clip={"x": 0, "y": 0, "width": size[0], "height": size[1], "scale": 1})
        folder = os.path.join(os.path.dirname(os.path.dirname(ARGS.shaderlab)), "tests")
        if not os.path.isdir(folder):
            folder = tempfile.gettempdir()
        path = os.path.join(folder, "class_page.png")
        with open(path, "wb") as f:
            f.write(base64.b64decode(shot["data"]))
        print("screenshot (%dx%d): %s" % (size[0], size[1], path))

    def lab(self, lab_id):
        return next(l for l in self.data["labs"] if l["id"] == lab_id)

    def test_counts_are_those_the_class_was_made_with(self):
        self.assertEqual(self.data["submissions"], len(CLASS) + 1)
        self.assertEqual(self.data["statuses"], {"graded": len(CLASS), "bad_archive": 1})
        phong = self.lab("01-phong")
        mistakes = {m["mistake"]: m["students"] for m in phong["mistakes"]}
        self.assertEqual(mistakes.get("gouraud"), 2, phong["mistakes"])
        self.assertEqual(mistakes.get("normals-model-matrix"), 1, phong["mistakes"])
        self.assertEqual(phong["statuses"].get("timeout"), 1)
        self.assertEqual(phong["handed_in"], 5)
        per_fragment = next(g for g in phong["goals"] if g["id"] == "per_fragment")
        # alice and carol meet it; bob and erin (Gouraud) and dave (timeout) do not.
        self.assertEqual((per_fragment["met"], per_fragment["of"]), (2, 5))
        self.assertEqual(per_fragment["mistakes"][0], {"mistake": "gouraud", "students": 2})
        toon = self.lab("02-toon")
        self.assertEqual(toon["handed_in"], 4)
        self.assertIn("ramp-lambert-coordinate", [m["mistake"] for m in toon["mistakes"]])
        # Re-teach first: per_fragment (2 of 5) leads, with Gouraud behind it.
        first = self.data["reteach_first"][0]
        self.assertEqual((first["lab"], first["goal"], first["mistake"]), ("01-phong", "per_fragment", "gouraud"))
        # frank's archive was refused, dave timed out, erin did not hand 02-toon in: they need help.
        # Bob lost a goal, but 8 of 10 points in one lab and 10 in the other are no call for help.
        needy = [n["student"] for n in self.data["needs_help"]]
        self.assertEqual(needy[0], "frank")
        for student in ("dave", "erin"):
            self.assertIn(student, needy)
        for student in ("alice", "bob"):
            self.assertNotIn(student, needy)

    def test_goal_shares_shown_are_class_json(self):
        for lab in self.data["labs"]:
            shown = self.page.eval(
                "Array.from(document.querySelectorAll('section.lab[data-lab=\"%s\"] g.goal')).map(g => "
                "[g.dataset.goal, +g.dataset.met, +g.dataset.of, g.querySelector('text.value').textContent, "
                "g.querySelector('rect.bar').getBBox().width])" % lab["id"])
            self.assertEqual([s[:3] for s in shown], [[g["id"], g["met"], g["of"]] for g in lab["goals"]])
            for (goal_id, met, of, text, width), goal in zip(shown, lab["goals"]):
                self.assertEqual(text, "%d / %d · %d %%" % (met, of, round(100.0 * met / of)))
                self.assertEqual(width > 0, met > 0, goal_id)

    def test_mistake_counts_shown_are_class_json(self):
        for lab in self.data["labs"]:
            shown = self.page.eval(
                "Array.from(document.querySelectorAll('section.lab[data-lab=\"%s\"] .mistake')).map(m => "
                "[m.dataset.mistake, +m.dataset.students, m.querySelector('.count').textContent, "
                "m.querySelectorAll('img').length])" % lab["id"])
            self.assertEqual([s[:2] for s in shown], [[m["mistake"], m["students"]] for m in lab["mistakes"]])
            for name, students, text, pictures in shown:
                self.assertEqual(text, "%d student%s" % (students, "" if students == 1 else "s"))
                self.assertEqual(pictures, 2, name)  # expected and the mistake

    def test_statuses_and_lists_shown_are_class_json(self):
        shown = self.page.eval("Object.fromEntries(Array.from(document.querySelectorAll("
                               "'#overview .legend li')).map(l => [l.dataset.status, +l.dataset.count]))")
        self.assertEqual(shown, self.data["statuses"])
        for lab in self.data["labs"]:
            shown = self.page.eval(
                "Object.fromEntries(Array.from(document.querySelectorAll('section.lab[data-lab=\"%s\"] "
                ".legend li')).map(l => [l.dataset.status, +l.dataset.count]))" % lab["id"])
            self.assertEqual(shown, lab["statuses"])
        reteach = self.page.eval("Array.from(document.querySelectorAll('#reteach li')).map(l => "
                                 "[l.dataset.lab, l.dataset.goal, +l.dataset.met, +l.dataset.of])")
        self.assertEqual(reteach, [[t["lab"], t["goal"], t["met"], t["of"]] for t in self.data["reteach_first"]])
        self.assertIn("gouraud", self.page.eval("document.querySelector('#reteach li').textContent"))
        help_rows = self.page.eval("Array.from(document.querySelectorAll('#help tbody tr')).map(r => "
                                   "r.dataset.student)")
        self.assertEqual(help_rows, [n["student"] for n in self.data["needs_help"]][:25])

    def test_plots_are_drawn(self):
        plots = self.page.eval(
            "Array.from(document.querySelectorAll('svg.plot')).map(s => { const b = s.getBoundingClientRect(); "
            "return [s.getAttribute('class'), b.width, b.height, "
            "Array.from(s.querySelectorAll('rect')).filter(r => r.getBBox().width > 0 && "
            "r.getBBox().height > 0).length]; })")
        kinds = [p[0] for p in plots]
        # Per lab: goals, points, statuses; for the class: submissions and totals.
        self.assertEqual(kinds.count("plot goals"), len(LABS))
        self.assertEqual(kinds.count("plot histogram"), len(LABS) + 1)
        self.assertEqual(kinds.count("plot statuses"), len(LABS) + 1)
        for kind, width, height, bars in plots:
            self.assertGreater(width, 100, kind)
            self.assertGreater(height, 20, kind)
            self.assertGreater(bars, 0, kind)
        counts = self.page.eval("Array.from(document.querySelectorAll('section.lab[data-lab=\"01-phong\"] "
                                "g.bin')).map(b => +b.dataset.count)")
        self.assertEqual(counts, [b["students"] for b in self.lab("01-phong")["points"]["bins"]])

    def test_pictures_load_from_the_page_folder_only(self):
        images = self.page.eval("Array.from(document.images).map(i => [i.getAttribute('src'), i.naturalWidth])")
        self.assertGreaterEqual(len(images), 6)  # 3 mistakes x 2, and the re-teach list's
        for src, width in images:
            self.assertTrue(src.startswith("pictures/"), src)
            self.assertGreater(width, 0, src)
            self.assertTrue(os.path.isfile(os.path.join(self.out, src)), src)
        fetched = self.page.eval("performance.getEntriesByType('resource').map(e => e.name)")
        for url in fetched:
            self.assertTrue(url.startswith("file://" + self.out + "/"), url)
        self.assertEqual(self.page.eval("document.scripts.length"), 0)


def main():
    global ARGS
    ap = argparse.ArgumentParser()
    ap.add_argument("--shaderlab", required=True, help="the shaderlab program")
    ap.add_argument("--source", required=True, help="the source tree (labs/, reference_solutions/, tests/corpus/)")
    ap.add_argument("tests", nargs="*", help="unittest names (default: all)")
    ARGS = ap.parse_args()
    ARGS.shaderlab = os.path.abspath(ARGS.shaderlab)
    ARGS.source = os.path.abspath(ARGS.source)
    try:
        import websocket  # noqa: F401
    except ImportError:
        print("skipped: the python3 websocket module (python3-websocket) is not installed")
        return SKIP
    import cdp
    if not cdp.find_chromium():
        print("skipped: no chromium to drive (install chromium)")
        return SKIP
    prog = unittest.main(argv=[sys.argv[0]] + list(ARGS.tests), verbosity=2, exit=False)
    return 0 if prog.result.wasSuccessful() else 1


if __name__ == "__main__":
    sys.exit(main())
