# SPDX-License-Identifier: MPL-2.0
"""Two rcxsim --panel on one port: the second is refused (one line naming the port, exit status 2) instead of both
serving it and sharing its requests; the first keeps answering."""
import os
import subprocess

from panel_lib import RCXSIM, Sim, check


def main():
    with Sim("--fast") as first:
        first.state()
        second = subprocess.run([RCXSIM, "--panel", str(first.port), "--fast", "--duration", "2000"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, timeout=30)
        err = second.stderr.decode("utf-8", "replace")
        check(second.returncode == 2, "second rcxsim on port %d: exit status %d, expected 2 (%r)"
              % (first.port, second.returncode, err))
        check(err.count("\n") == 1 and err.startswith("rcxsim: --panel %d:" % first.port),
              "second rcxsim: not one line naming --panel %d: %r" % (first.port, err))
        for _ in range(12):
            first.state()
        check(first.alive(), "the first rcxsim went away")
        first.stop()
    print("ok")


if __name__ == "__main__":
    main()
