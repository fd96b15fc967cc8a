# SPDX-License-Identifier: MPL-2.0
"""The panel end to end in a real browser: rcxsim with a tower and the panel, a program downloaded and started by
the real nqc, the page opened in Debian's headless Chromium (driven by chromedriver through python3-selenium).
From the page: output A forward, the LCD showing the program's slot and number; a real click on Run stops the
program (outputs brake); View is held as long as the pointer is down. Screenshots go to the folder given as the first
argument.

Usage: test_chromium.py SCREENSHOT_DIR"""
import os
import subprocess
import sys
import tempfile
import time

from selenium import webdriver
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.action_chains import ActionChains
from selenium.webdriver.common.by import By

from panel_lib import HERE, NQC, Sim, check, wait_for

SLOT = 3
SHOWN = "1234"  # forward.nqc puts it on the display

# The usual seven-segment shapes (rcx-hardware.md §3.6: "Digit fonts are the usual seven-segment shapes").
FONT = {"": " ", "abcdef": "0", "bc": "1", "abdeg": "2", "abcdg": "3", "bcfg": "4", "acdfg": "5", "acdefg": "6",
        "abc": "7", "abcdefg": "8", "abcdfg": "9", "g": "-"}

# What the page draws, read from the page itself: the lit segments of each digit, the arrows of output A, the
# output table and the tasks line.
READ_PAGE = """
const card = document.querySelector('[data-brick="0"]');
if (!card || !card.querySelector('.lcd')) return null;
const lit = el => el.classList.contains('on');
const digits = {};
for (const el of card.querySelectorAll('[data-digit]'))
    if (lit(el)) digits[el.dataset.digit] = (digits[el.dataset.digit] || '') + el.dataset.part;
const mark = name => lit(card.querySelector(`[data-mark="${name}"]`));
const rowA = card.querySelector('.outputs tr');
return {
    digits,
    a_fwd: mark('output A fwd'), a_rev: mark('output A rev'),
    a_row: rowA.className, a_text: rowA.innerText.replace(/\\s+/g, ' ').trim(),
    rotor: card.querySelector('[data-rotor="A"]').getAttribute('class'),
    tasks: card.querySelector('.tasks').textContent,
    world_hidden: document.getElementById('world').hidden,
    link: document.getElementById('link').textContent,
};
"""


def digit(page, pos):
    parts = "".join(sorted(page["digits"].get(str(pos), "")))
    return FONT.get(parts, "?")


def number(page):
    return "".join(digit(page, pos) for pos in (5, 4, 3, 2, 1)).strip()


def showing(driver, wanted):
    """What the page shows if `wanted` holds for it, else None."""
    page = driver.execute_script(READ_PAGE)
    return page if page and wanted(page) else None


def browser():
    options = webdriver.ChromeOptions()
    options.binary_location = "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1100,700",
              "--no-first-run", "--disable-extensions"):
        options.add_argument(a)
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    driver.set_page_load_timeout(30)
    driver.set_script_timeout(10)
    return driver


def main():
    shots = sys.argv[1]
    os.makedirs(shots, exist_ok=True)
    tty_dir = tempfile.mkdtemp(prefix="panel.", dir=os.environ.get("PANEL_TMP"))
    tty = os.path.join(tty_dir, "rcx")
    with Sim("--tty", tty) as sim:
        wait_for("the tower " + tty, lambda: os.path.exists(tty))
        subprocess.run([NQC, "-S" + tty, "-TRCX2", "-d", "-pgm", str(SLOT), os.path.join(HERE, "forward.nqc"),
                        "-run"], check=True, timeout=90, stdout=subprocess.DEVNULL)
        driver = browser()
        try:
            driver.get("http://127.0.0.1:%d/" % sim.port)
            page = wait_for("the page to show output A forward and the program's display",
                            lambda: showing(driver, lambda p: p["link"] == "live" and p["a_fwd"] and p["a_row"] == "fwd"
                                            and digit(p, 0) == str(SLOT) and number(p) == SHOWN), seconds=20)
            check(not page["a_rev"] and page["rotor"] == "rotor fwd", "A turns forward: %r" % page)
            check("forward" in page["a_text"] and "power 7" in page["a_text"], "output table: %r" % page)
            check(page["tasks"] == "task 0", "task 0 runs, and the page says so: %r" % page)
            check(page["world_hidden"], "no world without --world")
            time.sleep(0.3)  # a turn of the wheel in the picture
            driver.save_screenshot(os.path.join(shots, "panel-running.png"))

            # A real click (pointer down and up over the button) on Run: the program stops, the outputs brake.
            driver.find_element(By.CSS_SELECTOR, '[data-brick="0"] [data-button="run"] rect').click()
            page = wait_for("the program to stop and output A to brake",
                            lambda: showing(driver, lambda p: p["a_row"] == "brake" and p["tasks"] == "none"
                                            and not p["a_fwd"]), seconds=10)
            check(not page["a_rev"] and page["rotor"] == "rotor brake", "A stopped: %r" % page)
            check(digit(page, 0) == str(SLOT), "still slot %d: %r" % (SLOT, page))
            state = sim.state()["bricks"][0]
            check(state["tasks"] == [] and all(m["dir"] == "brake" for m in state["motors"].values()),
                  "the simulator agrees: %r" % state)
            check('"dir":"brake"' in open(sim.trace).read(), "brake traced")
            driver.save_screenshot(os.path.join(shots, "panel-e2e.png"))
            # Held while pressed: the brick sees View down until the pointer lets go.
            view = driver.find_element(By.CSS_SELECTOR, '[data-brick="0"] [data-button="view"] rect')
            ActionChains(driver).click_and_hold(view).perform()
            wait_for("View held", lambda: sim.state()["bricks"][0]["buttons"]["view"], seconds=5)
            time.sleep(0.3)
            check(sim.state()["bricks"][0]["buttons"]["view"], "View still held")
            ActionChains(driver).release().perform()
            wait_for("View released", lambda: not sim.state()["bricks"][0]["buttons"]["view"], seconds=5)

            driver.find_element(By.ID, "audio").click()  # the tones to the speakers: no error either
            time.sleep(0.3)
            errors = [e for e in driver.get_log("browser") if e["level"] == "SEVERE"]
            check(not errors, "the page logged errors: %r" % errors)
        finally:
            driver.quit()
        check(sim.stop() < 3, "rcxsim stopped")
    os.rmdir(tty_dir)  # rcxsim removed its link
    print("panel in Chromium: ok, screenshots in " + shots)


if __name__ == "__main__":
    main()
