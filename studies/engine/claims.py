"""Numbers a reader meets outside the reports: each one either quoted from a report or
checked against the code it comes from.

README.md and the documentation pages (``docs/**/*.md``, the generated results aside) quote
reports between include markers (README: :mod:`.readme`; the site: MyST ``{include}``), which
the audit compares with the reports themselves. Every other number with a unit in their
prose and tables (``160 mm``, ``10 %``, ``0.5 s``, ...) must be listed in
``docs/reference/stated-numbers.toml`` with its source, a Python expression over a module of
this project (``contract.paper:CANTILEVER["length"]``) and the scale from the source's SI
value to the printed one; :func:`problems` names every number that is not listed, and every
listed one whose source no longer gives it (``studies audit`` runs it). Code blocks are the
tutorials' runnable examples, which the tests run.
"""
from __future__ import annotations

import importlib
import math
import re
import tomllib
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LIST = ROOT / "docs" / "reference" / "stated-numbers.toml"
UNITS = ("%", "mm", "ms", "s", "MPa", "kPa", "Pa", "N", "J", "kg", "min", "GiB")
NUMBER = re.compile(r"(?<![\w.])(\d+(?:\.\d+)?(?:e-?\d+)?) ?(%|(?:mm|ms|s|MPa|kPa|Pa|N|J|kg|min|GiB)\b)")


def pages(root: Path = ROOT) -> list[Path]:
    """README.md and the hand-written documentation pages."""
    docs = [p for p in sorted((root / "docs").rglob("*.md"))
            if not {"_build", "generated", "_generated"} & set(p.relative_to(root / "docs").parts)]
    return [root / "README.md", *docs]


def stated(text: str) -> list[tuple[int, str]]:
    """(line, "number unit") of every number with a unit outside code blocks, inline code and
    include blocks."""
    out, fence, quoted = [], False, False
    for i, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if s.startswith(("```", "~~~")):
            fence = not fence
            continue
        if "<!-- include " in line:
            quoted = True
        if "<!-- /include" in line:
            quoted = False
            continue
        if fence or quoted:
            continue
        for m in NUMBER.finditer(re.sub(r"`[^`]*`", "", line)):
            out.append((i, f"{m.group(1)} {m.group(2)}"))
    return out


def _value(source: str):
    module, _, expr = source.partition(":")
    return eval(expr, {}, vars(importlib.import_module(module)))       # a listed expression of our own code


def problems(root: Path = ROOT, listing: Path = LIST) -> list[str]:
    """Unlisted numbers (file:line) and listed ones their source contradicts."""
    listed = {e["text"]: e for e in tomllib.loads(listing.read_text()).get("number", [])} if listing.exists() else {}
    out = []
    for page in pages(root):
        for line, text in stated(page.read_text()):
            if text not in listed:
                out.append(f"{page.relative_to(root)}:{line}: {text!r} is neither quoted from a report nor "
                           f"listed with its source in {listing.relative_to(root)}")
    for text, e in listed.items():
        number = float(text.split()[0])
        try:
            value = _value(e["source"]) * e.get("scale", 1.0)
        except Exception as err:        # a source that no longer exists is a problem, named
            out.append(f"{listing.relative_to(root)}: {text!r}: its source {e['source']!r} fails: {err}")
            continue
        if not math.isclose(value, number, rel_tol=float(e.get("rtol", 1e-12)), abs_tol=1e-12):
            out.append(f"{listing.relative_to(root)}: {text!r}: its source {e['source']!r} gives {value:g}")
    return out
