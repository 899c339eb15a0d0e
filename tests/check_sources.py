#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Checks the form of the sources: every C++ file is formatted as the
repository's .clang-format says (clang-format 14, the version of Debian
12), and every source file (C++, CMake, Python, shell) carries the licence
tag in its first lines. Registered as the ctest style.sources.

    check_sources.py CLANG_FORMAT ROOT

Exit code 1, with the files and what is wrong in them, when a file is not
formatted or has no licence tag. To format: clang-format -i on the files
named (from ROOT, so that .clang-format is found).
"""

import subprocess
import sys
from pathlib import Path

TAG = "SPDX-License-Identifier: LGPL-2.1-or-later"
CXX_DIRECTORIES = ("source", "include", "tests")


def sources(root):
    """The C++ files and the other source files below ROOT, without build
    directories and generated output."""
    cxx, other = [], []
    for path in sorted(root.rglob("*")):
        relative = path.relative_to(root)
        if not path.is_file() or relative.parts[0] not in (
                "source", "include", "tests", "doc", "meshes", "parameters",
                ".ci", "CMakeLists.txt", "soft-robot.sh"):
            continue
        if path.suffix in (".cc", ".h") and relative.parts[0] in CXX_DIRECTORIES:
            cxx.append(path)
        elif (path.suffix in (".py", ".cmake", ".sh") or path.name == "CMakeLists.txt"
              or relative == Path(".ci/run")):
            other.append(path)
    return cxx, other


def main():
    clang_format, root = sys.argv[1], Path(sys.argv[2]).resolve()
    cxx, other = sources(root)
    problems = []
    for path in cxx + other:
        head = path.read_text(errors="replace").splitlines()[:3]
        if not any(TAG in line for line in head):
            problems.append(f"{path.relative_to(root)}: no '{TAG}' in its first lines")
    for path in cxx:
        check = subprocess.run([clang_format, "--dry-run", "--Werror",
                                str(path.relative_to(root))],
                               cwd=root, capture_output=True, text=True)
        if check.returncode != 0:
            lines = [line for line in check.stderr.splitlines() if "error:" in line]
            problems.append(f"{path.relative_to(root)}: not formatted "
                            f"({len(lines)} places; first: "
                            f"{lines[0] if lines else check.stderr.strip()[:200]})")
    for problem in problems:
        print(problem)
    print(f"{len(cxx)} C++ files, {len(other)} other source files: "
          f"{len(problems)} problems")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
