# SPDX-License-Identifier: MPL-2.0
"""Makes docs/world-panel.png, the README's picture of the world in the panel (not a test): rcxsim --world testpad
with a tower, the line follower of tests/world downloaded and run by the real nqc, the page in headless Chromium,
and after SECONDS of simulated driving a screenshot of the world and the brick beside it.

Usage, from the top of the tree after `make`:
    RCXSIM=build/host/rcxsim /usr/bin/python3 tests/panel/world_shot.py docs/world-panel.png [SECONDS]"""
import os
import subprocess
import sys
import tempfile
import time

from panel_lib import HERE, NQC, Sim, wait_for
from test_chromium import browser
from test_world import read


def main():
    out = sys.argv[1]
    seconds = float(sys.argv[2]) if len(sys.argv) > 2 else 12
    tty = os.path.join(tempfile.mkdtemp(prefix="panel."), "rcx")
    with Sim("--world", "testpad", "--tty", tty) as sim:
        wait_for("the tower", lambda: os.path.exists(tty))
        driver = browser()
        try:
            driver.set_window_size(1900, 900)
            driver.get("http://127.0.0.1:%d/" % sim.port)
            wait_for("the world drawn", lambda: read(driver), seconds=20)
            subprocess.run([NQC, "-S" + tty, "-TRCX2", "-d", os.path.join(HERE, "..", "world", "linefollow.nqc"),
                            "-run"], check=True, timeout=90, stdout=subprocess.DEVNULL)
            time.sleep(seconds)
            driver.save_screenshot(out)
        finally:
            driver.quit()
        sim.stop()
    print("wrote " + out)


if __name__ == "__main__":
    main()
