"""The browser screenshots of docs/students.md ("In your browser"): `shaderlab serve` on a student's
course, the page driven in headless Chromium (tests/serve/cdp.py), saved at each step.
Run by scripts/student-docs-screenshots.sh as
  python3 scripts/serve-screenshots.py SHADERLAB COURSE REPO IMAGES"""
import os
import re
import shutil
import signal
import subprocess
import sys
import time

shaderlab, course, repo, images = sys.argv[1:5]
sys.path.insert(0, os.path.join(repo, "tests", "serve"))
import cdp  # noqa: E402

work = os.path.join(course, "work", "01-phong")
serve = subprocess.Popen([shaderlab, "serve", "01-phong", "--port", "0"], cwd=course,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
url = None
for line in serve.stdout:
    m = re.search(r"open (http://\S+)", line)
    if m:
        url = m.group(1)
        break
browser = cdp.Browser(width=1400, height=960)
try:
    page = browser.new_page(url)
    seq = lambda: page.eval("window.workbench.shownSeq")  # noqa: E731
    graded = "(() => { const b = document.getElementById('badge').textContent; return !b.includes('grading'); })()"

    def settle(extra=0.3):
        page.wait_for("window.workbench.loads > 0", 60)
        page.wait_for(graded, 60)
        page.wait_for("document.getElementById('grade-state').textContent === ''", 60)
        time.sleep(extra)

    def scene(name):
        page.eval("(() => { const s = document.getElementById('scene'); s.value = '%s';"
                  " s.dispatchEvent(new Event('change')); })()" % name)
        page.wait_for("window.workbench.stateVersion && document.getElementById('picture-label').textContent"
                      " && document.getElementById('scene').value === '%s'" % name, 30)

    def shot(name):
        with open(os.path.join(images, name), "wb") as f:
            f.write(page.screenshot())

    # 1. A nearly right solution (Blinn's half vector instead of Phong's mirror direction): the diff.
    shutil.copy(os.path.join(repo, "tests/corpus/01-phong/blinn-phong/phong.frag"), os.path.join(work, "phong.frag"))
    shutil.copy(os.path.join(repo, "reference_solutions/01-phong/phong.vert"), os.path.join(work, "phong.vert"))
    page.wait_for("window.workbench.loads > 0", 60)
    before = seq()
    scene("torus_grazing")
    page.wait_for("window.workbench.shownSeq > %d" % before, 60)
    page.eval("document.getElementById('mode-diff').click()")
    settle()
    shot("serve-diff.png")
    # 2. A typo saved: the error above the last good picture.
    page.eval("document.getElementById('mode-student').click()")
    text = open(os.path.join(work, "phong.frag")).read()
    broken = text.replace("vec3 n = normalize(v_world_normal);", "vec3 n = normalize(v_world_normal)")
    with open(os.path.join(work, "phong.frag.tmp"), "w") as f:
        f.write(broken)
    os.replace(os.path.join(work, "phong.frag.tmp"), os.path.join(work, "phong.frag"))
    page.wait_for("!document.getElementById('error').classList.contains('hidden')", 60)
    settle()
    shot("serve-compile-error.png")
    # 3. The finished lab.
    shutil.copy(os.path.join(repo, "reference_solutions/01-phong/phong.frag"), os.path.join(work, "phong.frag"))
    page.wait_for("document.getElementById('error').classList.contains('hidden')", 60)
    page.wait_for("document.getElementById('badge').textContent.startsWith('PASS')", 60)
    settle()
    shot("serve-pass.png")
finally:
    browser.close()
    serve.send_signal(signal.SIGINT)
    serve.wait(20)
print("browser screenshots written to", images)
