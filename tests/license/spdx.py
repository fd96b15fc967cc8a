# SPDX-License-Identifier: MPL-2.0
"""OpenRCX is licensed under the MPL 2.0 (issue 23 §5): every source file in the repository says so on its first
line (its second after a `#!` or `<!DOCTYPE html>` line), in a comment of its language.

  python3 spdx.py check SOURCE_DIR   (CTest's license.spdx) fails, naming each tracked source file that lacks the
                                     line, and when LICENSE or packaging/copyright do not carry the licence
  python3 spdx.py stamp SOURCE_DIR   writes the line into each source file that lacks it (run once for the whole
                                     tree; new files carry it from the start)

Which files are source, by name: C and headers (.c .h), the instruction tables (.def), assembler (.s with `;`,
.S), the linker script (.ld), CMake (CMakeLists.txt, .cmake), the Makefile, shell (.sh), Python (.py), the panel's
page (.html .js .css .svg), NQC programs (.nqc) and the man pages' sources (.1.in .7.in).
Exempt, as data or prose rather than source: Markdown and text documents (README.md, docs/*.md), the Debian
changelog template (packaging/changelog.in, whose format has no comments), packaging/copyright and README.Debian,
LICENSE itself, the fuzzers' corpus (tests/fuzz/corpus/: byte strings), the hand-made tool listings the firmware
checks read (tests/firmware/listings/*.nm, *.dis: a line more would be a line of the listing), firmware images
(.srec) and pictures (.png).
"""
import os
import subprocess
import sys

TAG = "SPDX-License-Identifier: MPL-2.0"

# How a file says it: the line, by the file's name.
C_STYLE = "/* %s */" % TAG
HASH = "# %s" % TAG
LINE_COMMENT = "// %s" % TAG
KINDS = [
    (lambda n: n.endswith((".c", ".h", ".def", ".ld", ".S", ".css")), C_STYLE),
    (lambda n: n.endswith(".s"), "; %s" % TAG),
    (lambda n: n.endswith((".js", ".nqc")), LINE_COMMENT),
    (lambda n: n == "CMakeLists.txt" or n == "Makefile" or n.endswith((".cmake", ".sh", ".py")), HASH),
    (lambda n: n.endswith((".html", ".svg")), "<!-- %s -->" % TAG),
    (lambda n: n.endswith((".1.in", ".7.in")), '.\\" %s' % TAG),
]
SKIP_DIRS = ("build/", ".git/", "tests/fuzz/corpus/", "tests/firmware/listings/")


def stamp_line(path):
    """The line `path` must carry, or None when it is not a source file."""
    if path.startswith(SKIP_DIRS) or "/__pycache__/" in "/" + path:
        return None
    name = os.path.basename(path)
    for matches, line in KINDS:
        if matches(name):
            return line
    return None


def files(root):
    """The repository's tracked files (or, outside a git checkout, every file but the build tree's)."""
    try:
        out = subprocess.run(["git", "-C", root, "ls-files", "-z"], capture_output=True, check=True).stdout
        return [p for p in out.decode().split("\0") if p and os.path.isfile(os.path.join(root, p))]
    except (OSError, subprocess.CalledProcessError):
        found = []
        for d, dirs, names in os.walk(root):
            rel = os.path.relpath(d, root)
            dirs[:] = [x for x in dirs if not (rel == "." and x in ("build", ".git"))]
            found += [os.path.normpath(os.path.join(rel, n)) for n in names]
        return found


def lead(lines):
    """How many lines come before the identifier's place: a `#!` or `<!DOCTYPE` line stays first."""
    return 1 if lines and (lines[0].startswith("#!") or lines[0].lower().startswith("<!doctype")) else 0


def carries(text):
    lines = text.split("\n")
    at = lead(lines)
    return len(lines) > at and TAG in lines[at]


def check(root):
    missing = []
    for p in sorted(files(root)):
        if stamp_line(p) and not carries(open(os.path.join(root, p), encoding="utf-8", errors="replace").read()):
            missing.append(p)
    problems = ["%s: no '%s' on its first line" % (p, TAG) for p in missing]
    common = "/usr/share/common-licenses/MPL-2.0"
    licence = os.path.join(root, "LICENSE")
    if not os.path.exists(licence):
        problems.append("LICENSE: missing")
    elif os.path.exists(common) and open(licence, "rb").read() != open(common, "rb").read():
        problems.append("LICENSE: not the text of %s" % common)
    copyright_text = open(os.path.join(root, "packaging", "copyright")).read()
    if "\nLicense: MPL-2.0\n" not in copyright_text or common not in copyright_text:
        problems.append("packaging/copyright: no 'License: MPL-2.0' paragraph pointing to %s" % common)
    for p in problems:
        print("FAIL: " + p, file=sys.stderr)
    if not problems:
        print("OK: %d source files carry %s" % (sum(1 for p in files(root) if stamp_line(p)), TAG))
    return 1 if problems else 0


def stamp(root):
    for p in sorted(files(root)):
        line = stamp_line(p)
        full = os.path.join(root, p)
        if not line:
            continue
        text = open(full, encoding="utf-8").read()
        if carries(text):
            continue
        lines = text.split("\n")
        at = lead(lines)
        lines.insert(at, line)
        with open(full, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        print("stamped " + p)
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 3 or sys.argv[1] not in ("check", "stamp"):
        print("usage: spdx.py check|stamp SOURCE_DIR", file=sys.stderr)
        sys.exit(2)
    sys.exit(check(sys.argv[2]) if sys.argv[1] == "check" else stamp(sys.argv[2]))
