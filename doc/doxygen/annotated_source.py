#!/usr/bin/env python3
# SPDX-License-Identifier: LGPL-2.1-or-later
"""The annotated source as doxygen pages, the way deal.II renders its
tutorial programs: the comments are the text, the code is shown between
them.

    annotated_source.py SOURCE_DIR PAGES_DIR
    annotated_source.py --warnings WARNINGS_FILE PAGES_DIR

The first form writes PAGES_DIR/index.md, the main page (doc/code-map.md
with its file names linked to their pages), PAGES_DIR/reading_order.md
(every page, in reading order) and one page PAGES_DIR/<name>.md per file
of include/ and source/, with PAGES_DIR/<name>.lines, the source line of
each line of the page. The second form prints doxygen's warnings about
the pages with the file and line of the source instead, and fails if
there are any.

The rules, those of deal.II's tutorials:
- A line whose first non-blank characters are `//` is text; the other
  lines are code, shown in @code ... @endcode blocks. A comment after code
  on the same line stays in the code.
- `// @sect3{Title}` and `// @sect4{Title}` at the start of a comment block
  are headings (doxygen's @section and @subsection).
- `$...$` in the text is an inline formula; `@f[ ... @f]` and
  `@f{align*}{ ... @f}` are displayed formulas; `@code ... @endcode` in the
  text is shown as code. The rest of the text is doxygen's markdown, in
  which `<word>` is text unless it is an HTML tag.

The reading order is the order in which doc/code-map.md names the files,
after its section "Layout" (which names a few of them in passing): a file
given with its area (`core/mesh.h`) or its full path (`source/main.cc`), or
by its name alone after another file of the same area. A header is
followed by the source file of the same name that implements it. A file of
include/ or source/ that the map does not name, or a name in the map that
is no file, is an error: the map and the pages would describe different
code. So is a comment that cannot be converted (an unclosed formula, code
span or code block). Exit code 1 after a message for each.
"""

import re
import sys
from pathlib import Path

SOURCE_PATTERNS = ("include/**/*.h", "source/**/*.h", "source/**/*.cc")

# HTML tags that doxygen renders in comments; any other `<word>` in the
# text (`Material <id>`, SoftRobotDynamics<dim>) is shown as it is.
HTML_TAGS = {"a", "b", "blockquote", "br", "caption", "center", "code", "dd",
             "del", "dfn", "div", "dl", "dt", "em", "h1", "h2", "h3", "h4",
             "h5", "h6", "hr", "i", "img", "kbd", "li", "ol", "p", "pre",
             "s", "small", "span", "strike", "strong", "sub", "sup", "table",
             "td", "th", "tr", "tt", "u", "ul", "var"}

FILE_NAME = r"`([A-Za-z0-9_./-]+\.(?:h|cc))`"


class ConversionError(Exception):
    pass


def page_name(path):
    """The doxygen label of a file's page: include/core/mesh.h gives
    include_core_mesh_h."""
    return re.sub(r"[^A-Za-z0-9]", "_", path)


# @sect{The reading order}

def source_files(root):
    files = set()
    for pattern in SOURCE_PATTERNS:
        files.update(p.relative_to(root).as_posix() for p in root.glob(pattern))
    return files


def map_sections(code_map):
    """The sections of the map, as (heading, text) pairs."""
    sections, heading, text = [], None, []
    for line in code_map.splitlines():
        if line.startswith("## "):
            sections.append((heading, "\n".join(text)))
            heading, text = line[3:].strip(), []
        else:
            text.append(line)
    sections.append((heading, "\n".join(text)))
    return sections


def resolve_names(code_map, existing):
    """The files the map names, in the order of their first mention, as
    (name in the map, path) pairs, and the names that are no file."""
    order, unknown, area = [], [], None
    for heading, text in map_sections(code_map):
        if heading == "Layout":
            continue
        for name in re.findall(FILE_NAME, text):
            parts = name.split("/")
            if parts[0] in ("include", "source"):
                candidates = [name]
                area = parts[1] if len(parts) > 2 else None
            elif len(parts) > 1:
                candidates = [f"include/{name}", f"source/{name}"]
                area = parts[0]
            elif area is not None:
                candidates = [f"include/{area}/{name}", f"source/{area}/{name}"]
            else:
                candidates = [f"source/{name}"]
            path = next((c for c in candidates if c in existing), None)
            if path is None:
                unknown.append(name)
            else:
                order.append((name, path))
    return order, unknown


def reading_order(order, existing):
    """The pages in reading order: each named file, a header followed by
    the source file that implements it."""
    pages = []
    for _, path in order:
        following = [path]
        if path.startswith("include/") and path.endswith(".h"):
            following.append("source/" + path[len("include/"):-2] + ".cc")
        for p in following:
            if p in existing and p not in pages:
                pages.append(p)
    return pages


# @sect{The text}

