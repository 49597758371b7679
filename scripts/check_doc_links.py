#!/usr/bin/env python3
"""Checks that the documentation works from a fresh clone (issue 15).

Usage: scripts/check_doc_links.py [REPO]   (default: the repository holding this script)

Over README.md and docs/**/*.md of REPO:
- every Markdown link and image ([text](target), ![alt](target), [id]: target, and HTML
  <a href>/<img src>) that is not http(s)/mailto must resolve, relative to the document, to a file
  (or a folder holding files) tracked by git, inside the repository;
- a #anchor must name a heading of the target Markdown file (GitHub's heading ids);
- no document may mention a path into ../shared or /work, which only the authors' machine has.
Prints one "file:line: problem" per finding; exits 1 if there is any, 0 otherwise.
"""
import os
import re
import subprocess
import sys
import urllib.parse

FENCE = re.compile(r"^ {0,3}(`{3,}|~{3,})")
CODE_SPAN = re.compile(r"(`+)(.+?)\1", re.S)
INLINE = re.compile(
    r"(!?)\[((?:[^\[\]]|\[[^\[\]]*\])*)\]"                 # [text] or ![alt], one level of nesting
    r"\(\s*(<[^>\n]*>|[^\s()]*(?:\([^\s()]*\)[^\s()]*)*)"   # (target or (<target>
    r"(?:\s+(?:\"[^\"]*\"|'[^']*'|\([^)]*\)))?\s*\)")       # optional "title")
REFERENCE = re.compile(r"^ {0,3}\[([^\]]+)\]:\s*(<[^>\n]*>|\S+)", re.M)
HTML = re.compile(r"<(?:a|img)\b[^>]*?\b(?:href|src)\s*=\s*(\"[^\"]*\"|'[^']*')", re.I)
FORBIDDEN = re.compile(r"(?:(?:\.\./)+shared\b|(?<![\w.~$-])/work(?:/|\b)|\bshared/(?:specs|seeds|hooks|CONVENTIONS))"
                       r"[^\s`'\"()<>\[\],;]*")
HEADING = re.compile(r"^ {0,3}(#{1,6})[ \t]+(.*?)(?:[ \t]+#+)?[ \t]*$")


def strip_fences(text):
    """The text with fenced code blocks blanked (line numbers kept)."""
    out, fence = [], None
    for line in text.split("\n"):
        m = FENCE.match(line)
        if fence:
            if m and m.group(1)[0] == fence[0] and len(m.group(1)) >= len(fence):
                fence = None
            out.append("")
        elif m:
            fence = m.group(1)
            out.append("")
        else:
            out.append(line)
    return "\n".join(out)


def strip_code(text):
    """The text with fenced blocks blanked and code spans replaced by a placeholder (same lines)."""
    return CODE_SPAN.sub(lambda m: "CODE" + "\n" * m.group(0).count("\n"), strip_fences(text))


def heading_ids(text):
    """GitHub's ids of the document's headings (ATX and setext), duplicates suffixed -1, -2 ..."""
    lines = strip_fences(text).split("\n")
    titles = []
    for i, line in enumerate(lines):
        m = HEADING.match(line)
        if m:
            titles.append(m.group(2))
        elif i > 0 and re.match(r"^ {0,3}(=+|-+)[ \t]*$", line) and lines[i - 1].strip() \
                and not lines[i - 1].lstrip().startswith(("|", "-", "*", "#", ">")):
            titles.append(lines[i - 1].strip())
    ids, seen = set(), {}
    for title in titles:
        title = re.sub(r"!?\[([^\]]*)\]\([^)]*\)", r"\1", title)   # links and images: their text
        title = re.sub(r"<[^>]+>", "", title)                       # inline HTML
        slug = re.sub(r"[^\w\- ]", "", title.strip().lower()).replace(" ", "-")
        n = seen.get(slug, 0)
        seen[slug] = n + 1
        ids.add(slug if n == 0 else "%s-%d" % (slug, n))
    return ids


