"""The repository stands alone: every path that a document, comment or docstring names
exists in the repository, every section of docs/model.md that one cites exists, nothing
points outside the repository, and no code or doc narrates history (commit hashes, issue
numbers).

Paths are recognised by their top-level folder (src/, docs/, python/, tests/, scripts/,
examples/, include/, .ci/); a `*` is a glob. Build outputs (target/, out/, .venv/) are not
names of the repository and are not checked.
"""

from __future__ import annotations

import glob
import re
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
TEXT = (".md", ".rs", ".py", ".sh", ".h", ".c", ".toml", ".txt", ".html", ".supp")
PATH = re.compile(
    r"(?<![\w./-])((?:src|docs|python|tests|scripts|examples|include|\.ci)/[\w.*/{},-]*[\w*/}])"
)
#: A section cited with its page: `docs/page.md, "Name"`, `docs/page.md ("Name")`,
#: `section "Name" of docs/page.md` (group 1 the page, 2 the section, or 3 and 4).
SECTION = re.compile(
    r'docs/(\w+\.md)(?:\)|`)?(?:,\s*\(?|\s*\()"([^"]+)"'
    r'|[Ss]ections? "([^"]+)" (?:\(?in\)? )?of `?docs/(\w+\.md)'
)
#: A markdown link to a heading of a page: `[text](page.md#anchor)`.
ANCHOR = re.compile(r"\]\((?:docs/)?(\w+\.md)#([\w-]+)\)")
#: A section of the same page: `see "Name" below` / `above`.
HERE = re.compile(r'"([^"]+)" (?:below|above)\b')
HISTORY = re.compile(
    r"\b(?:[Ii]ssues? \d+|the issue's|[Aa]t [0-9a-f]{7,40}\b|[Oo]n "
    r"[0-9a-f]{7,40}\b|[0-9a-f]{7,40} (?:returned|gave|was|had)\b)"
)
#: Another repository whose paths a comment may cite (with its name on the same line).
EXTERNAL = ("Reference-FMUs",)


def tracked_files() -> list[Path]:
    names = subprocess.run(
        ["git", "ls-files"], cwd=ROOT, capture_output=True, text=True, check=True
    ).stdout
    this = Path(__file__).resolve()
    return [
        ROOT / n
        for n in names.split()
        if (n.endswith(TEXT) or n == ".ci/run") and (ROOT / n).resolve() != this
    ]


def references(text: str):
    for line_no, line in enumerate(text.splitlines(), 1):
        if any(repo in line for repo in EXTERNAL):
            continue
        for m in PATH.finditer(line):
            yield line_no, m.group(1).rstrip(".")


def expand(name: str) -> list[str]:
    """Shell brace expansion of one `{a,b}` group (recursively)."""
    m = re.search(r"\{([^{}]*)\}", name)
    if not m:
        return [name]
    return [
        x
        for alt in m.group(1).split(",")
        for x in expand(name[: m.start()] + alt + name[m.end() :])
    ]


def exists(name: str) -> bool:
    return all(glob.glob(str(ROOT / n)) if "*" in n else (ROOT / n).exists() for n in expand(name))


#: A named item of a list, which a page cites like a section: `2. **Local fits** (...)`.
ITEM = re.compile(r"^(?:\d+\.|-) \*\*([^*]+?)\.?\*\*")


def headings(path: Path) -> set[str]:
    """The headings of a page, and its named list items."""
    lines = path.read_text().splitlines()
    return {line.lstrip("#").strip() for line in lines if line.startswith("#")} | {
        m.group(1) for m in map(ITEM.match, lines) if m
    }


def test_every_named_path_exists():
    missing = []
    for f in tracked_files():
        for line_no, name in references(f.read_text(errors="replace")):
            if not exists(name):
                missing.append(f"{f.relative_to(ROOT)}:{line_no}: {name}")
    assert not missing, "paths named but not in the repository:\n" + "\n".join(missing)


def slug(heading: str) -> str:
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    return re.sub(r"[^\w\- ]", "", heading.lower()).replace(" ", "-")