def escape_text(text):
    """Markdown outside code and formulas: `<word>` that is no HTML tag
    becomes text."""
    def tag(match):
        if match.group(2).lower() in HTML_TAGS:
            return match.group(0)
        return "&lt;" + match.group(0)[1:-1] + "&gt;"
    return re.sub(r"<(/?)([A-Za-z_][A-Za-z0-9_]*)([^<>\n]*)>", tag, text)


def convert_text(lines, where):
    """One comment block (without the comment markers) as doxygen
    markdown, line for line."""
    text = "\n".join(lines)
    out, i = [], 0
    # What is passed on unchanged, and the inline formulas.
    start = re.compile(r"`+|\$|@f\[|@f\{[A-Za-z*]+\}\{|@code\b")
    while i < len(text):
        match = start.search(text, i)
        if match is None:
            out.append(escape_text(text[i:]))
            break
        out.append(escape_text(text[i:match.start()]))
        opening = match.group(0)
        if opening.startswith("`"):
            closing = opening
        elif opening == "$":
            closing = "$"
        else:
            closing = {"@f[": "@f]", "@code": "@endcode"}.get(opening, "@f}")
        end = text.find(closing, match.end())
        if end < 0:
            raise ConversionError(f"{where}: {opening} without its {closing}")
        if opening == "$":
            out.append("@f$" + text[match.end():end] + "@f$")
        else:
            out.append(text[match.start():end + len(closing)])
        i = end + len(closing)
    return "".join(out).split("\n")


def heading(line, label):
    match = re.fullmatch(r"@sect([34])\{(.*)\}\s*", line)
    if match is None:
        return None
    command = "@section" if match.group(1) == "3" else "@subsection"
    return f"{command} {label} {convert_text([match.group(2)], label)[0]}"


# @sect{One file}

def blocks(source):
    """The file as a list of ("text" or "code", lines, first line number)."""
    result = []
    for number, line in enumerate(source.splitlines(), start=1):
        # The licence tag of the first line is for tools, not for readers.
        if number == 1 and "SPDX-License-Identifier" in line:
            continue
        comment = re.match(r"\s*//(.*)$", line)
        kind = "text" if comment else "code"
        if comment:
            line = comment.group(1)
            line = line[1:] if line.startswith(" ") else line
        if not result or result[-1][0] != kind:
            result.append((kind, [], number))
        result[-1][1].append(line.rstrip())
    return result


def convert_file(root, path, previous, following, notes):
    """The page of one file, as a list of (line, source line number);
    `notes` collects what is shown otherwise than the comment says."""
    name = page_name(path)
    out = [(f"# {path} {{#{name}}}", 1), ("", 1)]
    sections, has_section, promoted = 0, False, False
    for kind, lines, number in blocks((root / path).read_text()):
        numbers = list(range(number, number + len(lines)))
        if kind == "code":
            while lines and not lines[0].strip():
                lines, numbers = lines[1:], numbers[1:]
            while lines and not lines[-1].strip():
                lines, numbers = lines[:-1], numbers[:-1]
            if lines:
                out += ([("@code{.cpp}", numbers[0])] + list(zip(lines, numbers))
                        + [("@endcode", numbers[-1]), ("", numbers[-1])])
            continue
        where = f"{path}:{number}"
        title = heading(lines[0], f"{name}_{sections + 1}")
        if title is not None:
            if title.startswith("@section"):
                has_section = True
            elif not has_section:
                # A @sect4 before any @sect3 has no section to belong to.
                title = "@section" + title[len("@subsection"):]
                if not promoted:
                    notes.append(f"{where}: @sect4 before the first @sect3 of "
                                 "the file: shown as @sect3")
                promoted = True
            sections += 1
            out += [(title, number), ("", number)]
            lines, numbers = lines[1:], numbers[1:]
        if any(re.search(r"@sect\d", line) for line in lines):
            raise ConversionError(f"{where}: @sect3/@sect4 must start a comment block")
        if lines:
            out += list(zip(convert_text(lines, where), numbers))
            out.append(("", numbers[-1]))
    links = []
    if previous:
        links.append(f"previous: @ref {page_name(previous)} \"{previous}\"")
    if following:
        links.append(f"next: @ref {page_name(following)} \"{following}\"")
    links.append("@ref index \"the map of the code\"")
    last = out[-1][1]
    out += [("<hr>", last), ("", last), ("Reading order: " + "; ".join(links) + ".", last)]
    return out


# @sect{The main page and the list of pages}

def main_page(code_map, names):
    """doc/code-map.md with each file name linked to its page."""
    linked = dict(names)
    linked.update((path, path) for _, path in names)
    lines = code_map.splitlines()
    title = lines[0][2:].strip() if lines[0].startswith("# ") else "SoftRobotDynamics"
    text = "\n".join(lines[1:])

    def link(match):
        path = linked.get(match.group(1))
        if path is None:
            return match.group(0)
        return f'<code>@ref {page_name(path)} "{match.group(1)}"</code>'
    text = re.sub(FILE_NAME, link, text)
    text = re.sub(r"\$([^$]+)\$", r"@f$\1@f$", text)
    return "\n".join([
        f"@mainpage {title}", "",
        "The annotated source of SoftRobotDynamics, one page per file: the "
        "comments are the text, the code is shown between them. This page is "
        "the map of the code (doc/code-map.md); the pages follow in the order "
        "in which it names the files: @ref reading_order.", "", text, ""])


