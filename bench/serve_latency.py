"""The browser workbench's figures: start-up time of `shaderlab serve`, save-to-picture latency
(median and 95th percentile) as a student sees it in the page, and the page's weight.
  /usr/bin/python3 bench/serve_latency.py build/framework/shaderlab [LAB ...] [--saves N]
A save is a rename over the student's fragment shader (what most editors do) that adds a comment:
the files change, so the lab is rendered and graded again, and the page loads the new picture.
The latency is from just before the rename to the moment the page has drawn the new picture
(window.workbench.pictureShownAt, the page's clock; the same machine's clock as this script's)."""
import argparse
import json
import os
import statistics
import sys
import time
import urllib.request

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "tests", "serve"))
import cdp  # noqa: E402
import serve_fixture  # noqa: E402


def fetch_size(url):
    with urllib.request.urlopen(url, timeout=10) as r:
        return len(r.read())


def viewer_latencies(args, lab, saves):
    """The window's own figure for the same saves ("on screen N ms after the save", printed by
    `shaderlab view`), under Xvfb, for comparison."""
    import re
    import shutil
    import subprocess
    import tempfile
    tmp = tempfile.mkdtemp(prefix="shaderlab-view-bench-")
    root = os.path.join(tmp, "work")
    shutil.copytree(os.path.join(args.source, "reference_solutions", lab), os.path.join(root, lab))
    spec = json.load(open(os.path.join(args.source, "labs", lab, "lab.json")))
    frag = [f for f in spec["student_files"] if f.endswith(".frag")][-1]
    path = os.path.join(root, lab, frag)
    original = open(path).read()
    proc = subprocess.Popen(["xvfb-run", "-a", args.shaderlab, "view", lab, "--submission", root,
                             "--labs", os.path.join(args.source, "labs"),
                             "--exit-after-reloads", str(saves)],
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    latencies = []
    started = False
    for line in proc.stdout:
        if not started and "rendered in" in line:
            started = True
        m = re.search(r"on screen (\d+) ms after the save", line)
        if m:
            latencies.append(float(m.group(1)))
        if started and len(latencies) < saves and ("rendered in" in line):
            time.sleep(1.5)  # as the page's saves: after the previous picture has settled
            tmp_path = path + ".tmp-save"
            with open(tmp_path, "w") as f:
                f.write(original + "\n// save %d\n" % len(latencies))
            os.replace(tmp_path, path)
    proc.wait()
    shutil.rmtree(tmp, ignore_errors=True)
    return latencies


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("shaderlab")
    ap.add_argument("labs", nargs="*", default=["01-phong", "06-bloom"])
    ap.add_argument("--saves", type=int, default=20)
    ap.add_argument("--viewer", action="store_true", help="also measure `shaderlab view` (under Xvfb)")
    a = ap.parse_args()
    args = argparse.Namespace(shaderlab=os.path.abspath(a.shaderlab), source=os.path.join(here, ".."))
    browser = cdp.Browser()
    rows = []
    try:
        for lab in a.labs:
            with serve_fixture.Served(args, lab) as s:
                startup = s.address_printed - s.started
                page = browser.new_page(s.url)
                page.wait_for("window.workbench && window.workbench.loads > 0", 60)
                first_picture = page.eval("window.workbench.pictureShownAt") / 1000.0 - s.started
                state = s.state()
                frag = [f for f in state["lab"]["files"] if f.endswith(".frag")][-1]
                original = s.read(frag)
                # Let the first grade finish, as a student's first save would find it.
                s.wait_state(lambda st: st["grade"] and st["grade"]["lab"] and not st["grade"]["pending"], 120)
                latencies = []
                for i in range(a.saves):
                    seq = page.eval("window.workbench.shownSeq")
                    t0 = time.time()
                    s.save(frag, original + "\n// save %d\n" % i)
                    page.wait_for("window.workbench.shownSeq > %d" % seq, 60)
                    latencies.append(page.eval("window.workbench.pictureShownAt") - t0 * 1000.0)
                    # The next save comes after this one's grade, as a student's would.
                    s.wait_state(lambda st: st["grade"] and not st["grade"]["pending"] and not st["busy"], 120)
                latencies.sort()
                p95 = latencies[min(len(latencies) - 1, int(round(0.95 * (len(latencies) - 1))))]
                seq = page.eval("window.workbench.shownSeq")
                pic = json.loads(s.get("/api/state")[1])["picture"]
                weight = {
                    "page": fetch_size(s.url) + fetch_size(s.url + "assets/workbench.js") +
                            fetch_size(s.url + "assets/workbench.css"),
                    "state": len(s.get("/api/state")[1]),
                    "picture": fetch_size(s.url + "picture/%d/student/%d.png" % (seq, pic["final_image"])),
                }
                page.close()
                rows.append((lab, startup, first_picture, statistics.median(latencies), p95, weight))
    finally:
        browser.close()
    print("| lab | start-up (to the address) | first picture in the page | save to picture, median | p95 | page (html+js+css) | state JSON | one picture |")
    print("|---|---|---|---|---|---|---|---|")
    for lab, startup, first, med, p95, w in rows:
        print("| %s | %.0f ms | %.0f ms | %.0f ms | %.0f ms | %.1f KB | %.1f KB | %.1f KB |" % (
            lab, startup * 1000, first * 1000, med, p95, w["page"] / 1024, w["state"] / 1024, w["picture"] / 1024))
    if a.viewer:
        print()
        print("| lab | the window (`view`): save to picture on screen, median | p95 |")
        print("|---|---|---|")
        for lab in a.labs:
            v = sorted(viewer_latencies(args, lab, a.saves))
            if not v:
                print("| %s | (no figure: is Xvfb installed?) | |" % lab)
                continue
            p95 = v[min(len(v) - 1, int(round(0.95 * (len(v) - 1))))]
            print("| %s | %.0f ms | %.0f ms |" % (lab, statistics.median(v), p95))


if __name__ == "__main__":
    main()
