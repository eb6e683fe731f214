#!/usr/bin/python3
"""Every relative link in the repository's Markdown files points at a file that exists, and a
link with a #fragment at a heading of that file (GitHub's anchor rules: lower case, punctuation
other than '-' and '_' dropped, spaces to '-', a repeated heading gets -1, -2, ...).

Usage: check_markdown_links.py ROOT    check the Markdown files under ROOT (those git tracks)
       check_markdown_links.py --self-test
Prints one line per broken link (file:line: target: what is wrong) and exits 1 if there is one.
"""
import os
import re
import subprocess
import sys
import tempfile

LINK = re.compile(r"(?<!!)\[(?:[^\]\[]|\[[^\]]*\])*\]\(([^)\s]+)(?:\s+\"[^\"]*\")?\)")
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
FENCE = re.compile(r"^\s*(```|~~~)")


def slug(heading):
    """GitHub's anchor of a heading's text (inline code and link markup reduced to their text)."""
    text = re.sub(r"\[([^\]]*)\]\([^)]*\)", r"\1", heading)  # [text](url) -> text
    text = text.replace("`", "").lower()
    text = re.sub(r"[^\w\- ]", "", text)  # \w keeps letters, digits and '_'
    return text.replace(" ", "-")


def anchors(path):
    """The anchors of a Markdown file's headings (outside code fences)."""
    seen, result, fenced = {}, set(), False
    with open(path, encoding="utf-8") as f:
        for line in f:
            if FENCE.match(line):
                fenced = not fenced
                continue
            m = None if fenced else HEADING.match(line)
            if not m:
                continue
            base = slug(m.group(2))
            n = seen.get(base, 0)
            seen[base] = n + 1
            result.add(base if n == 0 else f"{base}-{n}")
    return result


def links(path):
    """(line number, target) of each link outside code fences and inline code."""
    fenced = False
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            if FENCE.match(line):
                fenced = not fenced
                continue
            if fenced:
                continue
            for m in LINK.finditer(re.sub(r"`[^`]*`", "", line)):
                yield number, m.group(1)


def problems(root, files):
    cache = {}
    out = []
    for rel in files:
        path = os.path.join(root, rel)
        for number, target in links(path):
            if re.match(r"^[a-z][a-z0-9+.-]*:", target, re.I):  # http:, https:, mailto:, ...
                continue
            file_part, _, fragment = target.partition("#")
            destination = os.path.normpath(os.path.join(os.path.dirname(path), file_part)) if file_part else path
            if not os.path.exists(destination):
                out.append(f"{rel}:{number}: {target}: no such file")
                continue
            if fragment and destination.endswith(".md"):
                if destination not in cache:
                    cache[destination] = anchors(destination)
                if fragment not in cache[destination]:
                    out.append(f"{rel}:{number}: {target}: no heading with that anchor")
    return out


def markdown_files(root):
    """The Markdown files git tracks under root; outside a git work tree (a source archive), every
    .md file but those of build and run folders."""
    try:
        listed = subprocess.run(["git", "-C", root, "ls-files", "*.md"], capture_output=True, text=True)
        if listed.returncode == 0:
            return [f for f in listed.stdout.splitlines() if f]
    except FileNotFoundError:
        pass
    found = []
    for folder, subfolders, names in os.walk(root):
        subfolders[:] = sorted(s for s in subfolders if not s.startswith((".", "build", "runs")))
        found += [os.path.relpath(os.path.join(folder, n), root) for n in sorted(names) if n.endswith(".md")]
    return found


def self_test():
    with tempfile.TemporaryDirectory() as d:
        with open(os.path.join(d, "a.md"), "w") as f:
            f.write("# Title\n## Run `tfmb-flow` (options, 2)\n## Run `tfmb-flow` (options, 2)\n"
                    "```\n# not a heading\n[x](missing.md)\n```\n"
                    "[ok](b.md) [ok](#title) [ok](#run-tfmb-flow-options-2-1) [ok](https://x.org/#y)\n"
                    "[bad](#not-a-heading) [bad](c.md) [bad](b.md#nowhere) `[code](nowhere.md)`\n")
        with open(os.path.join(d, "b.md"), "w") as f:
            f.write("## Section: one\n[ok](a.md#run-tfmb-flow-options-2) [ok](#section-one)\n")
        found = problems(d, ["a.md", "b.md"])
        expected = ["a.md:9: #not-a-heading: no heading with that anchor",
                    "a.md:9: c.md: no such file",
                    "a.md:9: b.md#nowhere: no heading with that anchor"]
        if found != expected:
            print("check_markdown_links self-test: expected\n  " + "\n  ".join(expected) +
                  "\nfound\n  " + "\n  ".join(found))
            return 1
    print("check_markdown_links self-test: passed")
    return 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) != 2:
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        return 2
    root = argv[1]
    found = problems(root, markdown_files(root))
    for line in found:
        print(line)
    print(f"check_markdown_links: {len(found)} broken link(s)")
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
