"""Comparisons in words that a reader meets outside the reports, each checked against the
reports it compares.

A number on the pages is checked by :mod:`.claims`; a sentence such as "the plane-stress
plateaus lie above the plane-strain ones" or "the same amount for every element" has no
number, and the records can contradict it all the same. ``docs/reference/stated-comparisons.toml``
lists every such fragment of README.md and the documentation pages (``page``, ``text``:
the fragment as written, line breaks aside) with a check of one of four kinds over values
read from the reports (a table of a report's ``.csv`` or ``.md`` file, or of every card)
or from the code (a Python expression, as in ``stated-numbers.toml``):

``above``
    every value of ``a`` exceeds ``factor`` (default 1) times the value of ``b`` with the
    same key ("lies above", "converges more slowly", "far more than");
``same``
    the values of ``values`` spread by at most ``tol`` in each column ("by the same amount
    for every element"), or each value of ``a`` lies within ``tol`` of the value of ``b``
    with its key ("prints as the paper's"); a key named in ``except`` must break it;
``least``
    in each group (the key but its last part) the smallest value is the one whose last key
    part is ``expect`` ("the cheapest", "closest to");
``every``
    every value holds ``op`` ``bound`` (``<``, ``<=``, ``>``, ``>=``, ``==``, or ``has`` /
    ``lacks`` a regular expression) but those whose key an ``except`` entry names, each of
    which must fail it at least once ("every default passes but ...").

A selector reads ``table`` (a path under the project, a glob for the cards, narrowed by
``stems`` or ``skip``), keeps the ``rows`` whose columns equal a value, one of a list, or
match ``"/regex/"`` (its groups join the key), and takes the ``columns`` (named in keys by
``as``) keyed by the file's stem (a glob), the ``key`` columns and the regex groups;
``reduce`` (max, min, absmax) folds rows with one key. A value of ``source`` is a Python
expression over a module (``module:expression``): a number, or a dict keyed by names.

A fragment comparing results may also be held by a test (``[[tested]]``: the tests it
names must exist), or be no comparison of results at all (``[[not_a_comparison]]``, with
``why``: "the table above"). :func:`problems` names every listed fragment that its page no
longer has, every check the reports contradict, and every comparison word (``KEYWORDS``)
in a sentence that names a subject the reports measure (:func:`subjects`: an element with a
card, a formulation, a law, a continuum, ...) that no listed fragment covers; ``studies
audit`` runs it beside :func:`.claims.problems`. The scan sees the words it knows: a
comparison put otherwise ("differ", "twice") or about no named subject passes unseen, so
the list of words grows with the pages; words that compare nothing on these pages ("the
table above") are listed once as such rather than left out of the scan.
"""
from __future__ import annotations

import ast
import csv
import importlib
import re
import tomllib
from pathlib import Path

from .claims import ROOT, pages

LIST = ROOT / "docs" / "reference" / "stated-comparisons.toml"

KEYWORDS = re.compile(
    r"\b(above|below|higher|lower|larger|smaller|more slowly|slower|faster|cheapest|cheaper|dearer|"
    r"closest|closer|nearest|next to|close to|far from|same amount|same for every|the same as|the same value|"
    r"as the paper's|stiffer|softer|more than|less than|fewer than|exceeds?|for every (?:law|element|formulation)|"
    r"every default|matches|agrees?)\b", re.I)
_FIXED_SUBJECTS = (r"elements?|cells?|rows?|plateaus?|defaults?|rules?|plane[ -]strain|plane[ -]stress|`paper`|"
                   r"neo-Hookean|Mooney-Rivlin|Yeoh|ABAQUS|continuum|3D beam")


def subjects(root: Path = ROOT) -> re.Pattern:
    """What the reports measure: every element with a card, and the formulations, laws and
    models they compare."""
    names = sorted((p.stem for p in (root / "reports" / "cards").glob("*.md")), key=len, reverse=True)
    return re.compile(r"(?<![\w-])(" + "|".join([*map(re.escape, names), _FIXED_SUBJECTS]) + r")(?![\w])", re.I)


# -- the pages' prose ----------------------------------------------------------------------

