#!/usr/bin/python3
"""The workbench a student lives in (issue 34): headless Chromium over the DevTools protocol
(cdp.py) on `shaderlab serve` (serve_fixture.py), checking what the page says and where it points.

What is checked: warnings and notes reach the page with their fix; parts of the page that belong
to an older save are greyed and say so, with a neutral badge while a grade runs; no sideways
scrolling at 1024 and 390 px with every panel reachable; the split's sides labelled, the heat
map's legend, the worst region and the first NaN marked on the picture; failing checks of the
grade that show their scene and pass; errors with the lines around them, the endless loop's line,
a matrix product's types; the keys of `shaderlab view`; accessible names and roles, verdicts
announced in a live region; the light theme; the terminal, the favicon, a save without a change.

Run: /usr/bin/python3 tests/serve/serve_workbench_test.py --shaderlab build/framework/shaderlab --source .
Exits 77 (CTest's skip) where chromium or python3-websocket is missing."""
import json
import os
import re
import subprocess
import sys
import time
import unittest

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import serve_fixture  # noqa: E402
from serve_fixture import Served  # noqa: E402

ARGS = None  # set in main()
GOOD_LINE = "o_color = vec4(color, 1.0);"
JS_PAGE_READY = "!!(window.workbench && document.getElementById('picture'))"


def settled(st):
    """The newest picture is shown and judged and the newest files graded; nothing runs."""
    p = st.get("picture")
    g = st.get("grade")
    return bool(p) and p.get("judged") and not st.get("busy") and bool(g) and bool(g.get("lab")) and \
        not g.get("pending") and g.get("generation") == st.get("generation")


def line_of(text, needle):
    for i, line in enumerate(text.split("\n")):
        if needle in line:
            return i + 1
    raise AssertionError("no line with %r" % needle)


