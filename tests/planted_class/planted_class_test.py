#!/usr/bin/env python3
"""`shaderlab batch`, `class` and `similarity` on a class as it really arrives, everything in it
planted (make_planted_class.py says what): 31 submissions handing in three labs of twelve.

Checks, each against what was planted (truth.json):
  - batch grades the labs each submission hands in: every verdict as planted, totals out of the three
    labs' 30 points, the untouched starter "not_attempted" with no hint and no known mistake, an empty
    lab folder not handed in, Phong.frag graded with the note "found Phong.frag; the lab expects
    phong.frag", and no path of the results folder's unpacked zips in anything a student reads;
  - the endless loop (a light loop without ++i) stopped after one strip of one scene, the lab's other
    scenes not drawn with it, as its report says; its wall time is printed;
  - class: per lab over those who handed it in, totals over the three labs, "needs help" exactly the
    students with a lab not handed in, not attempted, not built or rendered, or below half its
    points; "Re-teach first" the goals failed on the students' own work (the four shared mistakes),
    each known mistake under the goal it breaks;
  - similarity: every planted copy flagged, no pair written apart flagged (the two Blinn-Phong
    solutions among them), no cluster holding two students written apart.

Usage: planted_class_test.py SHADERLAB_BINARY SOURCE_DIR
"""
import itertools
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

BIN = os.path.abspath(sys.argv[1]) if len(sys.argv) > 1 else "build/framework/shaderlab"
SOURCE = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else "."
LABS = os.path.join(SOURCE, "labs")


def run(*args, expect=0):
    r = subprocess.run([BIN, *args], capture_output=True, text=True, timeout=900)
    if expect is not None and r.returncode != expect:
        raise AssertionError("%s exited %d:\n%s\n%s" % (" ".join(args), r.returncode, r.stdout, r.stderr))
    return r