def prose(text: str) -> tuple[str, list[int], list[tuple[int, int]]]:
    """The page's prose, paragraph by paragraph (one per line of a table) with each
    paragraph's whitespace collapsed, code and include blocks left out; the source line of
    each of its characters; and the spans of its sentences (a paragraph split after . ; :
    ! ? before a space)."""
    paras, cur, fence, quoted = [], [], False, False
    for i, line in enumerate(text.splitlines(), 1):
        s = line.strip()
        if s.startswith(("```", "~~~")):
            fence = not fence
        elif "<!-- include " in line:
            quoted = True
        elif "<!-- /include" in line:
            quoted = False
        elif not (fence or quoted or not s):
            if s.startswith("|"):
                paras += [cur, [(i, s)]]
                cur = []
            else:
                cur.append((i, " ".join(s.split())))
            continue
        paras.append(cur)
        cur = []
    paras.append(cur)
    body, lines, spans = [], [], []
    for para in filter(None, paras):
        if body:
            body.append("\n")
            lines.append(para[0][0])
        start = sum(map(len, body))
        for k, (i, s) in enumerate(para):
            piece = (" " if k else "") + s
            body.append(piece)
            lines += [i] * len(piece)
        text_ = "".join(body)[start:]
        a = 0
        for m in re.finditer(r"[.;:!?](?=\s)", text_):
            spans.append((start + a, start + m.end()))
            a = m.end() + 1
        spans.append((start + a, start + len(text_)))
    return "".join(body), lines, [(a, b) for a, b in spans if b > a]


# -- values from the reports and the code -------------------------------------------------

def _cell(v: str):
    """A table cell as a number where it is one ("0.362 %", "+0.57", "**12**"), else its text."""
    t = v.strip().replace("**", "").strip()
    m = re.fullmatch(r"([+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:e[+-]?\d+)?)\s*%?", t, re.I)
    return float(m.group(1)) if m else t


def _md_tables(text: str) -> list[tuple[list[str], list[list[str]]]]:
    tables, block = [], []
    for line in [*text.splitlines(), ""]:
        if line.startswith("|"):
            block.append([c.strip().replace("\\|", "|") for c in re.split(r"(?<!\\)\|", line.strip()[1:-1])])
        elif block:
            if len(block) > 1:
                tables.append((block[0], block[2:]))
            block = []
    return tables


def _rows(path: Path, need: set[str]) -> list[dict]:
    """The rows of a report's CSV file, or of the first table of a Markdown file that has
    every column named in ``need``."""
    if path.suffix == ".csv":
        with path.open(newline="") as f:
            rows = list(csv.DictReader(f))
        if rows and not need <= set(rows[0]):
            raise KeyError(f"{path.name} has no column {sorted(need - set(rows[0]))}")
        return rows
    for header, body in _md_tables(path.read_text()):
        if need <= set(header):
            return [dict(zip(header, r)) for r in body]
    raise KeyError(f"{path.name} has no table with the columns {sorted(need)}")


def source_value(source: str):
    """A listed Python expression over a module of this project (``module:expression``)."""
    module, _, expr = source.partition(":")
    return eval(expr, dict(vars(importlib.import_module(module))))    # a listed expression of our own code


def _match(spec, cell: str):
    """Does a cell pass a row filter? Returns the regex's groups (a tuple) or None."""
    if isinstance(spec, str) and len(spec) > 1 and spec.startswith("/") and spec.endswith("/"):
        m = re.search(spec[1:-1], cell)
        return m.groups() if m else None
    if isinstance(spec, list):
        return () if cell in map(str, spec) else None
    return () if cell == str(spec) else None


REDUCE = {"max": max, "min": min, "absmax": lambda v: max(v, key=abs)}


def select(spec: dict, root: Path = ROOT) -> tuple[dict[tuple, object], int]:
    """The values a selector names, keyed, and how many columns it takes."""
    if "source" in spec:
        v = source_value(spec["source"])
        if isinstance(v, dict):
            return {tuple(map(str, k)) if isinstance(k, tuple) else (str(k),): x for k, x in v.items()}, 1
        return {(): v}, 1
    table = spec["table"]
    glob = any(c in table for c in "*?[")
    files = sorted(root.glob(table)) if glob else [root / table]
    files = [f for f in files if f.stem in spec.get("stems", [f.stem]) and f.stem not in spec.get("skip", [])]
    if not files:
        raise FileNotFoundError(f"no file {table}")
    columns, keys, filters = list(spec["columns"]), list(spec.get("key", [])), dict(spec.get("rows", {}))
    names = list(spec.get("as", columns))
    found: dict[tuple, list] = {}
    for f in files:
        for row in _rows(f, {*columns, *keys, *filters}):
            groups = [_match(want, row[col]) for col, want in filters.items()]
            if any(g is None for g in groups):
                continue
            base = ((f.stem,) if glob else ()) + tuple(row[k] for k in keys) + tuple(x for g in groups for x in g)
            for c, name in zip(columns, names):
                found.setdefault(base + ((name,) if len(columns) > 1 else ()), []).append(_cell(row[c]))
    how = spec.get("reduce")
    if how is None and any(len(v) > 1 for v in found.values()):
        k = next(k for k, v in found.items() if len(v) > 1)
        raise ValueError(f"key {'/'.join(k)} names {len(found[k])} rows (give more key columns, or reduce)")
    return {k: REDUCE[how](v) if how else v[0] for k, v in found.items()}, len(columns)