def reading_order_page(pages):
    """The parent of all pages (doxygen 1.9.4 does not show the subpages of
    the main page in its tree view)."""
    out = ["# The files in reading order {#reading_order}", ""]
    out += [f"- @subpage {page_name(p)}" for p in pages]
    return "\n".join(out) + "\n"


# @sect{The two commands}

def write_pages(root, output):
    existing = source_files(root)
    code_map = (root / "doc" / "code-map.md").read_text()
    names, unknown = resolve_names(code_map, existing)
    pages = reading_order(names, existing)
    problems = [f"doc/code-map.md names `{n}`, which is no file of include/ or source/"
                for n in unknown]
    problems += [f"{p} is not named in doc/code-map.md" for p in sorted(existing - set(pages))]
    notes = []
    written = {"index.md": main_page(code_map, names),
               "reading_order.md": reading_order_page(pages)}
    for i, path in enumerate(pages):
        try:
            page = convert_file(root, path, pages[i - 1] if i > 0 else None,
                                pages[i + 1] if i + 1 < len(pages) else None, notes)
        except ConversionError as error:
            problems.append(str(error))
            continue
        written[page_name(path) + ".md"] = "\n".join(line for line, _ in page) + "\n"
        written[page_name(path) + ".lines"] = (
            path + "\n" + "\n".join(str(number) for _, number in page) + "\n")
    output.mkdir(parents=True, exist_ok=True)
    for stale in list(output.glob("*.md")) + list(output.glob("*.lines")):
        if stale.name not in written:
            stale.unlink()
    for name, text in written.items():
        target = output / name
        if not target.exists() or target.read_text() != text:
            target.write_text(text)
    for note in notes:
        print(f"annotated_source.py: note: {note}", file=sys.stderr)
    for problem in problems:
        print(f"annotated_source.py: error: {problem}", file=sys.stderr)
    return 1 if problems else 0


def source_location(pages, page, number):
    """The source file and line of line `number` of a page, or None."""
    lines = pages / (Path(page).stem + ".lines")
    if not lines.exists():
        return None
    source, *numbers = lines.read_text().split("\n")
    if 1 <= number <= len(numbers) and numbers[number - 1]:
        return f"{source}:{numbers[number - 1]}"
    return None


def latex_errors(pages):
    """The errors in doxygen's LaTeX run of the formulas (html/_formulas.log
    beside the pages), each with the formula and where it is in the source."""
    log, tex = pages.parent / "html" / "_formulas.log", pages.parent / "html" / "_formulas.tex"
    if not log.exists() or not tex.exists():
        return []
    formulas = tex.read_text().split("\n")
    errors = []
    for match in re.finditer(r"^! (.*)$(?:.*\n)*?^l\.(\d+) ", log.read_text(), flags=re.M):
        first = last = int(match.group(2)) - 1
        separators = ("", "\\pagebreak", "\\begin{document}")
        while first > 0 and formulas[first - 1].strip() not in separators:
            first -= 1
        while last + 1 < len(formulas) and formulas[last + 1].strip() not in separators:
            last += 1
        formula = "\n".join(formulas[first:last + 1]).strip()
        body = re.sub(r"^\$|\$$|^\\\[|\\\]$", "", formula).strip()
        where = "a formula"
        for page in sorted(pages.glob("*.md")):
            position = page.read_text().find(body)
            if position >= 0 and body:
                number = page.read_text().count("\n", 0, position) + 1
                where = source_location(pages, page.name, number) or page.name
                break
        errors.append(f"{where}: error: LaTeX: {match.group(1)} in {formula}")
    return errors


def translate_warnings(warnings, pages):
    """Doxygen's warnings, with the source file and line of each page line."""
    text = warnings.read_text() if warnings.exists() else ""
    if not text.strip():
        return 0

    def location(match):
        where = source_location(pages, match.group(1), int(match.group(2)))
        return f"{where}:" if where else match.group(0)
    print(re.sub(r"^(\S+\.md):(\d+):", location, text.rstrip("\n"), flags=re.M),
          file=sys.stderr)
    if "Problems running latex" in text:
        for error in latex_errors(pages):
            print(error, file=sys.stderr)
    return 1


def main():
    arguments = sys.argv[1:]
    if len(arguments) == 3 and arguments[0] == "--warnings":
        sys.exit(translate_warnings(Path(arguments[1]), Path(arguments[2])))
    if len(arguments) == 2 and not arguments[0].startswith("-"):
        sys.exit(write_pages(Path(arguments[0]).resolve(), Path(arguments[1])))
    sys.exit(__doc__)


if __name__ == "__main__":
    main()
