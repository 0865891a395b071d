#!/usr/bin/python3
"""How long a save takes to reach the workbench page: a benchmark that prints figures, not a test.

For each `shaderlab` given (NAME=PATH, e.g. this build and a baseline), `shaderlab serve` on a copy of
the lab's reference solution and one headless Chromium page on it (cdp.py). Each save changes a
comment of the lab's first student file (by rename, as most editors save), waits until the page
shows the new picture and the lab is graded again, then the next. Rounds alternate between the
programs, so that both meet the same load. Two figures per save:
  server: the server's own `latency_ms`, from the file's modification time to the picture ready;
  page:   from just before the save to the page's canvas showing it (window.workbench.pictureShownAt).
Prints the median and the 95th percentile of each.

Run: /usr/bin/python3 tests/serve/serve_latency.py --source . --saves 15 \\
         new=build/framework/shaderlab old=/path/to/baseline/shaderlab"""
import argparse
import os
import statistics
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cdp  # noqa: E402
from serve_fixture import Served  # noqa: E402


def percentile(values, q):
    v = sorted(values)
    if not v:
        return float("nan")
    pos = (len(v) - 1) * q
    lo = int(pos)
    hi = min(lo + 1, len(v) - 1)
    return v[lo] + (v[hi] - v[lo]) * (pos - lo)


def settled(st):
    p, g = st.get("picture"), st.get("grade")
    return bool(p) and p.get("judged") and not st.get("busy") and bool(g) and bool(g.get("lab")) and \
        not g.get("pending") and g.get("generation") == st.get("generation") and \
        p.get("generation") == st.get("generation")


def one_round(name, program, args, browser, saves, results):
    class Args:
        pass
    a = Args()
    a.shaderlab, a.source = program, args.source
    with Served(a, args.lab) as s:
        page = browser.new_page(s.url)
        try:
            page.wait_for("window.workbench && window.workbench.shownSeq > 0", 60)
            s.wait_state(settled, 120, "the first picture and grade")
            first = sorted(f for f in os.listdir(s.lab_dir) if f.endswith(".frag"))[0]
            text = s.read(first)
            for i in range(saves):
                seq = s.state()["picture"]["seq"]
                t0 = time.time()
                s.save(first, text + "\n// save %d of round %s %f\n" % (i, name, t0))
                shown = page.wait_for("window.workbench.shownSeq > %d && window.workbench.pictureShownAt" % seq,
                                      60, "the picture of save %d" % i)
                st = s.wait_state(settled, 120, "save %d graded" % i)
                results[name]["page"].append(shown - t0 * 1000.0)
                if st["picture"]["latency_ms"] is not None:
                    results[name]["server"].append(st["picture"]["latency_ms"])
        finally:
            page.close()


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--source", required=True)
    ap.add_argument("--lab", default="01-phong")
    ap.add_argument("--saves", type=int, default=15, help="saves per program, in rounds of 5")
    ap.add_argument("programs", nargs="+", help="NAME=PATH of a shaderlab program")
    args = ap.parse_args()
    args.source = os.path.abspath(args.source)
    programs = [(p.split("=", 1)[0], os.path.abspath(p.split("=", 1)[1])) for p in args.programs]
    results = {name: {"server": [], "page": []} for name, _ in programs}
    browser = cdp.Browser()
    try:
        done = 0
        while done < args.saves:
            n = min(5, args.saves - done)
            for name, program in programs:
                one_round(name, program, args, browser, n, results)
            done += n
    finally:
        browser.close()
    print("save to picture, %s, %d saves per program (ms): median, 95th percentile" % (args.lab, args.saves))
    for name, _ in programs:
        r = results[name]
        print("  %-8s server %6.0f %6.0f   page %6.0f %6.0f" % (
            name, statistics.median(r["server"]), percentile(r["server"], 0.95),
            statistics.median(r["page"]), percentile(r["page"], 0.95)))


if __name__ == "__main__":
    main()