class WorkbenchTest(unittest.TestCase):
    browser = None

    @classmethod
    def setUpClass(cls):
        import cdp
        cls.browser = cdp.Browser()

    @classmethod
    def tearDownClass(cls):
        if cls.browser:
            cls.browser.close()

    def setUp(self):
        self.pages = []

    def tearDown(self):
        for p in self.pages:
            p.close()

    def open(self, s, width=1400, height=1000, mobile=False):
        page = self.browser.new_page("about:blank")
        self.pages.append(page)
        page.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1,
                  mobile=mobile)
        page.navigate(s.url)
        page.wait_for(JS_PAGE_READY, 20, "the page's script")
        page.wait_for("window.workbench.shownSeq > 0", 60, "a first picture on the page")
        return page

    def wait_settled(self, s, page, timeout=90):
        st = s.wait_state(settled, timeout, "the picture judged and the lab graded")
        page.wait_for("window.workbench.stateVersion >= %d && window.workbench.shownSeq === %d" %
                      (st["version"], st["picture"]["seq"]), 30, "the page on state %d" % st["version"])
        return st

    def wait_error(self, s, after):
        """The state once a save after generation `after` failed."""
        return s.wait_state(lambda x: x["generation"] > after and x["error"] and
                            x["error"]["generation"] == x["generation"], 60, "a failed render after save %d" % after)

    def text(self, page, element_id):
        return page.eval("document.getElementById('%s').innerText" % element_id)

    def visible(self, page, element_id):
        return page.eval("(() => { const e = document.getElementById('%s'); if (!e) return false;"
                         " const r = e.getBoundingClientRect(); return r.width > 0 && r.height > 0 &&"
                         " getComputedStyle(e).visibility !== 'hidden'; })()" % element_id)

    # 1. Warnings and notes reach the page, each with its fix.
    def test_01_warning_and_its_fix_on_the_page(self):
        with Served(ARGS, "01-phong") as s:
            page = self.open(s)
            self.wait_settled(s, page)
            self.assertFalse(self.visible(page, "warnings"), "the reference solution has no warnings")
            frag = s.read("phong.frag")
            frag = frag.replace("out vec4 o_color;", "in vec3 v_extra;\nout vec4 o_color;")
            frag = frag.replace(GOOD_LINE, "o_color = vec4(color + v_extra, 1.0);")
            s.save("phong.frag", frag)
            st = s.wait_state(lambda x: settled(x) and x["picture"]["generation"] == x["generation"] and
                              x["picture"]["diagnostics"], 60, "the picture with its warning")
            page.wait_for("window.workbench.shownSeq === %d" % st["picture"]["seq"], 30)
            d = next(d for d in st["picture"]["diagnostics"] if "v_extra" in d["message"])
            self.assertEqual(d["severity"], "warning")
            self.assertEqual(d["line"], line_of(frag, "in vec3 v_extra;"))
            page.wait_for("!document.getElementById('warnings').classList.contains('hidden')", 10, "the warnings")
            shown = self.text(page, "warnings")
            self.assertIn("phong.frag:%d" % d["line"], shown)
            self.assertIn("v_extra", shown)
            self.assertIn("phong.vert has no output of that name", shown)
            self.assertTrue(d["explanation"], d)
            self.assertIn(d["explanation"][:40], shown, "the fix is on the page")
            self.assertIn("%d | in vec3 v_extra;" % d["line"], shown, "the line itself, among its neighbours")
            self.assertIn("%d | " % (d["line"] - 1), shown)
            link = page.eval("document.querySelector('#warnings a.where').href")
            self.assertRegex(link, r"^vscode://file/.*phong\.frag:%d:\d+$" % d["line"])
            # The grade says the same as the page: the lab fails, and the page says why.
            self.assertIn("FAILS", self.text(page, "badge"))

        # The starter: its "declared but never used" notes.
        with Served(ARGS, "01-phong", submission=os.path.join(ARGS.source, "labs", "01-phong")) as s:
            page = self.open(s)
            st = self.wait_settled(s, page)
            notes = [d for d in st["picture"]["diagnostics"] if "never used" in d["message"]]
            self.assertTrue(notes, st["picture"]["diagnostics"])
            page.wait_for("!document.getElementById('warnings').classList.contains('hidden')", 10, "the notes")
            self.assertIn(notes[0]["message"], self.text(page, "warnings"))
            # Not attempted: the lab's goals are listed as what to do, each with the work it asks for.
            self.assertIn("NOT ATTEMPTED", self.text(page, "badge"))
            with open(os.path.join(ARGS.source, "labs", "01-phong", "lab.json")) as f:
                lab_goals = json.load(f)["goals"]
            page.wait_for("document.getElementById('goals').children.length === %d" % len(lab_goals), 10,
                          "the goals to do")
            for i, g in enumerate(lab_goals):
                item = self.text(page, "goal-%d" % (i + 1))
                self.assertIn(g["title"], item)
                for work in g["work"]:
                    self.assertIn(work.replace(":", ": "), item)

    # 2. Older parts greyed and labelled: while a grade runs, and after a failed save.
    def test_02_stale_parts_greyed_and_labelled(self):
        with Served(ARGS, "01-phong") as s:
            page = self.open(s)
            self.wait_settled(s, page)
            self.assertEqual(page.eval("document.getElementById('badge').className"), "badge pass")
            # Sample the page while the next save is rendered and graded: every sample taken while
            # the grade shown is older than the files says so, with a neutral badge.
            page.eval("""window.__samples = []; window.__sampler = setInterval(() => {
                const s = ui.state; if (!s || !s.grade || !s.grade.lab) return;
                window.__samples.push({old: s.grade.pending || s.grade.generation < s.generation,
                  badge: document.getElementById('badge').className,
                  badgeText: document.getElementById('badge').textContent,
                  boxStale: document.getElementById('grade-box').classList.contains('stale'),
                  tag: document.getElementById('grade-state').classList.contains('hidden') ? '' :
                    document.getElementById('grade-state').textContent}); }, 15); true""")
            s.save("phong.frag", s.read("phong.frag").replace(GOOD_LINE, "o_color = vec4(color * 0.5, 1.0);"))
            s.wait_state(lambda x: settled(x) and x["generation"] >= 2, 60, "the new save graded")
            time.sleep(0.3)
            samples = page.eval("clearInterval(window.__sampler); window.__samples")
            during = [x for x in samples if x["old"]]
            self.assertTrue(during, "no sample caught the grade running (%d samples)" % len(samples))
            for x in during:
                self.assertEqual(x["badge"], "badge pending", x)
                self.assertIn("GRADING", x["badgeText"], x)
                self.assertTrue(x["boxStale"], x)
                self.assertIn("grading your latest save", x["tag"], x)
            after = [x for x in samples if not x["old"]]
            self.assertTrue(after and after[-1]["badge"] == "badge fail", samples[-3:])

            # A save that does not compile: the verdict, the picture and its timing are the last
            # good picture's, greyed and labelled; the grade says why there are no goals.
            seq = s.state()["picture"]["seq"]
            s.save("phong.frag", s.read("phong.frag").replace("vec3 n = normalize(v_world_normal);",
                                                              "vec3 n = normalize(v_world_normal)"))
            st = s.wait_state(lambda x: x["error"] and settled(x) and x["grade"]["lab"]["status"] == "compile_error",
                              60, "the failed save graded")
            self.assertEqual(st["picture"]["seq"], seq)
            page.wait_for("window.workbench.stateVersion >= %d" % st["version"], 10)
            page.wait_for("document.getElementById('badge').textContent.startsWith('DOES NOT COMPILE')", 10)
            self.assertTrue(page.eval("document.getElementById('verdict-box').classList.contains('stale')"))
            self.assertIn("before the error", self.text(page, "verdict-stale"))
            self.assertTrue(page.eval("document.getElementById('stage').classList.contains('stale')"))
            self.assertIn("before the error", self.text(page, "picture-stale"))
            info = self.text(page, "picture-info")
            self.assertNotIn("after your save", info)
            self.assertIn("from an earlier save", info)
            self.assertIn("until your shaders build", self.text(page, "grade-message"))
            opacity = float(page.eval("getComputedStyle(document.getElementById('scene-verdict')).opacity"))
            self.assertLess(opacity, 0.6, "the scene's verdict of the old picture is not greyed")

    # 3. No sideways scrolling at 1024 and 390 px; every panel reachable.
    def test_03_layout_at_1024_and_390(self):
        # A lab with one mistake (a reversed light vector): a goal missed and the others judged alone,
        # so every panel has something in it. (The starter is not attempted and lists no goals.)
        with Served(ARGS, "01-phong") as s:
            with open(os.path.join(ARGS.source, "tests", "corpus", "01-phong", "light-vector-reversed",
                                   "phong.frag")) as f:
                s.save("phong.frag", f.read())
            s.wait_state(lambda x: settled(x) and (x.get("grade") or {}).get("lab", {}).get("status") == "failed",
                         90, "the mistake graded")
            for width, mobile in ((1400, False), (1024, False), (390, True)):
                page = self.open(s, width=width, height=900, mobile=mobile)
                self.wait_settled(s, page)
                page.wait_for("document.getElementById('goals').children.length > 0", 10)
                m = page.eval("""(() => {
                    const d = document.documentElement;
                    const boxes = {};
                    for (const id of ['left', 'center', 'right', 'picture', 'verdict-box', 'grade-box', 'goals',
                                      'scene', 'badge', 'mode-split']) {
                      const r = document.getElementById(id).getBoundingClientRect();
                      boxes[id] = {left: r.left, right: r.right, width: r.width, height: r.height};
                    }
                    return {scrollWidth: d.scrollWidth, innerWidth: window.innerWidth,
                            height: d.scrollHeight, boxes};
                  })()""")
                self.assertLessEqual(m["scrollWidth"], m["innerWidth"], "sideways scrolling at %d px: %r" % (width, m))
                for name, b in m["boxes"].items():
                    self.assertGreater(b["width"], 0, "%s is not shown at %d px" % (name, width))
                    self.assertGreaterEqual(b["left"], 0, "%s starts off screen at %d px: %r" % (name, width, b))
                    self.assertLessEqual(b["right"], m["innerWidth"] + 0.5, "%s is cut off at %d px: %r" % (name, width, b))
                if width == 1400:
                    self.assertGreater(m["boxes"]["right"]["left"], m["boxes"]["center"]["right"], "three columns")
                # A goal's reason is its own (the checks where it fails, how it was judged), never the
                # titles of other goals repeated (a goal that waits on others names them by number).
                titles = [g["title"] for g in s.state()["grade"]["lab"]["goals"]]
                whys = page.eval("[...document.querySelectorAll('#goals .why')].map(e => e.textContent)")
                self.assertTrue(whys, "no goal says why it is not met")
                for w in whys:
                    for t in titles:
                        self.assertNotIn(t, w)
                page.close()
                self.pages.remove(page)

    # 4. Pictures that point: split sides, the heat map's legend, the worst region, the first NaN.
    def test_04_split_legend_worst_region_and_first_nan(self):
        blinn = os.path.join(ARGS.source, "tests", "corpus", "01-phong", "blinn-phong")
        with Served(ARGS, "01-phong") as s:
            page = self.open(s, width=1400)
            self.wait_settled(s, page)
            with open(os.path.join(blinn, "phong.frag")) as f:
                s.save("phong.frag", f.read())
            page.eval("(() => { const s = document.getElementById('scene'); s.value = 'torus_grazing';"
                      " s.dispatchEvent(new Event('change')); return true; })()")
            st = s.wait_state(lambda x: settled(x) and x["picture"]["scene"] == "torus_grazing" and
                              x["generation"] >= 2, 90, "torus_grazing judged")
            page.wait_for("window.workbench.shownSeq === %d" % st["picture"]["seq"], 30)
            p = st["picture"]
            img = p["images"][p["final_image"]]
            v = img["verdict"]
            self.assertFalse(v["passed"])
            self.assertIsNotNone(v["worst"])

            page.eval("document.getElementById('mode-split').click(); true")
            page.wait_for("window.workbench.shownKey.includes('/reference/')", 20, "the split drawn")
            self.assertTrue(self.visible(page, "side-student") and self.visible(page, "side-reference"))
            self.assertIn("yours", self.text(page, "side-student"))
            self.assertIn("reference", self.text(page, "side-reference"))
            sides = page.eval("[document.getElementById('side-student').getBoundingClientRect().left,"
                              " document.getElementById('side-reference').getBoundingClientRect().right,"
                              " document.getElementById('picture').getBoundingClientRect().left,"
                              " document.getElementById('picture').getBoundingClientRect().right]")
            self.assertLess(sides[0] - sides[2], 20, sides)
            self.assertLess(sides[3] - sides[1], 20, sides)

            page.eval("document.getElementById('mode-diff').click(); true")
            page.wait_for("window.workbench.shownKey.includes('/diff/')", 20, "the heat map drawn")
            self.assertFalse(self.visible(page, "side-student"), "split labels outside the split")
            self.assertTrue(self.visible(page, "legend"))
            legend = self.text(page, "legend")
            self.assertIn("FLIP error", legend)
            self.assertIn("outline", legend)
            ends = page.eval("(() => { const c = document.getElementById('legend-bar'); const x = c.getContext('2d');"
                             " return [[...x.getImageData(0, 0, 1, 1).data], [...x.getImageData(c.width - 1, 0, 1, 1).data]]; })()")
            stops = st["heatmap"]["stops"]
            for got, want in ((ends[0], stops[0]), (ends[1], stops[-1])):
                self.assertTrue(all(abs(a - b) <= 2 for a, b in zip(got[:3], want)), (got, want))

            # The worst region: a box over the picture where the verdict's window is.
            self.assertTrue(self.visible(page, "mark-worst"))
            box = page.eval("(() => { const m = document.getElementById('mark-worst').getBoundingClientRect();"
                            " const c = document.getElementById('picture').getBoundingClientRect();"
                            " return [(m.left - c.left) / c.width, (m.top - c.top) / c.height,"
                            " (m.right - c.left) / c.width, (m.bottom - c.top) / c.height]; })()")
            t = v["worst"]["tile"]
            want = [t["x0"] / img["width"], t["y0"] / img["height"], (t["x1"] + 1) / img["width"], (t["y1"] + 1) / img["height"]]
            for got, w in zip(box, want):
                self.assertAlmostEqual(got, w, delta=0.02, msg="worst box %r, want %r" % (box, want))
            self.assertIn("x=%d, y=%d" % (v["worst"]["x"], v["worst"]["y"]), self.text(page, "marks"))

            # The first NaN: a shader that writes NaN on the right half.
            frag = s.read("phong.frag")
            marker = "o_color = vec4("
            self.assertIn(marker, frag)
            nan_frag = frag.replace(marker, "color *= gl_FragCoord.x > 128.0 ? sqrt(-1.0 - color.r) : 1.0;\n    " + marker, 1)
            s.save("phong.frag", nan_frag)
            st = s.wait_state(lambda x: settled(x) and x["picture"]["generation"] == x["generation"] and
                              x["picture"]["images"][x["picture"]["final_image"]]["verdict"]["non_finite"],
                              60, "a picture with NaN judged")
            page.wait_for("window.workbench.shownSeq === %d" % st["picture"]["seq"], 30)
            nf = st["picture"]["images"][st["picture"]["final_image"]]["verdict"]["non_finite"]
            self.assertGreaterEqual(nf["x"], 128)
            page.wait_for("!document.getElementById('mark-nan').classList.contains('hidden')", 10, "the NaN mark")
            centre = page.eval("(() => { const m = document.getElementById('mark-nan').getBoundingClientRect();"
                               " const c = document.getElementById('picture').getBoundingClientRect();"
                               " return [((m.left + m.right) / 2 - c.left) / c.width * %d,"
                               " ((m.top + m.bottom) / 2 - c.top) / c.height * %d]; })()" % (img["width"], img["height"]))
            self.assertAlmostEqual(centre[0], nf["x"] + 0.5, delta=1.5)
            self.assertAlmostEqual(centre[1], nf["y"] + 0.5, delta=1.5)
            self.assertIn("x=%d, y=%d" % (nf["x"], nf["y"]), self.text(page, "marks"))

    # 5. A failing check of the grade shows its scene and pass.
    def test_05_failing_checks_select_their_scene_and_pass(self):
        case = os.path.join(ARGS.source, "tests", "corpus", "06-bloom", "blur-offsets-in-pixels")
        with Served(ARGS, "06-bloom") as s:
            page = self.open(s)
            self.wait_settled(s, page)
            for name in os.listdir(case):
                with open(os.path.join(case, name)) as f:
                    s.save(name, f.read())
            st = s.wait_state(lambda x: settled(x) and x["generation"] >= 2 and
                              x["grade"]["lab"]["status"] == "failed", 120, "the mistake graded")
            goal = next(g for g in st["grade"]["lab"]["goals"] if not g["met"] and g["failing"])
            check = next(c for c in goal["failing"] if c.split("/")[0] != st["view"]["scene"])
            scene, pass_name = check.split("/")
            # A goal lists its first checks; "+N more" shows the rest.
            page.wait_for("document.querySelectorAll('#goals .chips button').length > 0", 20, "the checks as links")
            page.eval("(() => { const want = '%s';"
                      " if ([...document.querySelectorAll('#goals .chips button')].some(b => b.textContent === want)) return true;"
                      " for (const b of document.querySelectorAll('#goals .chips button.link')) b.click(); return true; })()" % check)
            page.wait_for("[...document.querySelectorAll('#goals .chips button')].some(b => b.textContent === '%s')" % check,
                          20, "the check %s as a link" % check)
            page.eval("[...document.querySelectorAll('#goals .chips button')].find(b => b.textContent === '%s').click(); true" % check)
            st = s.wait_state(lambda x: x["view"]["scene"] == scene and x["picture"] and x["picture"]["scene"] == scene,
                              60, "scene %s drawn" % scene)
            page.wait_for("(() => { const p = ui.state.picture; if (!p || p.scene !== '%s') return false;"
                          " const i = shownIndex(p); return p.images[i].pass === '%s'; })()" % (scene, pass_name),
                          30, "pass %s of scene %s shown" % (pass_name, scene))
            self.assertIn(pass_name, self.text(page, "picture-label"))
            self.assertEqual(page.eval("document.getElementById('scene').value"), scene)

    # 6. Errors with the lines around them; the endless loop's line; a matrix product's types.
    def test_06_errors_lines_around_loop_line_and_matrix_types(self):
        with Served(ARGS, "01-phong", extra=["--view-timeout", "30", "--timeout", "30"]) as s:
            page = self.open(s)
            self.wait_settled(s, page)
            good = s.read("phong.frag")
            broken = good.replace("vec3 n = normalize(v_world_normal);", "vec3 n = normalize(v_world_normal)")
            s.save("phong.frag", broken)
            st = self.wait_error(s, 1)
            d = st["error"]["diagnostics"][0]
            page.wait_for("!document.getElementById('error').classList.contains('hidden')", 10)
            shown = self.text(page, "error")
            lines = broken.split("\n")
            for n in range(d["line"] - 2, d["line"] + 3):
                self.assertIn("%d | %s" % (n, lines[n - 1]), shown, "line %d around the error" % n)
            self.assertRegex(page.eval("document.querySelector('#error a.where').href"),
                             r"^vscode://file/.*phong\.frag:%d:" % d["line"])
            self.assertRegex(shown, r"(vi|\S+) \+%d \S*phong\.frag" % d["line"])

            # An endless loop: named as such, at its line, with the caret under the loop. It loops in
            # a few pixels only, so that the loop guard stops it long before any clock would.
            loop_line = ("float k = 0.0; if (gl_FragCoord.x < 130.0 && gl_FragCoord.x > 126.0) while (k >= 0.0) "
                         "{ k += u_ambient + 1.0; } o_color = vec4(color * max(k, 1.0), 1.0);")
            looping = good.replace(GOOD_LINE, loop_line)
            s.save("phong.frag", looping)
            st = self.wait_error(s, st["generation"])
            err = st["error"]
            self.assertTrue(err["endless_loop"], err)
            n = line_of(looping, loop_line)
            self.assertIn("Endless loop: phong.frag:%d (pass 'shade')" % n, err["title"])
            self.assertNotIn("Timed out", err["title"])
            d = err["diagnostics"][0]
            self.assertEqual((d["line"], d["column"]), (n, looping.split("\n")[n - 1].index("while") + 1), d)
            page.wait_for("document.getElementById('error-title').textContent.startsWith('Endless loop')", 20)
            pre = page.eval("document.querySelector('#error-diagnostics pre').textContent")
            caret = [l for l in pre.split("\n") if l.rstrip().endswith("^")]
            self.assertEqual(len(caret), 1, pre)
            src = [l for l in pre.split("\n") if l.strip().startswith("%d |" % n)][0]
            self.assertEqual(caret[0].index("^"), src.index("while"), pre)

            # A matrix product of the wrong sizes in the vertex shader: caret and types.
            s.save("phong.frag", good)
            st = s.wait_state(lambda x: x["generation"] > st["generation"] and not x["error"], 60, "mended")
            vert = s.read("phong.vert")
            bad = vert.replace("u_model * vec4(a_position, 1.0)", "u_model * a_position")
            self.assertNotEqual(bad, vert)
            s.save("phong.vert", bad)
            st = self.wait_error(s, st["generation"])
            d = st["error"]["diagnostics"][0]
            self.assertEqual(d["file"], "phong.vert")
            self.assertIn("`u_model` is a mat4 and `a_position` a vec3", d["message"])
            self.assertEqual(d["column"], d["source_line"].index("*") + 1, d)
            page.wait_for("document.getElementById('error').innerText.includes('is a mat4')", 20)

    # 7. The keys of `shaderlab view`, and keys kept after a list is used.
    def test_07_keys_of_view(self):
        def key(page, k, code=None, vk=0):
            for kind in ("rawKeyDown", "keyUp"):
                params = {"type": kind, "key": k, "code": code or k, "windowsVirtualKeyCode": vk}
                page.call("Input.dispatchKeyEvent", **params)

        with Served(ARGS, "06-bloom") as s:
            page = self.open(s)
            st = self.wait_settled(s, page)
            scenes = st["scenes"]
            self.assertEqual(page.eval("document.activeElement.id"), "stage")
            key(page, "ArrowRight", vk=39)
            st = s.wait_state(lambda x: x["view"]["scene"] == scenes[1], 10, "the next scene")
            page.wait_for("ui.state.picture && ui.state.picture.scene === '%s'" % scenes[1], 60)
            first = page.eval("shownIndex(ui.state.picture)")
            key(page, "ArrowUp", vk=38)
            page.wait_for("shownIndex(ui.state.picture) === %d" % (first - 1), 10, "the image above")
            key(page, "ArrowDown", vk=40)
            page.wait_for("shownIndex(ui.state.picture) === %d" % first, 10, "the image below")
            # Tab on the picture: the textures the pass reads, one by one.
            inputs = page.eval("ui.state.picture.images[shownIndex(ui.state.picture)].inputs.length")
            self.assertGreater(inputs, 0)
            key(page, "Tab", vk=9)
            page.wait_for("ui.input && ui.input.k === 0", 10, "the first texture")
            self.assertEqual(page.eval("document.activeElement.id"), "stage")
            page.wait_for("document.getElementById('picture-label').textContent.includes(' reads ')", 20,
                          "the texture drawn")
            page.eval("document.getElementById('mode-split').click(); document.getElementById('stage').focus(); true")
            split = page.eval("ui.split")
            key(page, "]", code="BracketRight", vk=221)
            page.wait_for("ui.split > %f" % split, 5, "the split moved")
            key(page, "ArrowLeft", vk=37)
            s.wait_state(lambda x: x["view"]["scene"] == scenes[0], 10, "the scene before")
            # The scene list used with the mouse: the keys still work after it.
            page.eval("(() => { const e = document.getElementById('scene'); e.focus(); e.value = '%s';"
                      " e.dispatchEvent(new Event('change')); return true; })()" % scenes[2])
            s.wait_state(lambda x: x["view"]["scene"] == scenes[2], 10, "the scene picked")
            self.assertEqual(page.eval("document.activeElement.id"), "stage", "the keys went with the list")
            key(page, "3", code="Digit3", vk=51)
            page.wait_for("ui.mode === 'diff'", 5, "key 3")
            key(page, "?", code="Slash", vk=191)
            page.wait_for("!document.getElementById('keys').classList.contains('hidden')", 5, "the list of keys")
            self.assertIn("previous / next scene", self.text(page, "keys"))

    # 8. Accessible names and roles; verdict changes in a live region.
    def test_08_accessible_names_roles_and_live_verdicts(self):
        with Served(ARGS, "01-phong") as s:
            page = self.open(s)
            self.wait_settled(s, page)
            page.call("Accessibility.enable")
            nodes = page.call("Accessibility.getFullAXTree")["nodes"]

            def named(role, pattern):
                roles = {"img": ("img", "image")}.get(role, (role,))
                for n in nodes:
                    if n.get("ignored"):
                        continue
                    r = n.get("role", {}).get("value")
                    name = n.get("name", {}).get("value", "")
                    if r in roles and re.search(pattern, name):
                        return n
                return None

            self.assertIsNotNone(named("combobox", r"^Scene$"), "the scene list has no name")
            self.assertIsNotNone(named("list", r"^Images of this scene$"), "the image list has no name")
            self.assertIsNotNone(named("img", r"^your picture of scene \w+, pass shade into shade\.color, passes$"),
                                 "the picture has no name")
            self.assertIsNotNone(named("list", r"^Goals$"))
            self.assertIsNotNone(named("button", r"^scene sphere passes$"))
            self.assertIsNotNone(named("button", r"^pass shade into shade\.color, graded, passes$"))
            student = named("button", r"^student$")
            self.assertIsNotNone(student)
            pressed = [p for p in student.get("properties", []) if p["name"] == "pressed"]
            self.assertTrue(pressed and pressed[0]["value"]["value"] in (True, "true"), student)
            self.assertIsNotNone(named("navigation", r"What the picture shows"))
            self.assertIsNotNone(named("complementary", r"Verdict and grade"))
            live = page.eval("(() => { const e = document.getElementById('announce');"
                             " return [e.getAttribute('role'), e.getAttribute('aria-live'), e.textContent]; })()")
            self.assertEqual(live[:2], ["status", "polite"])
            self.assertIn("Grade: the lab passes, 10.0 of 10.0 points", live[2])
            s.save("phong.frag", s.read("phong.frag").replace("vec3 n = normalize(v_world_normal);",
                                                              "vec3 n = normalize(v_world_normal)"))
            said = page.wait_for("(() => { const t = document.getElementById('announce').textContent;"
                                 " return t.includes('does not compile') ? t : ''; })()", 60, "the failure announced")
            self.assertIn("Your shader does not compile", said)

    # 9. A light theme under prefers-color-scheme: light.
    def test_09_light_theme(self):
        with Served(ARGS, "01-phong") as s:
            page = self.open(s)
            self.wait_settled(s, page)

            def luminance(expr):
                rgb = page.eval("getComputedStyle(%s).backgroundColor" % expr)
                r, g, b = [int(v) for v in re.findall(r"\d+", rgb)[:3]]
                return (0.2126 * r + 0.7152 * g + 0.0722 * b) / 255

            page.call("Emulation.setEmulatedMedia", features=[{"name": "prefers-color-scheme", "value": "dark"}])
            page.wait_for("matchMedia('(prefers-color-scheme: dark)').matches", 5)
            self.assertLess(luminance("document.body"), 0.2)
            page.call("Emulation.setEmulatedMedia", features=[{"name": "prefers-color-scheme", "value": "light"}])
            page.wait_for("matchMedia('(prefers-color-scheme: light)').matches", 5)
            self.assertGreater(luminance("document.body"), 0.8)
            self.assertGreater(luminance("document.getElementById('grade-box')"), 0.8)
            text = page.eval("getComputedStyle(document.getElementById('grade-score')).color")
            self.assertLess(sum(int(v) for v in re.findall(r"\d+", text)[:3]) / 3, 100, "dark text on light: %s" % text)

    # 10. The terminal follows the page; the favicon; a save without a change gets a sign.
    def test_10_terminal_favicon_and_unchanged_saves(self):
        with Served(ARGS, "01-phong") as s:
            page = self.open(s)
            self.wait_settled(s, page)
            status, body = s.get("/favicon.ico")
            self.assertEqual(status, 200)
            self.assertIn(b"<svg", body)
            good = s.read("phong.frag")
            s.save("phong.frag", good.replace("vec3 n = normalize(v_world_normal);", "vec3 n = normalize(v_world_normal)"))
            s.wait_state(lambda x: x["error"] and settled(x), 60, "the error graded")
            out = "".join(s.output)
            self.assertIn("serve: phong.frag changed; rendering again", out)
            self.assertIn("serve: Your shader does not compile", out)
            self.assertRegex(out, r"open it: \S+ \+\d+ \S*phong\.frag")
            self.assertRegex(out, r"serve: grade 0\.00 / 10\.00")
            s.save("phong.frag", good)
            s.wait_state(lambda x: not x["error"] and settled(x) and x["grade"]["lab"]["status"] == "passed", 60)
            out = "".join(s.output)
            self.assertRegex(out, r"serve: scene \w+ rendered in \d+ ms; ready \d+ ms after the save")
            self.assertIn("serve: grade 10.00 / 10.00; every goal met", out)
            before = s.state()["unchanged_saves"]["count"]
            # Saved again as it is (an editor's save of a buffer it did not change): a sign, no render.
            time.sleep(0.05)
            os.utime(os.path.join(s.lab_dir, "phong.frag"))
            s.wait_state(lambda x: x["unchanged_saves"]["count"] > before, 10, "the unchanged save seen")
            note = page.wait_for("(() => { const e = document.getElementById('save-note');"
                                 " return e.classList.contains('hidden') ? '' : e.textContent; })()", 10, "the sign")
            self.assertIn("phong.frag saved without a change", note)
            self.assertIn("phong.frag saved without a change", "".join(s.output))


    # 11. How a goal was judged (report.json's judged, judged_note, whole_failing), from a grade
    #     that carries them: a fixture state handed to the page as an event would hand it.
    def test_11_goals_say_how_they_were_judged(self):
        with Served(ARGS, "01-phong") as s:
            page = self.open(s)
            st = self.wait_settled(s, page)
            goals = st["grade"]["lab"]["goals"]
            self.assertGreaterEqual(len(goals), 4)
            shown = page.eval("""(() => {
                const s = JSON.parse(JSON.stringify(ui.state));
                s.version += 1000;
                const g = s.grade.lab.goals;
                g[0].judged = 'alone'; g[0].met = true; g[0].whole_failing = ['sphere/shade'];
                g[1].judged = 'alone'; g[1].met = false; g[1].failing = ['torus/shade'];
                g[2].judged = 'whole'; g[2].judged_note = 'its work is in main(), with the rest';
                g[3].judged = 'combination';
                take(s);
                return [...document.querySelectorAll('#goals > li')].map(li => {
                  const j = li.querySelector('.judged'); return j ? j.textContent : ''; });
              })()""")
            self.assertEqual(shown[0], "your own work for it is right; it fails in your whole shader because of another part")
            self.assertEqual(shown[1], "judged on your own work for it")
            self.assertEqual(shown[2], "its work is in main(), with the rest")
            self.assertEqual(shown[3], "")
            # A grade without the fields (an older report) says nothing of it.
            self.assertEqual(page.eval("""(() => {
                const s = JSON.parse(JSON.stringify(ui.state)); s.version += 1;
                for (const g of s.grade.lab.goals) { delete g.judged; delete g.judged_note; delete g.whole_failing; }
                take(s);
                return [...document.querySelectorAll('#goals .judged')].length; })()"""), 0)