def tracked_files(repo):
    try:
        out = subprocess.run(["git", "-C", repo, "ls-files", "-z"], check=True,
                             capture_output=True).stdout.decode()
    except (OSError, subprocess.CalledProcessError):
        sys.exit("check_doc_links: '%s' is not a git checkout; the links must resolve to tracked files" % repo)
    files = {f for f in out.split("\0") if f}
    folders = set()
    for f in files:
        parts = f.split("/")[:-1]
        for i in range(1, len(parts) + 1):
            folders.add("/".join(parts[:i]))
    return files, folders


def documents(repo):
    docs = ["README.md"] if os.path.isfile(os.path.join(repo, "README.md")) else []
    for root, dirs, names in os.walk(os.path.join(repo, "docs")):
        dirs.sort()
        for name in sorted(names):
            if name.endswith(".md"):
                docs.append(os.path.relpath(os.path.join(root, name), repo).replace(os.sep, "/"))
    return docs


def links(text):
    """(line, target) of every link and image outside code."""
    clean = strip_code(text)
    found = []
    for m in INLINE.finditer(clean):
        found.append((m.start(3), m.group(3)))
    for m in REFERENCE.finditer(clean):
        found.append((m.start(2), m.group(2)))
    for m in HTML.finditer(clean):
        found.append((m.start(1), m.group(1)[1:-1]))
    return sorted((clean.count("\n", 0, pos) + 1, target.strip("<>")) for pos, target in found)


def check(repo):
    files, folders = tracked_files(repo)
    problems = []
    ids_cache = {}

    def ids_of(path):
        if path not in ids_cache:
            with open(os.path.join(repo, path), encoding="utf-8") as f:
                ids_cache[path] = heading_ids(f.read())
        return ids_cache[path]

    for doc in documents(repo):
        found = []
        with open(os.path.join(repo, doc), encoding="utf-8") as f:
            text = f.read()
        for m in FORBIDDEN.finditer(text):
            line = text.count("\n", 0, m.start()) + 1
            found.append((line, "%s:%d: mentions '%s', a path outside the repository" % (doc, line, m.group(0))))
        for line, target in links(text):
            problem = link_problem(repo, doc, target, files, folders, ids_of)
            if problem:
                found.append((line, "%s:%d: link '%s'%s" % (doc, line, target, problem)))
        problems += [p for _, p in sorted(found, key=lambda f: f[0])]
    return problems


def link_problem(repo, doc, target, files, folders, ids_of):
    """Why a link target of doc does not resolve in a fresh clone (a phrase), or None."""
    if re.match(r"(?i)(https?|mailto):", target):
        return None
    if re.match(r"[A-Za-z][A-Za-z0-9+.-]*:", target):
        return " uses a scheme other than http(s)/mailto"
    if target == "":
        return " is empty"
    path, _, anchor = target.partition("#")
    path = urllib.parse.unquote(path.split("?")[0])
    if path.startswith("/"):
        return " is absolute; make it relative to " + doc
    resolved = os.path.normpath(os.path.join(os.path.dirname(doc), path)).replace(os.sep, "/") if path else doc
    if resolved == ".." or resolved.startswith("../"):
        return " leaves the repository"
    if resolved not in files and resolved not in folders:
        if os.path.exists(os.path.join(repo, resolved)):
            return ": '%s' exists but is not tracked by git" % resolved
        return ": '%s' does not exist" % resolved
    if anchor and resolved.endswith(".md") and resolved in files:
        if urllib.parse.unquote(anchor).lower() not in ids_of(resolved):
            return ": '%s' has no heading with id '#%s'" % (resolved, anchor)
    return None


def main():
    repo = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
    problems = check(os.path.abspath(repo))
    for p in problems:
        print(p)
    if problems:
        print("%d problem(s) in README.md and docs/*.md" % len(problems), file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