def _name(key: tuple) -> str:
    return "/".join(key) or "the value"


def _named(key: tuple, entries) -> str | None:
    """The ``except`` entry that names a key (the key itself or a leading part of it)."""
    s = _name(key)
    return next((e for e in entries if s == e or s.startswith(e + "/")), None)


def _num(v, key) -> float:
    if isinstance(v, (int, float)) and not isinstance(v, bool):
        return float(v)
    raise ValueError(f"{_name(key)}: {v!r} is not a number")


# -- the four kinds ------------------------------------------------------------------------

def _above(e: dict, root: Path) -> list[str]:
    a, _ = select(e["a"], root)
    b, _ = select(e["b"], root)
    factor, absolute = float(e.get("factor", 1.0)), e.get("abs", False)
    both = sorted(a.keys() & b.keys())
    if not both:
        return [f"no key is on both sides (a: {', '.join(map(_name, a)) or '-'}; b: {', '.join(map(_name, b)) or '-'})"]
    out = []
    for k in both:
        x, y = _num(a[k], k), _num(b[k], k)
        if absolute:
            x, y = abs(x), abs(y)
        if not x > factor * y:
            out.append(f"{_name(k)}: {x:g} is not above " + (f"{factor:g} x " if factor != 1 else "") + f"{y:g}")
    return out


def _same(e: dict, root: Path) -> list[str]:
    tol, excepted, out = float(e["tol"]), list(e.get("except", [])), []
    if "values" in e:
        vals, ncol = select(e["values"], root)
        column = (lambda k: k[-1]) if ncol > 1 else (lambda k: "")
        groups: dict[str, dict] = {}
        for k, v in vals.items():
            groups.setdefault(column(k), {})[k] = _num(v, k)
        for c, g in groups.items():
            kept = [v for k, v in g.items() if not _named(k, excepted)]
            if len(kept) < 2:
                out.append(f"{c or 'the values'}: fewer than two values to compare")
                continue
            if max(kept) - min(kept) > tol:
                out.append(f"{c + ': ' if c else ''}spread {max(kept) - min(kept):g} > {tol:g}")
        for x in excepted:
            broken = any(max(kept := [v for k, v in g.items() if not _named(k, excepted) or _named(k, [x])])
                         - min(kept) > tol for g in groups.values() if any(_named(k, [x]) for k in g))
            if not broken:
                out.append(f"{x}: named as an exception, but with it the spread stays within {tol:g}")
        return out
    a, _ = select(e["a"], root)
    b, _ = select(e["b"], root)
    both = sorted(a.keys() & b.keys())
    if not both:
        return ["no key is on both sides"]
    for k in both:
        d = abs(_num(a[k], k) - _num(b[k], k))
        if d > tol and not _named(k, excepted):
            out.append(f"{_name(k)}: {a[k]:g} and {b[k]:g} differ by {d:g} > {tol:g}")
    for x in excepted:
        if not any(_named(k, [x]) and abs(_num(a[k], k) - _num(b[k], k)) > tol for k in both):
            out.append(f"{x}: named as an exception, but it is within {tol:g}")
    return out


def _least(e: dict, root: Path) -> list[str]:
    vals, _ = select(e["values"], root)
    groups: dict[tuple, dict] = {}
    for k, v in vals.items():
        groups.setdefault(k[:-1], {})[k[-1] if k else ""] = _num(v, k)
    out, want = [], str(e["expect"])
    for g, cand in sorted(groups.items()):
        low = min(cand, key=cand.get)
        if want not in cand:
            out.append(f"{_name(g)}: no candidate {want!r} (candidates: {', '.join(cand)})")
        elif cand[want] > cand[low]:
            out.append(f"{_name(g) + ': ' if g else ''}the least is {low} ({cand[low]:g}), not {want} ({cand[want]:g})")
    return out or ([] if groups else ["no values"])


