"""The benchmark suite's rows, from its records alone (:mod:`studies.verification.benchmarks`
draws its report from them; :mod:`studies.external.verdicts` judges an external solver's
records by them): each case with its reference, kind and source, tolerance and why, the
measured value, its error and verdict, and the cause of a miss (:class:`Row`)."""
from __future__ import annotations

import math
import re
from dataclasses import dataclass

from ancf.elements import ELEMENTS

from .benchmark_causes import cause_of
from .benchmark_scenes import (NEWTON_TOL, STRIP, _solvers, arc_departure, bending_scene, bending_tolerance, constants,
                               elastica_tolerance, mu_of, tension_reference, timoshenko_reference)
from .closed_forms import (MATTIASSON_1981, MATTIASSON_1981_DIGITS, elastica_end_moment, elastica_tip_load,
                           simple_shear_stress)


@dataclass
class Row:
    case: str
    solver: str
    quantity: str
    reference: float | None
    kind: str
    source: str
    tolerance: float
    why: str
    value: float | None
    note: str = ""
    cause: str = ""     # why a miss misses (measured: :data:`CAUSES`, or from the records), "" if unknown

    @property
    def error(self) -> float | None:
        """|value - reference| relative to the reference (absolute where it is 0)."""
        if self.value is None or self.reference is None:
            return None
        return abs(self.value - self.reference) / (abs(self.reference) if self.reference else 1.0)

    @property
    def verdict(self) -> str:
        if self.value is None:
            return "no result"
        return "pass" if self.error <= self.tolerance else "FAIL"


OGDEN = "Ogden 1984, Non-linear elastic deformations, sec. 7.2.2"


SOURCES = {
    "tension": ("closed form", OGDEN),
    "shear": ("closed form", "Ogden 1984, sec. 5.3 (simple shear)"),
    "elastica": ("closed form", "Bisshopp & Drucker 1945, Q. Appl. Math. 3(3) 272-275 (elliptic integrals)"),
    "timoshenko": ("closed form", "Timoshenko & Gere 1972, Mechanics of Materials: q L^4 / 8 EI + q L^2 / 2 kappa G A"),
    "bending plane-strain": ("closed form", "Rivlin 1949, Proc. R. Soc. A 195, 463-473 (flexure); Ogden 1984, sec. 5.2"),
    "bending plane-stress": ("closed form (ODE)", "the same flexure for a plane-stress strip: a two-point problem "
                                                  "across the thickness, shot to round-off (closed_forms)"),
    "arc": ("closed form", "Euler's elastica under an end couple: x/L = sin(phi)/phi, y/L = (1 - cos phi)/phi"),
}


NONCONFORMING = ("HB2n-12", "HB3n-12")


# why a cable misses the finite-strain bending: a model error, not a discretisation one
CABLE_BENDING = ("a cable's fibres are in uniaxial stress (no radial stress, eta = Y): its M(kappa) lies above "
                 "the exact strip's by a model error of order (kappa h)^2 (0.225 (kappa h)^2 neo-Hookean and Yeoh, "
                 "0.245 Mooney-Rivlin: its card, 1b), so its kappa that much below")


def _is_cable(solver: str) -> bool:
    return solver in ELEMENTS and (not ELEMENTS[solver].family.section_field)


def _solver_of(rec: dict) -> str:
    """The continuum backend that ran (the record's label), or the ANCF element."""
    return rec["solver"] if "fem" in rec["scene"] else rec["scene"]["ancf"]["element"]


def rows(ctx) -> list[Row]:
    g = ctx.study.grid
    out = []
    for r in ctx.records():
        s, name = r["scene"], r["scene"]["name"]
        ok = r.get("status") == "converged"
        if name.startswith("bench-tension-"):
            law, form = s["material"]["law"], s["material"]["formulation"]
            ref, lam = tension_reference(g, law, form)
            solver = _solver_of(r)
            tol, why = NEWTON_TOL, "state in the model's space: Newton's stop"
            if form == "plane-strain" and r["solver"] == "ancf":
                P = g["tension_stress"][law]
                tol = max(tol, 2.0 * P * lam / (s["material"]["penalty"] * (lam - 1.0)))
                why = "penalised: 2 P lambda / (alpha (lambda - 1))"
            note = "non-conforming: its patch test fails" if solver in NONCONFORMING else ""
            out.append(Row(f"tension {law} {form}", solver, "lambda - 1 = u_x(L) / L", ref, *SOURCES["tension"],
                           tol, why, r["tip"]["ux"] / s["beam"]["length"] if ok else None, note, note))
        elif name.startswith("bench-shear-"):
            law, form = s["material"]["law"], s["material"]["formulation"]
            gamma = s["point"]["F"][0][1]
            ref = simple_shear_stress(law, constants(law)[0], gamma)
            out.append(Row(f"shear {law} {form} gamma {gamma:g}", "ANCF material", "P_12 (Pa)", ref,
                           *SOURCES["shear"], 1e-12, "explicit formulas: round-off",
                           r["point"]["P"][0][1] if ok else None))
        elif name.startswith("bench-elastica-"):
            L, h = s["beam"]["length"], s["beam"]["height"]
            E = 3.0 * mu_of("neo-hookean")
            alpha = -s["loads"]["tip_force"][1] * L ** 2 / (E * s["beam"]["width"] * h ** 3 / 12.0)
            u, v, _ = elastica_tip_load(alpha)
            ratio = L / h
            val = None
            if ok:   # the tip's distance from the elastica's, over L; the reference is then 0 at scale 1
                val = math.hypot(r["tip"]["ux"] / L + u, r["tip"]["uy"] / L + v)
            out.append(Row(f"elastica alpha {alpha:.3g} L/h {ratio:g}", _solver_of(r), "|r_tip - r_elastica| / L",
                           0.0, *SOURCES["elastica"], elastica_tolerance(alpha, ratio),
                           "2 (0.9 + alpha/12 + alpha^2/4) (h/L)^2: shear, stretch, the law's cubic term",
                           val, f"elastica u/L {u:.6f}, v/L {v:.6f}"))
        elif name.startswith("bench-arc-"):
            L, h = s["beam"]["length"], s["beam"]["height"]
            E = 3.0 * mu_of("neo-hookean")
            phi = s["loads"]["end_moment"] * L / (E * s["beam"]["width"] * h ** 3 / 12.0)
            x, y = elastica_end_moment(phi)
            val = math.hypot(1.0 + r["tip"]["ux"] / L - x, r["tip"]["uy"] / L - y) if ok else None
            row = Row(f"arc phi {phi:.3g} L/h {L / h:g}", _solver_of(r), "|r_tip - r_arc| / L", 0.0,
                      *SOURCES["arc"], 2.0 * arc_departure(phi, L / h) + NEWTON_TOL,
                      "2 x the exact pure bending's own departure from the arc (its curvature and its mid-line's "
                      "stretch, plane stress) + 1e-6", val)
            if row.verdict == "FAIL":
                row.cause = cause_of("arc", row.solver, "neo-hookean", "plane-stress")
                row.note = _joined(f"its end turned {r['tip']['rotation'] / phi:.4f} phi", row.cause)
            out.append(row)
        elif name.startswith("bench-timoshenko-"):
            L, h = s["beam"]["length"], s["beam"]["height"]
            ref = timoshenko_reference(L / h)
            out.append(Row(f"Timoshenko L/h {L / h:g}", _solver_of(r), "tip deflection (m)", ref,
                           *SOURCES["timoshenko"], 2.0 * (h / L) ** 2,
                           "2 (h/L)^2: plane-stress elasticity departs from the beam by (h/L)^2",
                           -r["tip"]["uy"] if ok else None))
    return _beam_notes(out + bending_rows(ctx))