class CommandLineTest(unittest.TestCase):
    """What `serve` prints before there is a page: addresses, unknown labs."""

    def run_serve(self, *args, timeout=60):
        return subprocess.run([ARGS.shaderlab, "serve", *args, "--labs", os.path.join(ARGS.source, "labs")],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=timeout)

    def test_unknown_labs_are_listed_with_a_guess(self):
        r = self.run_serve("99-nope")
        self.assertEqual(r.returncode, 2, r.stdout)
        self.assertEqual(r.stdout.count("99-nope"), 1, r.stdout)
        self.assertIn("01-phong", r.stdout)
        self.assertIn("06-bloom", r.stdout)
        for wrong in ("phong", "01-phogn"):
            r = self.run_serve(wrong)
            self.assertEqual(r.returncode, 2, r.stdout)
            self.assertIn("did you mean 01-phong?", r.stdout)

    def test_any_address_prints_one_to_open(self):
        with Served(ARGS, "01-phong", extra=["--host", "0.0.0.0"]) as s:
            out = "".join(s.output)
            self.assertRegex(out, r"open http://127\.0\.0\.1:%d/" % s.port)
            self.assertNotIn("http://0.0.0.0", out)
            self.assertIn("WARNING", out)


def main():
    def take(args):
        global ARGS
        ARGS = args
    return serve_fixture.run_browser_suite(take)


if __name__ == "__main__":
    sys.exit(main())
