"""The browser screenshots of docs/students.md ("In your browser"): `shaderlab serve` on a student's
course, the page driven in headless Chromium (tests/serve/cdp.py) at 1400, 1024 and 390 px wide, in
the dark theme and the light one, saved at each step.
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
# The server keeps talking (saves, grades): read it so that it never blocks on a full pipe.
terminal = []
reader = __import__("threading").Thread(target=lambda: [terminal.append(x) for x in serve.stdout], daemon=True)
reader.start()
browser = cdp.Browser(width=1400, height=960)


def save_file(name, text):
    path = os.path.join(work, name)
    with open(path + ".tmp", "w") as f:
        f.write(text)
    os.replace(path + ".tmp", path)


try:
    page = browser.new_page("about:blank")

    def size(width, height, mobile=False, theme="dark"):
        page.call("Emulation.setDeviceMetricsOverride", width=width, height=height, deviceScaleFactor=1, mobile=mobile)
        page.call("Emulation.setEmulatedMedia", features=[{"name": "prefers-color-scheme", "value": theme}])

    # Everything current: the newest files drawn, judged and graded, nothing running.
    current = ("(() => { const s = ui.state; if (!s || !s.picture || !s.grade || !s.grade.lab) return false;"
               " return !s.busy && s.picture.judged && s.picture.generation === s.generation &&"
               " s.grade.generation === s.generation && !s.grade.pending &&"
               " window.workbench.shownSeq === s.picture.seq; })()")

    def settle(extra=0.4):
        page.wait_for("window.workbench.loads > 0", 90)
        page.wait_for(current, 90)
        time.sleep(extra)

    def failed():
        page.wait_for("!!ui.state && !!ui.state.error && ui.state.error.generation === ui.state.generation &&"
                      " !!ui.state.grade && ui.state.grade.generation === ui.state.generation && !ui.state.busy", 90)
        time.sleep(0.4)

    def scene(name):
        page.eval("(() => { const s = document.getElementById('scene'); s.value = '%s';"
                  " s.dispatchEvent(new Event('change')); return true; })()" % name)
        page.wait_for("ui.state && ui.state.picture && ui.state.picture.scene === '%s'" % name, 60)

    def click(element_id):
        page.eval("document.getElementById('%s').click(); true" % element_id)

    def shot(name):
        with open(os.path.join(images, name), "wb") as f:
            f.write(page.screenshot())

    size(1024, 900)
    page.navigate(url)
    page.wait_for("!!window.workbench", 30)
    # 1. The starter as it comes, at 1024 px (a browser beside an editor): its warnings and goals.
    settle()
    shot("serve-1024.png")
    # 2. A nearly right solution (Blinn's half vector instead of Phong's mirror direction): the
    #    diff, its legend and the worst region marked, at 1400 px.
    size(1400, 960)
    shutil.copy(os.path.join(repo, "tests/corpus/01-phong/blinn-phong/phong.frag"), os.path.join(work, "phong.frag"))
    shutil.copy(os.path.join(repo, "reference_solutions/01-phong/phong.vert"), os.path.join(work, "phong.vert"))
    scene("torus_grazing")
    click("mode-diff")
    settle()
    shot("serve-diff.png")
    # 3. The same as a split in the light theme: whose side is whose.
    size(1400, 960, theme="light")
    click("mode-split")
    page.wait_for("window.workbench.shownKey.includes('/reference/')", 30)
    time.sleep(0.4)
    shot("serve-light.png")
    # 4. A typo saved: the error with the lines around it above the last good picture, greyed.
    size(1400, 960)
    click("mode-student")
    text = open(os.path.join(work, "phong.frag")).read()
    save_file("phong.frag", text.replace("vec3 n = normalize(v_world_normal);", "vec3 n = normalize(v_world_normal)"))
    failed()
    shot("serve-compile-error.png")
    # 5. The finished lab, on a phone-sized screen (390 px): one column, nothing cut off.
    shutil.copy(os.path.join(repo, "reference_solutions/01-phong/phong.frag"), os.path.join(work, "phong.frag"))
    size(1400, 960)
    settle()
    shot("serve-pass.png")
    # The whole page, top to bottom: every panel is there, one under the other.
    size(390, 844, mobile=True)
    time.sleep(0.6)
    height = page.eval("document.documentElement.scrollHeight")
    size(390, height, mobile=True)
    time.sleep(0.6)
    shot("serve-390.png")
finally:
    browser.close()
    serve.send_signal(signal.SIGINT)
    serve.wait(20)
print("browser screenshots written to", images)
