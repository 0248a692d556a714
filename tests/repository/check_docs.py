#!/usr/bin/env python3
"""Checks the Markdown documentation a reader follows: every relative link and image in README.md
and docs/*.md names a file of the repository, every #anchor a heading of its page (GitHub's
heading ids), and the README stays a five-minute read (at most 300 lines).

    check_docs.py REPOSITORY        exit 1 listing each broken link as FILE:LINE: what
    check_docs.py --self-test       checks the checker on pages made to break it
"""

import pathlib
import re
import sys
import tempfile

LINK = re.compile(r"!?\[(?:[^\]\\]|\\.)*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
README_MAX_LINES = 300


def heading_ids(text):
    """GitHub's ids of a page's headings: lower case, punctuation dropped, spaces to hyphens,
    repeats numbered -1, -2, ..."""
    ids, seen = set(), {}
    for line in strip_code(text, inline=False).splitlines():
        match = re.match(r"#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not match:
            continue
        slug = re.sub(r"[^\w\- ]", "", match.group(1).lower()).replace(" ", "-")
        count = seen.get(slug, 0)
        seen[slug] = count + 1
        ids.add(slug if count == 0 else f"{slug}-{count}")
    return ids


def strip_code(text, inline=True):
    """The text with fenced and indented code blocks (and inline code, when `inline`) blanked, lines
    kept."""
    out, fenced = [], False
    for line in text.splitlines():
        if line.lstrip().startswith("```"):
            fenced = not fenced
            out.append("")
        elif fenced or line.startswith("    ") and not line.lstrip().startswith(("-", "|", "*")):
            out.append("")
        else:
            out.append(re.sub(r"`[^`]*`", "", line) if inline else line)
    return "\n".join(out)


def problems(repository):
    repository = pathlib.Path(repository).resolve()
    pages = [repository / "README.md"] + sorted((repository / "docs").glob("*.md"))
    found = []
    readme_lines = len((repository / "README.md").read_text().splitlines())
    if readme_lines > README_MAX_LINES:
        found.append(f"README.md: {readme_lines} lines, more than {README_MAX_LINES}")
    for page in pages:
        text = page.read_text()
        for number, line in enumerate(strip_code(text).splitlines(), 1):
            for match in LINK.finditer(line):
                target = match.group(1)
                where = f"{page.relative_to(repository)}:{number}: {target}"
                if re.match(r"[a-z]+:", target):
                    continue  # a web address: not checked here (no network)
                path, _, anchor = target.partition("#")
                file = (page.parent / path).resolve() if path else page
                if repository not in file.parents and file != repository:
                    found.append(f"{where}: outside the repository")
                elif not file.exists():
                    found.append(f"{where}: no such file")
                elif anchor and file.suffix == ".md" and anchor not in heading_ids(file.read_text()):
                    found.append(f"{where}: no heading #{anchor} in {file.relative_to(repository)}")
    return found


def self_test():
    with tempfile.TemporaryDirectory() as folder:
        root = pathlib.Path(folder)
        (root / "docs").mkdir()
        (root / "docs" / "a.md").write_text("# Page A\n\n## `fastcorot run`: runs\n\n## Same\n\n## Same\n")
        (root / "README.md").write_text(
            "[ok](docs/a.md) [ok](docs/a.md#fastcorot-run-runs) [ok](docs/a.md#same-1) [ok](#top)\n"
            "# Top\n[web](https://example.org/x) `[code](nowhere.md)`\n\n    [indented](nowhere.md)\n"
            "[missing](docs/b.md)\n![picture](docs/none.png)\n[anchor](docs/a.md#nothing)\n"
            "[outside](../secret.md)\n")
        found = problems(root)
        expected = ["docs/b.md: no such file", "docs/none.png: no such file",
                    "docs/a.md#nothing: no heading #nothing", "../secret.md: outside the repository"]
        missed = [e for e in expected if not any(e in f for f in found)]
        if missed or len(found) != len(expected):
            print("self-test failed: expected", expected, "found", found)
            return 1
        (root / "README.md").write_text("line\n" * (README_MAX_LINES + 1))
        if not any("more than" in f for f in problems(root)):
            print("self-test failed: a long README passed")
            return 1
    print("self-test passed")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    found = problems(argv[1])
    for problem in found:
        print(problem)
    print(f"{len(found)} broken links" if found else "every link resolves")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
