"""The README's generated blocks: a table of a report quoted in the project's README.

A block is ``<!-- include reports/NAME.md -->`` ... ``<!-- /include -->``: the lines between
the markers are the file's content. :func:`refresh` writes them (``studies run`` does, after
rebuilding the reports in ``reports/``; ``make loops`` for its record), :func:`problems`
names a block that differs from its file or quotes a missing one (``studies audit``); an
empty block whose file does not exist yet quotes nothing and passes.
"""
from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
README = ROOT / "README.md"
BLOCK = re.compile(r"(<!-- include (\S+) -->\n)(.*?)(<!-- /include -->)", re.S)


def _content(path: Path) -> str:
    text = path.read_text()
    return text if text.endswith("\n") else text + "\n"


def refresh(readme: Path = README, root: Path = ROOT) -> bool:
    """Rewrite every block of ``readme`` from its file (those whose file exists); True if
    the README changed."""
    text = readme.read_text()

    def sub(m):
        path = root / m.group(2)
        return m.group(1) + (_content(path) if path.exists() else m.group(3)) + m.group(4)

    new = BLOCK.sub(sub, text)
    if new != text:
        readme.write_text(new)
    return new != text


def problems(readme: Path = README, root: Path = ROOT) -> list[str]:
    """Each block that is not its file's content, named by the README's line."""
    text = readme.read_text() if readme.exists() else ""
    out = []
    for m in BLOCK.finditer(text):
        line = text[: m.start()].count("\n") + 1
        path = root / m.group(2)
        if not path.exists():
            if m.group(3).strip():      # an empty block quotes nothing yet
                out.append(f"{readme}:{line}: quotes {m.group(2)}, which is missing")
        elif m.group(3) != _content(path):
            out.append(f"{readme}:{line}: the quote of {m.group(2)} differs from the file (studies run rewrites it)")
    return out
