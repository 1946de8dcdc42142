"""Checks of the documentation: README.md and docs/*.md.

    python3 -m pytest -q tests/docs

(a) docs/parameters.md equals what tools/param_reference.py generates from the schema that
    `photon_cli --print-schema` prints (the binary: $PHOTON_CLI, default build/photon_cli;
    skipped when it does not exist);
(b) every relative link and image in README.md and docs/*.md resolves to an existing file, and
    every #anchor to a heading of its target;
(c) the README keeps exactly the two set-up commands, stays within 180 lines and links every
    page of docs/.

Standard library and pytest only; no Blender, no build step.
"""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
README = REPO / "README.md"
DOCS = REPO / "docs"
GENERATOR = REPO / "tools" / "param_reference.py"
PARAMETERS = DOCS / "parameters.md"

README_MAX_LINES = 180
SETUP_COMMANDS = ["./tools/setup_and_demo.sh", "./tools/run_tests.sh"]
SETUP_HEADING = re.compile(r"^##\s+Set up\b")


def markdown_files():
    return [README] + sorted(DOCS.glob("*.md"))


# ---- Markdown parsing: just enough for links and headings ----

FENCE = re.compile(r"^\s*(```|~~~)")


def prose_lines(text):
    """(line number, line) of the lines outside fenced code blocks."""
    in_fence = False
    for number, line in enumerate(text.splitlines(), 1):
        if FENCE.match(line):
            in_fence = not in_fence
            continue
        if not in_fence:
            yield number, line


def fenced_blocks(text):
    """(heading above the block, [lines]) for every fenced code block."""
    blocks, heading, current = [], "", None
    for line in text.splitlines():
        if FENCE.match(line):
            if current is None:
                current = []
            else:
                blocks.append((heading, current))
                current = None
            continue
        if current is not None:
            current.append(line)
        elif line.startswith("#"):
            heading = line
    return blocks


CODE_SPAN = re.compile(r"(`+)(.+?)\1")
INLINE_LINK = re.compile(r"(!?)\[((?:[^\[\]]|\[[^\]]*\])*)\]\(\s*<?([^)\s>]*)>?(?:\s+\"[^\"]*\")?\s*\)")
REFERENCE_DEF = re.compile(r"^\s{0,3}\[[^\]]+\]:\s*<?(\S+?)>?(?:\s+.*)?$")
HTML_TARGET = re.compile(r"<(?:img|a)\b[^>]*?\b(?:src|href)\s*=\s*\"([^\"]+)\"", re.IGNORECASE)


def links(path):
    """(line number, kind, target) of every link and image of a Markdown file."""
    found = []
    for number, line in prose_lines(path.read_text(encoding="utf-8")):
        bare = CODE_SPAN.sub(lambda m: " " * len(m.group(0)), line)
        for m in INLINE_LINK.finditer(bare):
            found.append((number, "image" if m.group(1) else "link", m.group(3)))
        m = REFERENCE_DEF.match(bare)
        if m:
            found.append((number, "link", m.group(1)))
        for m in HTML_TARGET.finditer(bare):
            found.append((number, "html", m.group(1)))
    return found


def slug(heading):
    """GitHub's anchor of a heading: lower case, punctuation dropped, spaces to hyphens."""
    text = heading.strip().lower()
    text = re.sub(r"<[^>]+>", "", text)
    text = re.sub(r"[^\w\- ]", "", text)
    return text.replace(" ", "-")


def anchors(path):
    """Every anchor of a Markdown file: its headings' slugs (numbered when repeated)."""
    seen, result = {}, set()
    for _, line in prose_lines(path.read_text(encoding="utf-8")):
        m = re.match(r"^\s{0,3}#{1,6}\s+(.*?)\s*#*\s*$", line)
        if not m:
            continue
        base = slug(m.group(1))
        count = seen.get(base, 0)
        seen[base] = count + 1
        result.add(base if count == 0 else f"{base}-{count}")
    for _, line in prose_lines(path.read_text(encoding="utf-8")):
        for m in re.finditer(r"<a\s+(?:name|id)\s*=\s*\"([^\"]+)\"", line):
            result.add(m.group(1))
    return result


def is_external(target):
    return re.match(r"^[a-zA-Z][a-zA-Z0-9+.-]*:", target) is not None  # http:, mailto:, ...


def shown(path):
    """A path as messages show it: relative to the repository when inside it."""
    try:
        return str(path.relative_to(REPO))
    except ValueError:
        return str(path)


def broken_links(files):
    """Messages for every relative link or image that does not resolve."""
    problems = []
    for path in files:
        for number, kind, target in links(path):
            where = f"{shown(path)}:{number}"
            if not target:
                problems.append(f"{where}: empty {kind} target")
                continue
            if is_external(target):
                continue
            file_part, _, anchor = target.partition("#")
            resolved = (path.parent / file_part).resolve() if file_part else path
            if not resolved.exists():
                problems.append(f"{where}: {kind} {target!r}: {file_part} does not exist")
                continue
            if anchor:
                if resolved.is_dir() or resolved.suffix.lower() != ".md":
                    problems.append(f"{where}: {kind} {target!r}: anchor into a non-Markdown file")
                elif anchor not in anchors(resolved):
                    problems.append(f"{where}: {kind} {target!r}: no heading #{anchor} in "
                                    f"{shown(resolved)}")
    return problems