def cited_sections(f: Path, text: str):
    """(line, page, section, is_anchor) of every section that `f` cites by name or anchor."""
    for line_no, line in enumerate(text.splitlines(), 1):
        for m in SECTION.finditer(line):
            page, name = (m.group(1), m.group(2)) if m.group(1) else (m.group(4), m.group(3))
            yield line_no, page, name, False
        for m in ANCHOR.finditer(line):
            yield line_no, m.group(1), m.group(2), True
        if f.suffix == ".md" and f.parent.name == "docs":
            for m in HERE.finditer(line):
                yield line_no, f.name, m.group(1), False


def test_every_cited_section_lives_on_the_page_named():
    """A section named with a page (`docs/model.md, "Exact results"`, `section "Physical
    units" of docs/model.md`, a link `[x](docs/fitting.md#intervals)`, or on a page of docs/
    `see "Name" below`) is a heading of that page, not of another."""
    missing, cited = [], 0
    for f in tracked_files():
        for line_no, page, name, anchor in cited_sections(f, f.read_text(errors="replace")):
            path = ROOT / "docs" / page
            cited += 1
            heads = headings(path) if path.is_file() else set()
            if (name not in {slug(h) for h in heads}) if anchor else (name not in heads):
                missing.append(
                    f"{f.relative_to(ROOT)}:{line_no}: {name!r} is not a section of docs/{page}"
                )
    assert cited >= 5, f"only {cited} citations of sections found: is the pattern broken?"
    assert not missing, "sections cited but not on the page named:\n" + "\n".join(missing)


def test_nothing_points_outside_the_repository():
    outside = [
        f"{f.relative_to(ROOT)}:{i}"
        for f in tracked_files()
        for i, line in enumerate(f.read_text(errors="replace").splitlines(), 1)
        if "../shared" in line
    ]
    assert not outside, "references outside the repository: " + ", ".join(outside)


def test_no_history_narration():
    found = [
        f"{f.relative_to(ROOT)}:{i}: {line.strip()[:100]}"
        for f in tracked_files()
        for i, line in enumerate(f.read_text(errors="replace").splitlines(), 1)
        if HISTORY.search(line)
    ]
    assert not found, "comments or docs that narrate history:\n" + "\n".join(found)


def test_the_patterns_find_what_they_look_for():
    """The checks above cannot pass vacuously: their patterns match the forms they look for."""
    assert list(references("see `docs/fmi.md` and src/solver/mod.rs.")) == [
        (1, "docs/fmi.md"),
        (1, "src/solver/mod.rs"),
    ]
    assert not exists("docs/no_such_page.md") and not exists("docs/{model,no_such_page}.md")
    assert exists("docs/{model,fmi}.md")
    assert SECTION.search('docs/model.md, "Exact results"').group(1, 2) == (
        "model.md",
        "Exact results",
    )
    assert SECTION.search('(docs/model.md ("Exact results"),').group(2) == "Exact results"
    assert SECTION.search('section "Physical units" of docs/model.md').group(3, 4) == (
        "Physical units",
        "model.md",
    )
    assert not SECTION.search('read_to_string("/docs/fmi.md")).expect("docs/fmi.md")')
    assert "Local fits" in headings(
        ROOT / "docs/fitting.md"
    )  # a named item: `2. **Local fits** (...)`
    fmi = ROOT / "docs/fmi.md"
    assert [c[1:] for c in cited_sections(fmi, 'see "Physical units" below')] == [
        ("fmi.md", "Physical units", False)
    ]
    assert list(cited_sections(fmi, "[x](docs/fitting.md#local-fits)"))[0][1:] == (
        "fitting.md",
        "local-fits",
        True,
    )
    assert "Physical units" not in headings(fmi) and "Physical units" in headings(
        ROOT / "docs/model.md"
    )
    assert (
        HISTORY.search("at 90e9375 it returned")
        and HISTORY.search("issue 3")
        and not HISTORY.search("tissue 3")
    )
    assert HISTORY.search("90e9375 returned a mesh artefact")