def bending_rows(ctx, solvers=None) -> list[Row]:
    """kappa = (theta(2 L) - theta(L)) / L of each pair of lengths (the end face's rotation:
    the couple's end zone, the same in both, cancels) against the exact pure bending's;
    ``solvers(form)``: whose pairs (default: the grid's elements that run the form and its
    continuum codes)."""
    g = ctx.study.grid
    recs = {r["scene"]["name"]: r for r in ctx.records()}
    out = []
    for form in g["formulations"]:
        for law, curvatures in g["bending_curvatures"][form].items():
            if law not in g["laws"]:
                continue
            for x in curvatures:
                kappa = x / STRIP["height"]
                for solver in (solvers or (lambda f: _solvers(g, f)))(form):
                    n1, n2 = g["bending_lengths"]
                    pair = [recs.get(bending_scene(g, law, form, x, n, solver)["name"]) for n in (n1, n2)]
                    val = None
                    if all(p is not None and p["status"] == "converged" for p in pair):
                        dL = (n2 - n1) * STRIP["height"]
                        val = (pair[1]["tip"]["rotation"] - pair[0]["tip"]["rotation"]) / dL
                    tol, why = bending_tolerance(g, law, form, solver)
                    row = Row(f"bending {law} {form} kappa h {x:g}", solver,
                              f"kappa = (theta({n2}h) - theta({n1}h)) / {n2 - n1}h (1/m)", kappa,
                              *SOURCES[f"bending {form}"], tol, why, val)
                    if _is_cable(solver):
                        row.note = row.cause = CABLE_BENDING
                    elif row.verdict == "FAIL":
                        row.cause = cause_of("bending", solver, law, form)
                        row.note = _joined(f"kappa {val / kappa:.4f} x the exact", row.cause)
                    out.append(row)
    return out


def _beam_notes(rows: list[Row]) -> list[Row]:
    """A missed beam case (elastica, Timoshenko) says why, from the element's own errors
    across the slendernesses of the same case: growing with L/h (shear locking: the
    element's bending stiffens as the beam thins), or not falling with h/L (an error of
    the element at this mesh that the slender limit does not remove)."""
    groups: dict = {}
    for r in rows:
        m = re.match(r"(elastica alpha \S+|Timoshenko) L/h (\S+)", r.case)
        if m and r.error is not None:
            groups.setdefault((m.group(1), r.solver), []).append((float(m.group(2)), r))
    for series in groups.values():
        series.sort(key=lambda x: x[0])
        first, last = series[0][1].error, series[-1][1].error
        for _, r in series:
            if r.verdict == "FAIL" and len(series) > 1:
                why = ("its error grows with L/h, so with l_e / h at this mesh: locking" if last > 1.25 * first
                       else "its error does not fall with h/L: the element's own at this mesh")
                r.note, r.cause = _joined(r.note, why), why
    return rows


def _joined(*parts: str) -> str:
    return "; ".join(p for p in parts if p)


def mattiasson_rows() -> list[list]:
    """The elastica's closed form against Mattiasson's published table."""
    half = 0.5 * 10.0 ** -MATTIASSON_1981_DIGITS
    out = []
    for alpha, (u_pub, v_pub) in sorted(MATTIASSON_1981.items()):
        u, v, _ = elastica_tip_load(alpha)
        err = max(abs(u - u_pub), abs(v - v_pub))
        out.append([alpha, u_pub, u, v_pub, v, err, half, "pass" if err <= half else "FAIL"])
    return out