# ---- (a) the generated parameter reference ----

def cli_binary():
    path = Path(os.environ.get("PHOTON_CLI", "build/photon_cli"))
    return path if path.is_absolute() else REPO / path


def generate_check(schema_text, parameters):
    """Runs the generator's --check on a schema; returns the process."""
    return subprocess.run(
        [sys.executable, str(GENERATOR), "--schema", "-", "--out", str(parameters), "--check"],
        input=schema_text, capture_output=True, text=True, timeout=60)


@pytest.fixture(scope="module")
def schema_text():
    cli = cli_binary()
    if not cli.exists():
        pytest.skip(f"no photon_cli at {cli} (set PHOTON_CLI or build the photon_cli target): "
                    "the parameter reference is not checked")
    proc = subprocess.run([str(cli), "--print-schema"], capture_output=True, text=True,
                          timeout=60)
    assert proc.returncode == 0, f"{cli} --print-schema failed:\n{proc.stderr}"
    return proc.stdout


def test_parameter_reference_is_up_to_date(schema_text):
    proc = generate_check(schema_text, PARAMETERS)
    assert proc.returncode == 0, (
        "docs/parameters.md differs from the schema of photon_cli --print-schema; regenerate it:\n"
        "  build/photon_cli --write-schema /tmp/schema.json\n"
        "  python3 tools/param_reference.py --schema /tmp/schema.json --out docs/parameters.md\n"
        f"{proc.stdout}{proc.stderr}")


def test_parameter_reference_check_fails_on_a_stale_file(schema_text, tmp_path):
    stale = tmp_path / "parameters.md"
    stale.write_text(PARAMETERS.read_text(encoding="utf-8").replace("scene.photon", "scene.old", 1),
                     encoding="utf-8")
    proc = generate_check(schema_text, stale)
    assert proc.returncode == 1 and "scene.old" in proc.stdout, proc.stdout + proc.stderr


def test_parameter_reference_lists_every_parameter(schema_text):
    import json
    text = PARAMETERS.read_text(encoding="utf-8")
    for group in json.loads(schema_text):
        for p in group["params"]:
            assert f"`{p['name']}`" in text, p["name"]
            assert "--" + p["name"].replace("_", "-") in text, p["name"]


# ---- (b) links and images ----

def test_every_relative_link_and_image_resolves():
    problems = broken_links(markdown_files())
    assert not problems, "broken links:\n" + "\n".join(problems)


def test_link_checker_sees_broken_links(tmp_path):
    page = DOCS / "architecture.md"  # a real page as the anchor target
    probe = tmp_path / "probe.md"
    probe.write_text(
        "# Probe\n\n"
        "[missing](no_such_page.md) ![missing](no_such.png) "
        f"[bad anchor]({page}#no-such-heading) [good anchor]({page}#the-parameter-schema) "
        "[self](#probe) [self bad](#nope) [web](https://example.com/x.md)\n\n"
        "```\n[in code](not_checked.md)\n```\n", encoding="utf-8")
    problems = broken_links([probe])
    text = "\n".join(problems)
    assert len(problems) == 4, text
    for expected in ("no_such_page.md", "no_such.png", "#no-such-heading", "#nope"):
        assert expected in text


# ---- (c) the README ----

def test_readme_is_short():
    lines = README.read_text(encoding="utf-8").splitlines()
    assert len(lines) <= README_MAX_LINES, (
        f"README.md has {len(lines)} lines; keep it within {README_MAX_LINES} and move detail "
        "into docs/")


def setup_commands(text):
    """The commands of the README's set-up section, and every ./tools/ command in its code."""
    in_setup = [line.strip() for heading, block in fenced_blocks(text)
                if SETUP_HEADING.match(heading) for line in block if line.strip()]
    tools = [line.strip() for _, block in fenced_blocks(text) for line in block
             if line.strip().startswith("./tools/")]
    return in_setup, tools


def test_readme_keeps_exactly_the_two_setup_commands():
    in_setup, tools = setup_commands(README.read_text(encoding="utf-8"))
    assert in_setup == SETUP_COMMANDS, (
        f"the README's set-up section must hold exactly {SETUP_COMMANDS}, found {in_setup}")
    assert tools == SETUP_COMMANDS, (
        f"the README's code blocks must run exactly {SETUP_COMMANDS} from tools/, found {tools}")


def test_readme_links_every_docs_page():
    linked = {(README.parent / target.partition("#")[0]).resolve()
              for _, kind, target in links(README) if kind == "link" and not is_external(target)}
    unlinked = [p.name for p in sorted(DOCS.glob("*.md")) if p.resolve() not in linked]
    assert not unlinked, f"README.md links no docs page for: {', '.join(unlinked)}"
