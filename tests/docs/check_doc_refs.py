#!/usr/bin/env python3
"""CTest `doc_refs` (label `docs`): every documentation reference in the code and the docs resolves.

Usage: check_doc_refs.py REPO_ROOT

Checked, in src include tests jobs models slurm waveforms setup.sh CMakeLists.txt README.md docs:
  - paths into the project's docs, `docs/NAME.ext`, and to any Markdown file with a directory
    (`models/library/README.md`): the file exists, from the repository's root or from the citing
    file (`../shared/...` is reference data beside the checkout, never in it, and is not checked);
  - sections, `physics.md §N`, `physics.md N`, `physics.md sections N, M` (likewise hazard.md and
    style.md): docs/NAME.md exists and has a heading numbered N;
  - named sections, `README "Heading"` or `docs/NAME.md, "Heading"`: that heading exists;
  - in Markdown files, relative links and images `[text](path#anchor)`: the path exists and, for a
    Markdown target, the anchor is one of its headings (GitHub's slugs).
Prints one line per broken reference (`FILE:LINE: problem`) and exits 1 if there is any.

Before checking the repository it checks itself: a temporary copy of the docs with one planted
broken reference of each kind must produce exactly those errors, so this test cannot pass by
finding nothing.
"""
import os
import re
import shutil
import sys
import tempfile
from pathlib import Path

SCANNED = ["src", "include", "tests", "jobs", "models", "slurm", "waveforms", "setup.sh",
           "CMakeLists.txt", "README.md", "docs"]
TEXT_SUFFIXES = {".cpp", ".hpp", ".h", ".c", ".py", ".sh", ".toml", ".md", ".txt", ".cmake",
                 ".sbatch", ".cfg", ".in"}
SKIP_DIRS = {"build", ".git", "__pycache__", "data"}  # tests/data: fixtures, not prose
NUMBERED_DOCS = ("physics", "hazard", "style")
SELF = Path(__file__).resolve()
REPO_DIRS = {"docs", "src", "include", "tests", "jobs", "models", "slurm", "waveforms"}

# docs/NAME.ext, and any other path to a Markdown file with a directory (models/library/README.md)
DOC_PATH = re.compile(r"(?<![\w./-])((?:\.\./)*(?:shared/)?docs/[\w./-]*\w\.(?:md|tsv|csv|png|json)"
                      r"|(?:\.\./)*[\w-]+/[\w./-]*\w\.md)(?![\w/])")
# "physics.md §2", "physics.md 11", "physics.md sections 1, 11", across a comment line break
SECTION = re.compile(r"(?<![\w/.-])(?:docs/)?(" + "|".join(NUMBERED_DOCS) + r")\.md"
                     r"(?:[ \t]|\n[ \t]*(?://+|#+|\*|/\*+)?[ \t]*)*"
                     r"(?:(§|sections?|items?)[ \t]*)?(\d+(?:[ \t]*(?:,|and)[ \t]*\d+)*)(?![\d.]*\w)")
NAMED = re.compile(r"(?<![\w/.-])((?:docs/)?[\w-]+\.md|README)[,:]?[ \t]+\"([^\"\n]+)\"")
MD_LINK = re.compile(r"!?\[(?:[^\]\n]|\][^(\n])*\]\(([^)\s]+)\)")
HEADING = re.compile(r"^(#{1,6})[ \t]+(.+?)[ \t]*#*[ \t]*$", re.M)
FENCE = re.compile(r"^```.*?^```[ \t]*$", re.M | re.S)