OPS = {"<": lambda x, b: x < b, "<=": lambda x, b: x <= b, ">": lambda x, b: x > b, ">=": lambda x, b: x >= b,
       "==": lambda x, b: x == b}


def _every(e: dict, root: Path) -> list[str]:
    vals, _ = select(e["values"], root)
    op, bound, excepted = e["op"], e["bound"], list(e.get("except", []))
    if isinstance(bound, str) and op in OPS:
        bound = float(source_value(bound)) * float(e.get("scale", 1.0))
    if op in ("has", "lacks"):
        def holds(k, v):
            return (re.search(bound, str(v)) is not None) == (op == "has")
    else:
        def holds(k, v):
            x = _num(v, k)
            return OPS[op](abs(x) if e.get("abs") else x, bound)
    if not vals:
        return ["no values"]
    fails = [k for k, v in vals.items() if not holds(k, v)]
    out = [f"{_name(k)}: {vals[k]!r} does not hold {'|x| ' if e.get('abs') else ''}{op} {bound!r}"
           for k in fails if not _named(k, excepted)]
    out += [f"{x}: named as an exception, but every value of it holds {op} {bound!r}"
            for x in excepted if not any(_named(k, [x]) for k in fails)]
    return out


KINDS = {"above": _above, "same": _same, "least": _least, "every": _every}


def _tests_missing(e: dict, root: Path) -> list[str]:
    out = []
    for t in e.get("tests", []):
        path, _, name = t.partition("::")
        f = root / path
        defined = ({n.name for n in ast.walk(ast.parse(f.read_text())) if isinstance(n, ast.FunctionDef)}
                   if f.exists() else set())
        if name.split("[")[0] not in defined:
            out.append(f"its test {t} does not exist")
    return out or ([] if e.get("tests") else ["it names no test"])


# -- the audit -----------------------------------------------------------------------------

def _short(s: str) -> str:
    return repr(s if len(s) <= 90 else s[:87] + "...")


def problems(root: Path = ROOT, listing: Path = LIST) -> list[str]:
    """Listed fragments their page no longer has, checks the reports contradict, and
    comparison words on the pages that no entry covers (file:line each)."""
    data = tomllib.loads(listing.read_text()) if listing.exists() else {}
    where_list = listing.relative_to(root) if listing.is_relative_to(root) else listing
    texts = {p.relative_to(root).as_posix(): prose(p.read_text()) for p in pages(root)}
    covered: dict[str, list[tuple[int, int]]] = {}
    out = []
    for group in ("comparison", "tested", "not_a_comparison"):
        for e in data.get(group, []):
            page, frag = e.get("page", ""), " ".join(e.get("text", "").split())
            if page not in texts:
                out.append(f"{where_list}: {_short(frag)}: {page!r} is not one of the pages checked")
                continue
            body, lines, _ = texts[page]
            at = [m.start() for m in re.finditer(re.escape(frag), body)] if frag else []
            if not at:
                out.append(f"{where_list}: {page}: {_short(frag)} is no longer on the page")
                continue
            covered.setdefault(page, []).extend((s, s + len(frag)) for s in at)
            where = f"{page}:{lines[at[0]]}: {_short(frag)}"
            if group == "comparison":
                kind = e.get("kind")
                if kind not in KINDS:
                    out.append(f"{where}: unknown kind {kind!r} (one of {', '.join(KINDS)})")
                    continue
                try:
                    found = KINDS[kind](e, root)
                except Exception as err:           # a check that cannot be read is a problem, named
                    found = [f"cannot be checked: {type(err).__name__}: {err}"]
                out += [f"{where}: {kind}: {d}" for d in found]
            elif group == "tested":
                out += [f"{where}: {d}" for d in _tests_missing(e, root)]
            elif not e.get("why"):
                out.append(f"{where}: listed as no comparison, without a why")
    subject = subjects(root)
    for page, (body, lines, spans) in texts.items():
        for a, b in spans:
            unit = body[a:b]
            if not subject.search(unit):
                continue
            for m in KEYWORDS.finditer(unit):
                s, t = a + m.start(), a + m.end()
                if not any(x <= s and t <= y for x, y in covered.get(page, [])):
                    out.append(f"{page}:{lines[s]}: {m.group(0)!r} compares in words, in a fragment {where_list} "
                               f"does not list: {_short(unit)}")
    return out