class PlantedClass(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.dir = tempfile.mkdtemp(prefix="shaderlab_planted_")
        subprocess.run([sys.executable, os.path.join(SOURCE, "tests/planted_class/make_planted_class.py"),
                        cls.dir], check=True, capture_output=True)
        with open(os.path.join(cls.dir, "truth.json"), encoding="utf-8") as f:
            cls.truth = json.load(f)
        cls.subs = os.path.join(cls.dir, "submissions")
        cls.results = os.path.join(cls.dir, "results")
        t0 = time.time()
        cls.batch = run("batch", cls.subs, "--out", cls.results, "--labs", LABS, "--jobs", "2")
        cls.batch_seconds = time.time() - t0
        with open(os.path.join(cls.results, "summary.json"), encoding="utf-8") as f:
            cls.summary = json.load(f)
        run("class", cls.results, "--out", os.path.join(cls.dir, "class"), "--labs", LABS)
        with open(os.path.join(cls.dir, "class", "class.json"), encoding="utf-8") as f:
            cls.cls = json.load(f)
        run("similarity", cls.subs, "--out", os.path.join(cls.dir, "similarity"), "--labs", LABS)
        with open(os.path.join(cls.dir, "similarity", "pairs.json"), encoding="utf-8") as f:
            cls.pairs = json.load(f)
        print("\n[planted class] batch of %d submissions: %.1f s" % (len(cls.truth["students"]), cls.batch_seconds))

    @classmethod
    def tearDownClass(cls):
        shutil.rmtree(cls.dir, ignore_errors=True)

    def row(self, student):
        return next(r for r in self.summary["submissions"] if r["student"] == student)

    def report(self, student):
        with open(os.path.join(self.results, self.row(student)["report"]), encoding="utf-8") as f:
            return json.load(f)

    def lab_report(self, student, lab):
        return next(l for l in self.report(student)["labs"] if l["id"] == lab)

    # ---- batch ------------------------------------------------------------------------------

    def test_the_labs_handed_in_are_graded_and_totalled(self):
        self.assertEqual(self.summary["labs"], self.truth["labs"])
        self.assertFalse(self.summary["labs_named"])
        self.assertIn("labs: 01-phong (31), 02-toon (30), 11-shadow-mapping (31)", self.batch.stdout)
        for r in self.summary["submissions"]:
            self.assertEqual(r["status"], "graded", r["student"])
            self.assertEqual(r["max_total"], 30.0, r["student"])
            self.assertAlmostEqual(r["total"], sum(l["score"] for l in r["labs"].values()), places=6)

    def test_every_verdict_is_as_planted(self):
        wrong = []
        for student, labs in self.truth["students"].items():
            for lab, planted in labs.items():
                got = self.row(student)["labs"][lab]["status"]
                if got != planted["status"]:
                    wrong.append("%s %s: %s, planted %s" % (student, lab, got, planted["status"]))
                    continue
                if planted["status"] != "failed":
                    continue
                failed = {g["id"] for g in self.lab_report(student, lab)["goals"]
                          if not g["met"] and not g["not_met_because"]}
                if set(planted["fails"]) != failed:
                    wrong.append("%s %s: own work failed %s, planted %s" % (student, lab, sorted(failed),
                                                                             planted["fails"]))
        self.assertEqual(wrong, [])

    def test_untouched_starter_is_not_attempted(self):
        for student in ("sam", "tara"):  # tara's files have CRLF line endings and trailing spaces
            for lab in self.truth["labs"]:
                l = self.lab_report(student, lab)
                self.assertEqual(l["status"], "not_attempted", (student, lab))
                self.assertEqual(l["score"], 0.0)
                self.assertEqual(l["scenes"], [])
                self.assertEqual(l["goals"], [])
                self.assertIn("the lab's starter code, unchanged", l["message"])
        # A comment of one's own is a change: graded (and, the starter drawing what it draws, failed).
        folder = os.path.join(self.dir, "commented", "01-phong")
        shutil.copytree(os.path.join(LABS, "01-phong"), folder, ignore=shutil.ignore_patterns("golden", "hints"))
        with open(os.path.join(folder, "phong.frag"), "a", encoding="utf-8") as f:
            f.write("// I will do this tomorrow\n")
        out = os.path.join(self.dir, "commented-grade")
        run("grade", os.path.dirname(folder), "--lab", "01-phong", "--out", out, "--labs", LABS, expect=1)
        with open(os.path.join(out, "report.json"), encoding="utf-8") as f:
            self.assertEqual(json.load(f)["labs"][0]["status"], "failed")

    def test_an_empty_lab_folder_is_not_handed_in(self):
        l = self.lab_report("max", "02-toon")
        self.assertEqual(l["status"], "missing")
        self.assertIn("not handed in: 02-toon/ holds none of the lab's files", l["message"])

    def test_a_file_named_but_for_its_case_is_graded_with_a_note(self):
        l = self.lab_report("lea", "01-phong")
        self.assertEqual(l["status"], "passed")
        notes = [d["message"] for d in l["diagnostics"] if d["severity"] == "warning"]
        self.assertIn("found Phong.frag; the lab expects phong.frag", notes)
        self.assertIn("01-phong: found Phong.frag; the lab expects phong.frag", self.row("lea")["message"])

    def test_no_unpacked_or_temporary_path_reaches_a_student(self):
        state = os.path.join(self.results, ".shaderlab")
        with open(os.path.join(self.results, "summary.csv"), encoding="utf-8") as f:
            csv = f.read()
        self.assertNotIn(state, csv)
        for student in self.truth["students"]:
            report = self.report(student)
            for l in report["labs"]:
                texts = [l["message"], l["folder"]] + [d["message"] for d in l["diagnostics"]]
                for s in l["scenes"]:
                    texts.append(s["message"])
                for t in texts:
                    self.assertNotIn(".shaderlab", t, student)
                    self.assertNotIn(tempfile.gettempdir() + "/shaderlab-", t, student)
        # The zip's labs are named inside the zip, and the missing file by the name the student uses.
        zipped = self.lab_report("Zoë Ångström", "01-phong")["folder"]
        self.assertTrue(zipped.endswith("Zoë Ångström.zip/Assignment 1/01-phong"), zipped)

    def test_the_endless_loop_costs_one_strip(self):
        l = self.lab_report("kim", "01-phong")
        self.assertEqual(l["status"], "timeout")
        self.assertEqual(l.get("limit"), "loop")
        with open(os.path.join(LABS, "01-phong", "lab.json")) as f:
            others = len(json.load(f)["scenes"]) - 1
        self.assertIn("the lab's %d other scenes were not drawn with this shader" % others, l["message"])
        # One strip of the first scene ran the loop to the guard, not the whole sphere (23,750 pixels).
        looped = int(l["message"].split("(")[1].split(" pixels")[0])
        self.assertLessEqual(looped, 2048)
        print("\n[planted class] the light loop without ++i: %d pixels ran it, %.2f s for the lab"
              % (looped, l["wall_ms"] / 1000.0))
        # The loop's cost in a lone grade too.
        out = os.path.join(self.dir, "kim-grade")
        t0 = time.time()
        run("grade", os.path.join(self.subs, "kim"), "--lab", "01-phong", "--out", out, "--labs", LABS, expect=1)
        print("[planted class] grade of that lab alone: %.2f s" % (time.time() - t0))

    # Named to run last: it adds a student to the class the other tests read.
    def test_zz_a_rerun_grades_nothing_and_a_new_student_only_that_one(self):
        r = run("batch", self.subs, "--out", self.results, "--labs", LABS, "--jobs", "2")
        self.assertIn("(0 graded, 31 unchanged since their report), 0 worker runs", r.stdout)
        shutil.copytree(os.path.join(self.subs, "ada"), os.path.join(self.subs, "zed"))
        with open(os.path.join(self.subs, "zed", "01-phong", "phong.frag"), "a", encoding="utf-8") as f:
            f.write("// zed's own\n")
        r = run("batch", self.subs, "--out", self.results, "--labs", LABS, "--jobs", "2")
        self.assertIn("(1 graded, 31 unchanged since their report), 1 worker runs (1 lab folders graded, 0 "
                      "reference solutions rendered), 2 lab folders found graded by an earlier run", r.stdout)

    # ---- class ------------------------------------------------------------------------------

    def test_class_totals_and_counts_are_over_the_labs_handed_in(self):
        c = self.cls
        self.assertEqual(c["max_total"], 30.0)
        self.assertEqual([l["id"] for l in c["labs"]], self.truth["labs"])
        by_id = {l["id"]: l for l in c["labs"]}
        self.assertEqual(by_id["01-phong"]["handed_in"], 29)  # not sam, tara
        self.assertEqual(by_id["01-phong"]["not_attempted"], 2)
        self.assertEqual(by_id["02-toon"]["handed_in"], 28)  # not max (empty folder), sam, tara
        for lab in c["labs"]:
            for m in lab["mistakes"]:
                self.assertNotIn(m["mistake"], ("geometric-normal-lit",), "the starter is not a known mistake")

    def test_needs_help_means_help(self):
        needs = {n["student"]: n for n in self.cls["needs_help"]}
        self.assertEqual(set(needs), {"jules", "kim", "max", "sam", "tara"})
        self.assertIn("did not compile: 01-phong", needs["jules"]["reasons"])
        self.assertIn("timed out in 1 lab: 01-phong", needs["kim"]["reasons"])
        self.assertIn("not handed in: 02-toon", needs["max"]["reasons"])
        for n in needs.values():
            self.assertEqual(n["max_total"], 30.0)

    def test_reteach_first_ranks_goals_failed_on_the_students_own_work(self):
        first = [(r["lab"], r["goal"], r["own_failed"], r["mistake"]) for r in self.cls["reteach_first"]]
        # Ties keep the course's order (lab, then goal).
        self.assertEqual(first, [
            ("02-toon", "bands", 4, "steps-round"),
            ("11-shadow-mapping", "bias", 4, "no-bias"),
            ("01-phong", "phong_lobe", 3, "blinn-phong-same-exponent"),
            ("01-phong", "per_fragment", 3, "gouraud"),
            ("11-shadow-mapping", "pcf", 3, "pcf-single-tap"),
        ])
        # Each known mistake under the goal it breaks, not under the goals resting on it.
        goals = {m["mistake"]: m["goals"] for l in self.cls["labs"] for m in l["mistakes"]}
        self.assertEqual(goals["no-bias"], ["bias"])
        self.assertEqual(goals["blinn-phong-same-exponent"], ["phong_lobe"])
        self.assertEqual(goals["gouraud"], ["per_fragment"])

    # ---- similarity -------------------------------------------------------------------------

    def relation(self, lab, a, b):
        """copy, independent or related (make_planted_class.py says what each means)."""
        ta, tb = self.truth["students"][a].get(lab), self.truth["students"][b].get(lab)
        if not ta or not tb or not ta["origins"] or not tb["origins"]:
            return "none"
        if {"lab": lab, "students": sorted([a, b])} in self.truth["copies"]:
            return "copy"
        oa = {o for o in ta["origins"].values() if o != "starter"}
        ob = {o for o in tb["origins"].values() if o != "starter"}
        return "independent" if oa and ob and not (oa & ob) else "related"

    def test_similarity_flags_every_copy_and_no_pair_written_apart(self):
        flagged = {(p["lab"], tuple(sorted([p["a"]["student"], p["b"]["student"]])))
                   for p in self.pairs["pairs"] if p["flagged"]}
        copies, independent, false_flags = 0, 0, []
        for lab in self.truth["labs"]:
            for a, b in itertools.combinations(sorted(self.truth["students"]), 2):
                rel = self.relation(lab, a, b)
                key = (lab, (a, b))
                if rel == "copy":
                    copies += 1
                    self.assertIn(key, flagged, "the planted copy %s is not flagged" % (key,))
                elif rel == "independent":
                    independent += 1
                    if key in flagged:
                        false_flags.append(key)
        self.assertEqual(copies, 3)
        self.assertEqual(false_flags, [])
        print("\n[planted class] similarity: %d of %d planted copies flagged; %d of %d pairs written apart "
              "flagged" % (copies, copies, len(false_flags), independent))
        # The two Blinn-Phong solutions written apart: not flagged (listed for reading, or not at all
        # where they share less than the listing's floor).
        blinn = [p for p in self.pairs["pairs"] if p["lab"] == "01-phong"
                 and {p["a"]["student"], p["b"]["student"]} == {"quinn", "rosa"}]
        for p in blinn:
            self.assertFalse(p["flagged"])
            self.assertTrue(p["why"].startswith("not flagged: shares "), p["why"])
        for p in self.pairs["pairs"]:
            self.assertTrue(p["why"].startswith("flagged: " if p["flagged"] else "not flagged: "), p)

    def test_similarity_clusters_never_join_students_written_apart(self):
        for c in self.pairs["clusters"]:
            names = [s["student"] for s in c["students"]]
            for a, b in itertools.combinations(sorted(names), 2):
                self.assertNotEqual(self.relation(c["lab"], a, b), "independent", (c["lab"], names))

    def test_similarity_compares_a_file_named_but_for_its_case(self):
        self.assertIn("lea: found 01-phong/Phong.frag; the lab expects 01-phong/phong.frag", self.pairs["notes"])


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