def slug(heading):
    """GitHub's anchor for a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = re.sub(r"[`*_]|\[([^\]]*)\]\([^)]*\)", lambda m: m.group(1) or "", heading)
    text = text.strip().lower()
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def headings(path):
    """Heading texts and anchors of a Markdown file (code blocks left out)."""
    text = FENCE.sub("", path.read_text(encoding="utf-8", errors="replace"))
    texts, anchors, seen = [], set(), {}
    for m in HEADING.finditer(text):
        texts.append(m.group(2).strip())
        base = slug(m.group(2))
        n = seen.get(base, 0)
        anchors.add(base if n == 0 else f"{base}-{n}")
        seen[base] = n + 1
    return texts, anchors


def scanned_files(root):
    for name in SCANNED:
        p = root / name
        if p.is_file():
            yield p
        elif p.is_dir():
            for dirpath, dirnames, filenames in os.walk(p):
                dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS)
                for f in sorted(filenames):
                    fp = (Path(dirpath) / f).resolve()
                    if fp == SELF:
                        continue  # its own docstring and planted examples
                    if fp.suffix in TEXT_SUFFIXES or f == "CMakeLists.txt":
                        yield fp


def line_of(text, pos):
    return text.count("\n", 0, pos) + 1


def check(root):
    root = root.resolve()
    errors = []
    cache = {}
    counts = {"paths": 0, "sections": 0, "named sections": 0, "links": 0}

    def doc_headings(path):
        if path not in cache:
            cache[path] = headings(path) if path.is_file() else None
        return cache[path]

    for f in scanned_files(root):
        text = f.read_text(encoding="utf-8", errors="replace")
        rel = f.relative_to(root)

        def err(pos, problem):
            errors.append(f"{rel}:{line_of(text, pos)}: {problem}")

        for m in DOC_PATH.finditer(text):
            ref = m.group(1)
            counts["paths"] += 1
            if "shared/" in ref:
                continue  # shared reference data beside the checkout, not in the repository
            first = ref.lstrip("./").split("/")[0]
            if not ref.startswith(("docs/", "../")) and first not in REPO_DIRS:
                continue  # an output path (out/..., DIR/...), not a document of the repository
            # from the repository's root, or from the citing file's directory
            if not ((root / ref).exists() or (f.parent / ref).exists()):
                err(m.start(1), f"{ref} does not exist in the repository")

        for m in SECTION.finditer(text):
            if text[max(0, m.start() - 10):m.start()].endswith("shared/docs/"):
                continue
            counts["sections"] += 1
            doc = root / "docs" / f"{m.group(1)}.md"
            found = doc_headings(doc)
            if found is None:
                err(m.start(), f"docs/{m.group(1)}.md does not exist")
                continue
            numbers = {re.match(r"(\d+)\.", h).group(1) for h in found[0] if re.match(r"\d+\.", h)}
            for n in re.findall(r"\d+", m.group(3)):
                if n not in numbers:
                    err(m.start(), f"{m.group(1)}.md §{n}: no section {n} in docs/{m.group(1)}.md")

        for m in NAMED.finditer(text):
            name, section = m.group(1), m.group(2)
            counts["named sections"] += 1
            if name == "README":
                doc = root / "README.md"
            elif name.startswith("docs/"):
                doc = root / name
            else:
                doc = root / "docs" / name
                if not doc.exists() and (root / name).exists():
                    doc = root / name
            found = doc_headings(doc)
            if found is None:
                err(m.start(), f"{name}: no such document")
            elif not any(h == section or h.startswith(section) or slug(h) == slug(section)
                         for h in found[0]):
                err(m.start(), f"{name}: no section \"{section}\"")

        if f.suffix == ".md":
            body = FENCE.sub(lambda m: "\n" * m.group(0).count("\n"), text)
            for m in MD_LINK.finditer(body):
                url = m.group(1)
                counts["links"] += 1
                if re.match(r"[a-z][a-z0-9+.-]*:", url, re.I):
                    continue  # http:, https:, mailto:
                path, _, anchor = url.partition("#")
                target = (f.parent / path).resolve() if path else f
                if not target.exists():
                    err(m.start(), f"link target {path} does not exist")
                    continue
                if anchor and target.suffix == ".md":
                    if anchor not in doc_headings(target)[1]:
                        err(m.start(), f"link anchor #{anchor} is not a heading of {path or rel.name}")
    check.counts = counts
    return errors


def self_test():
    """A copy of the real docs with one broken reference of each kind planted must fail."""
    here = Path(__file__).resolve().parents[2]
    with tempfile.TemporaryDirectory() as tmp:
        t = Path(tmp)
        shutil.copytree(here / "docs", t / "docs")
        shutil.copy(here / "README.md", t / "README.md")
        (t / "src").mkdir()
        (t / "src" / "planted.cpp").write_text(
            "// ok: physics.md §2, physics.md 11, ../shared/docs/hazard.md §9\n"
            "// broken: physics.md §99 and docs/no_such_page.md\n"
            "// broken: README \"No such section\"\n"
            "// ok: out/plots/table.md; broken: models/no_such/README.md\n", encoding="utf-8")
        (t / "docs" / "planted.md").write_text(
            "# Planted\n\n[ok](physics.md#2-the-rocking-block) [ok](#planted)\n"
            "[broken](no_such.md) [broken](physics.md#no-such-anchor)\n", encoding="utf-8")
        found = check(t)
        expected = ["physics.md §99", "docs/no_such_page.md", "No such section",
                    "models/no_such/README.md", "no_such.md", "#no-such-anchor"]
        planted = [e for e in found if e.startswith(("src/planted.cpp", "docs/planted.md"))]
        missing = [x for x in expected if not any(x in e for e in planted)]
        if missing or len(planted) != len(expected):
            print("self-test failed: the planted broken references gave", planted,
                  "; expected one error for each of", expected, file=sys.stderr)
            return False
    return True


def main():
    if len(sys.argv) != 2:
        print("usage: check_doc_refs.py REPO_ROOT", file=sys.stderr)
        return 2
    if not self_test():
        return 1
    errors = check(Path(sys.argv[1]))
    for e in errors:
        print(e)
    if errors:
        print(f"{len(errors)} documentation reference(s) do not resolve", file=sys.stderr)
        return 1
    print("every documentation reference resolves:",
          ", ".join(f"{n} {k}" for k, n in check.counts.items()))
    return 0


if __name__ == "__main__":
    sys.exit(main())
