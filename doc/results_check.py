#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""Checks that doc/results.md lists the registered tests, no more and no
fewer. Registered as the ctest doc.results_lists_every_test.

    results_check.py [--ctest CTEST] BUILD_DIR [RESULTS_MD]

The registered tests are those `ctest --show-only=json-v1` lists in
BUILD_DIR (a build with SOFT_ROBOT_BUILD_TESTS=ON, after the build: the
GoogleTest cases are discovered when their executables are linked). The
entries of RESULTS_MD (default: doc/results.md beside this script) are the
names in backquotes in the first column of the tables of its section
"Test cases". A typed test is listed once for all its dimensions:
`Suite.Name` stands for the ctest entries `Suite.Name<std::integral_constant
<int, 1>>` and so on (and `Suite/0.Name`), and `*` in an entry stands for
any text (the scene runs, one per parameter file).

Exit code 1, with the rows to add or remove, when a test has no entry, an
entry matches no test, or a test is listed twice.
"""

import argparse
import fnmatch
import json
import re
import subprocess
import sys
from pathlib import Path


def registered_tests(ctest, build):
    listing = subprocess.run([ctest, "--show-only=json-v1"], cwd=build,
                             capture_output=True, text=True, check=True)
    names = [test["name"] for test in json.loads(listing.stdout)["tests"]]
    return sorted({folded(name) for name in names})


def folded(name):
    """The name of a test for all its dimensions: without the type
    parameter that gtest_discover_tests appends, and without gtest's
    /<index> of typed and parameterised tests."""
    name = re.sub(r"<.*>$", "", name)
    return re.sub(r"/\d+(?=[./]|$)", "", name)


def listed_tests(results):
    """The entries of the section "Test cases", with their line numbers."""
    entries, in_section = [], False
    for number, line in enumerate(results.read_text().splitlines(), start=1):
        if line.startswith("## "):
            in_section = line[3:].strip() == "Test cases"
        elif in_section and line.startswith("|") and not re.match(r"\|\s*-", line):
            first_column = line.split("|")[1]
            entries += [(name, number) for name in re.findall(r"`([^`]+)`", first_column)]
    return entries


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--ctest", default="ctest")
    parser.add_argument("build")
    parser.add_argument("results", nargs="?",
                        default=str(Path(__file__).resolve().parent / "results.md"))
    arguments = parser.parse_args()
    results = Path(arguments.results)

    tests = registered_tests(arguments.ctest, arguments.build)
    entries = listed_tests(results)
    problems = []
    seen = {}
    for name, number in entries:
        if name in seen:
            problems.append(f"{results.name}:{number}: `{name}` is listed twice "
                            f"(also line {seen[name]})")
        seen[name] = number
    unmatched = [(name, number) for name, number in entries
                 if not any(fnmatch.fnmatchcase(test, name) for test in tests)]
    missing = [test for test in tests
               if not any(fnmatch.fnmatchcase(test, name) for name, _ in entries)]
    for name, number in unmatched:
        problems.append(f"{results.name}:{number}: `{name}` is no registered test "
                        "(renamed or removed? remove or rename the row)")
    if missing:
        problems.append(f"registered tests without a row in {results.name} (add a row "
                        "to the table of their test file, with what the test checks "
                        "and the numbers it prints):\n"
                        + "\n".join(f"| `{test}` | | |" for test in missing))
    for problem in problems:
        print(problem, file=sys.stderr)
    if problems:
        sys.exit(1)
    print(f"{results.name} lists all {len(tests)} tests "
          f"(typed tests once for all dimensions).")


if __name__ == "__main__":
    main()
