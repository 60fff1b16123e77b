#!/usr/bin/env python3
"""Every relative link of docs/**/*.md and README.md resolves: the file
exists and, for a link into a Markdown file, the #anchor is one of its
headings (GitHub's rule: lower case, punctuation other than '-' and '_'
dropped, spaces to '-', repeated headings numbered -1, -2, ...).  Fenced
code blocks are skipped.  Usage: check_doc_links.py [REPO]; exit 1 and one
line per broken link when any is broken (the ctest docs_links)."""
import glob
import os
import re
import sys

FENCE = re.compile(r"```.*?```", re.S)
HEADING = re.compile(r"^(#{1,6})\s+(.*?)\s*#*\s*$")
LINK = re.compile(r"\]\(([^)\s]+)\)")


def anchors(path, cache={}):
    if path not in cache:
        found, seen, fenced = set(), {}, False
        with open(path, encoding="utf-8") as f:
            for line in f:
                if line.startswith("```"):
                    fenced = not fenced
                    continue
                m = None if fenced else HEADING.match(line)
                if not m:
                    continue
                slug = re.sub(r"[^\w\- ]", "", m.group(2).lower()).replace(" ", "-")
                n = seen.get(slug, 0)
                seen[slug] = n + 1
                found.add(slug if n == 0 else f"{slug}-{n}")
        cache[path] = found
    return cache[path]


def main():
    root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..")
    files = sorted(glob.glob(os.path.join(root, "docs", "**", "*.md"), recursive=True))
    files.append(os.path.join(root, "README.md"))
    broken = 0
    for doc in files:
        with open(doc, encoding="utf-8") as f:
            text = FENCE.sub("", f.read())
        for m in LINK.finditer(text):
            link = m.group(1)
            if re.match(r"^[a-z]+:", link):  # http:, https:, mailto:
                continue
            path, _, frag = link.partition("#")
            target = os.path.normpath(os.path.join(os.path.dirname(doc), path)) if path else doc
            where = os.path.relpath(doc, root)
            if not os.path.exists(target):
                print(f"{where}: no file for link {link}")
                broken += 1
            elif frag and target.endswith(".md") and frag not in anchors(target):
                print(f"{where}: no heading for anchor {link}")
                broken += 1
    print(f"check_doc_links: {len(files)} files, {broken} broken links")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
