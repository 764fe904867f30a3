"""Every displayed step of every derivation follows from the steps it names by the operation it
names: the checker below applies the operation itself (substitute, solve, add, differentiate,
integrate, linearise, ...) to the equations of the steps used, with SymPy, and the displayed
equation must equal the result up to a non-zero constant factor (the residual simplifies to
zero). It never reads how the engine computed a step, only what is displayed. Steps that state a
law, data or a definition (``given``, ``define``) must say so in words."""

from __future__ import annotations

import re
from collections.abc import Iterable
from typing import Any

import pytest
import sympy as sp

import rollspring
from rollspring.analysis.derivation import Derivation, derive
from rollspring.analysis.derivation.steps import OPERATIONS, Named, Step
from rollspring.analysis.paper import paper_system
from rollspring.model import load_system, preset_names
from tests.conftest import body, make_system, spring

#: Symbols that do not change in time and may appear in a constant factor between equivalent
#: forms of an equation (beyond the system's parameters).
CONSTANTS = {"A", "m", "R", "I", "F", "gamma"}


def wall_chain():
    """Two walls and three bodies (hoop, cylinder, sphere) joined at their centres."""
    return make_system(
        [
            body("hoop", "hoop", x=0.0),
            body("cyl", "cylinder", mass=1.5, x=0.5),
            body("ball", "sphere", mass=0.8, x=1.0),
        ],
        [
            spring("left", "hoop", rest_length=0.5),
            spring("hoop", "cyl", stiffness=80.0),
            spring("cyl", "ball", stiffness=120.0),
            spring("ball", "right", stiffness=60.0, rest_length=0.5),
        ],
        anchors=[{"id": "left", "x": -0.5, "y": 0.1}, {"id": "right", "x": 1.5, "y": 0.1}],
    )


def pulled_slider_pair():
    """A slider and a cylinder, a constant force on the cylinder's top, a wall spring."""
    return make_system(
        [body("block", "slider", mass=2.0, radius=0.05, x=0.0), body("cyl", "cylinder", x=0.5)],
        [spring("wall", "block", rest_length=0.5), spring("block", "cyl", stiffness=50.0)],
        anchors=[{"id": "wall", "x": -0.5, "y": 0.05}],
    )


def wall_hoop():
    """One hoop held by a wall spring at its top (off the centre: the exact equation is not
    linear)."""
    return make_system(
        [body("hoop", "hoop", x=0.0)],
        [spring("wall", "hoop", at=[{}, {"height": 0.2}], rest_length=0.5)],
        anchors=[{"id": "wall", "x": -0.5, "y": 0.2}],
    )


def pulled_cylinder():
    """A cylinder pulled by a constant force: no equilibrium, the exact equations only."""
    return make_system(
        [body("c", "cylinder", x=0.0)],
        [],
        forces=[{"body": "c", "at": {"height": 0.05}, "fx": 1.0}],
    )


def ten_body_chain():
    """Ten bodies, hoop and cylinder alternating, between walls (``rollspring chain``): a
    characteristic polynomial of degree 10, not expanded with the parameters as symbols."""
    return rollspring.chain("hoop,cylinder", 10, walls="both", pluck=1)


CASES: dict[str, Any] = {
    **{f"{name} (symbols)": (lambda n=name: load_system(n), True) for name in preset_names()},
    "hoop-cylinder (numbers)": (lambda: load_system("hoop-cylinder"), False),
    "frictionless (numbers)": (lambda: load_system("frictionless"), False),
    "paper Fig. 3, raised track (symbols)": (lambda: paper_system("fig3"), True),
    "wall chain (symbols)": (wall_chain, True),
    "wall chain (numbers)": (wall_chain, False),
    "slider and cylinder (symbols)": (pulled_slider_pair, True),
    "one hoop on a wall spring (symbols)": (wall_hoop, True),
    "a pulled cylinder, no equilibrium (numbers)": (pulled_cylinder, False),
    "ten-body chain (symbols)": (ten_body_chain, True),
    "ten-body chain (numbers)": (ten_body_chain, False),
}
#: Cases whose step check takes more than a few seconds (determinants of 10 x 10 matrices).
SLOW = {"ten-body chain (symbols)", "ten-body chain (numbers)"}


@pytest.fixture(
    scope="module",
    params=[
        pytest.param(name, marks=pytest.mark.slow) if name in SLOW else name
        for name in sorted(CASES)
    ],
)
def derivation(request: pytest.FixtureRequest) -> Derivation:
    build, symbols = CASES[request.param]
    return derive(build(), symbols=symbols)


# -- the checker ------------------------------------------------------------------------------


class Checker:
    """Applies a step's named operation to the equations it names and compares."""

    def __init__(self, derivation: Derivation) -> None:
        self.derivation = derivation
        self.sym = derivation.symbolic
        self.steps: dict[str, Step] = {}
        self.rates: dict[sp.Symbol, sp.Symbol] = {}
        for section in derivation.sections:
            self.rates.update(section.rates)
            for step in section.steps:
                if step.tag:
                    assert step.tag not in self.steps, f"the number {step.tag} is used twice"
                    self.steps[step.tag] = step
        self.constants = set(self.sym.values) | {
            s for s in self._all_symbols() if s.name in CONSTANTS
        }

    def _all_symbols(self) -> Iterable[sp.Symbol]:
        for step in self.steps.values():
            for eq in step.equations:
                if isinstance(eq, sp.Basic):
                    yield from eq.free_symbols

    # premises
    def equations(self, ref: str) -> list[Any]:
        tag, _, picks = ref.partition(":")
        found = self.steps[tag].equations
        if picks:
            return [found[int(k) - 1] for k in picks.split(",")]
        return found

    def used(self, refs: Iterable[str]) -> list[Any]:
        out: list[Any] = []
        for ref in refs:
            out.extend(self.equations(ref))
        return out

    # algebra
    def ddt(self, expr: sp.Expr) -> sp.Expr:
        expr = sp.sympify(expr)
        return sp.Add(*[sp.diff(expr, s) * rate for s, rate in self.rates.items() if expr.has(s)])

    def zero(self, expr: Any) -> bool:
        """The residual simplifies to zero (with the system's conditions): expanded, over a
        common denominator, or simplified."""
        expr = self.sym.apply_conditions(sp.sympify(expr))
        if self.numerically_nonzero(expr):
            return False
        expr = sp.expand(expr)
        if expr == 0:
            return True
        expr = sp.cancel(sp.together(expr))
        if expr == 0:
            return True
        return sp.simplify(expr) == 0

    def numerically_nonzero(self, expr: sp.Expr) -> bool:
        """expr is clearly not zero at a point (a quick screen before simplify)."""
        point = {s: sp.Rational(3 + sum(map(ord, s.name)) % 17, 7) for s in expr.free_symbols}
        try:
            value = complex(sp.sympify(expr).xreplace(point).evalf(30))
        except (TypeError, ValueError, ZeroDivisionError):
            return False
        return abs(value) > 1e-12

    def residual(self, eq: Any) -> sp.Expr:
        if isinstance(eq, sp.Eq):
            return sp.sympify(eq.lhs - eq.rhs)
        return sp.sympify(eq)

    def dynamic(self) -> set[sp.Symbol]:
        return set(self.rates) | set(self.rates.values())

    def same(self, shown: Any, expected: Any) -> bool:
        """The same equation: residuals equal up to a non-zero factor free of anything that
        changes in time (tried: 1, -1, the ratio of the coefficients of a rate, the ratio)."""
        a, b = self.residual(shown), self.residual(expected)
        b_zero = self.zero(b)
        if b_zero or self.zero(a):
            return b_zero and self.zero(a)
        for c in self.factors(a, b):
            c = self.sym.apply_conditions(c)
            if c != 0 and c.free_symbols <= self.constants and self.zero(a - c * b):
                return True
        return False

    def factors(self, a: sp.Expr, b: sp.Expr) -> Iterable[sp.Expr]:
        """Candidate constant factors a/b, cheapest first."""
        yield sp.Integer(1)
        yield sp.Integer(-1)
        for x in sorted(self.dynamic() & a.free_symbols & b.free_symbols, key=str):
            ca, cb = sp.diff(a, x), sp.diff(b, x)
            if cb != 0 and not (ca.free_symbols | cb.free_symbols) - self.constants:
                yield sp.powsimp(ca / cb)
                break
        if sp.count_ops(a) + sp.count_ops(b) < 300:
            yield sp.cancel(a / b)

    def substitutions(self, sources: list[Any], unknowns: tuple[Any, ...]) -> dict[Any, Any]:
        """Each unknown from the source equation that holds it (solved for it; the sources'
        time derivatives too, for a rate), the results substituted into each other."""
        extended = list(sources)
        for eq in sources:
            once = self.ddt(self.residual(eq))
            if once != 0:
                extended.append(sp.Eq(once, 0))
                extended.append(sp.Eq(self.ddt(once), 0))
        mapping: dict[Any, Any] = {}
        for u in unknowns:
            direct = [eq.rhs for eq in sources if eq.lhs == u]
            if direct:
                mapping[u] = direct[0]
                continue
            for eq in sorted(extended, key=lambda e: isinstance(e, sp.Eq) and e.lhs in unknowns):
                r = self.residual(eq)
                if r.has(u):
                    solutions = sp.solve(r, u)
                    if solutions:
                        mapping[u] = solutions[-1] if len(solutions) > 1 else solutions[0]
                        break
            assert u in mapping, f"no source gives {u}: {sources}"
        for _ in range(len(mapping)):
            mapping = {u: sp.sympify(v).subs(mapping) for u, v in mapping.items()}
        return mapping

    # the operations
    def check(self, step: Step) -> None:
        how = step.how
        assert how is not None, f"{step.tag} does not say how it follows"
        shown = step.equations
        op = how.op
        if op in ("given", "define", "check"):
            assert step.words
            return
        method = getattr(self, "op_" + op.replace(" ", "_"))
        method(step, shown, how)

    def op_substitute(self, step: Step, shown: list[Any], how: Any) -> None:
        if how.law is not None:
            target = how.law if isinstance(how.law, list) else [how.law]
            sources = self.used(how.uses) + list(how.given)
        else:
            target = self.equations(how.uses[0])
            sources = self.used(how.uses[1:]) + list(how.given)
        mapping = self.substitutions(sources, how.args)
        assert len(shown) == len(target), step.tag
        for eq, goal in zip(shown, target, strict=True):
            expected = self.residual(goal).subs(mapping)
            assert self.same(eq, expected), f"{step.tag}: {eq} is not {expected} = 0"

    def op_solve(self, step: Step, shown: list[Any], how: Any) -> None:
        """The displayed values satisfy the equations used: substituted into them (and the
        unknowns not displayed eliminated between them), every residual vanishes."""
        unknowns = list(how.args)
        if how.law is not None:
            premises = how.law if isinstance(how.law, list) else [how.law]
            definitions = self.used(how.uses)
        else:
            used = self.used(how.uses)
            rhs_symbols = set().union(*(eq.rhs.free_symbols for eq in shown))
            definitions = [eq for eq in used if eq.lhs in rhs_symbols]
            premises = [eq for eq in used if eq not in definitions]
        given = {eq.lhs: eq.rhs for eq in how.given}
        residuals = [self.residual(eq).subs(given) for eq in premises]
        roots = [eq for eq in shown if eq.lhs not in unknowns]
        if roots:  # the roots of one equation in args[0], each displayed under its own name
            (residual,) = residuals
            for eq in roots:
                self.is_root(step, residual, unknowns[0], eq.rhs)
            return
        values = {eq.lhs: eq.rhs.subs({d.lhs: d.rhs for d in definitions}) for eq in shown}
        residuals = [r.subs(values) for r in residuals]
        remaining = [u for u in unknowns if u not in values]
        if remaining:  # eliminate them with the first equation that holds them
            first = next(r for r in residuals if r.has(*remaining))
            (elimination,) = [sp.solve(first, remaining, dict=True)[0]]
            residuals = [r.subs(elimination) for r in residuals if r is not first]
        for r in residuals:
            assert self.zero(r), f"{step.tag}: {shown} does not solve {premises} ({r})"

    def is_root(self, step: Step, residual: sp.Expr, unknown: Any, value: Any) -> None:
        if isinstance(value, sp.Float):  # a number where there is no closed form
            numbers = sp.Poly(residual.xreplace(self.sym.values), unknown).nroots(n=30)
            assert any(
                abs(complex(r) - float(value)) <= 1e-8 * max(1.0, abs(complex(r))) for r in numbers
            ), f"{step.tag}: {value} is not a root"
            return
        assert self.zero(residual.subs(unknown, value)), f"{step.tag}: {value} is not a root"

    def op_add(self, step: Step, shown: list[Any], how: Any) -> None:
        premises = self.used(how.uses)
        total = sp.Add(*[w * self.residual(eq) for w, eq in zip(how.args, premises, strict=True)])
        (eq,) = shown
        assert self.same(eq, total), f"{step.tag}: {eq} is not {total} = 0"

    def op_differentiate_in_time(self, step: Step, shown: list[Any], how: Any) -> None:
        premises = self.used(how.uses)
        given = {eq.lhs: eq.rhs for eq in how.given}
        assert len(shown) == len(premises)
        for eq, premise in zip(shown, premises, strict=True):
            expected = self.ddt(self.residual(premise)).subs(given)
            assert self.same(eq, expected), f"{step.tag}: {eq} is not d/dt of {premise}"

    def op_integrate_in_time(self, step: Step, shown: list[Any], how: Any) -> None:
        (premise,) = self.used(how.uses)
        (eq,) = shown
        assert self.same(sp.Eq(self.ddt(self.residual(eq)), 0), premise), (
            f"{step.tag}: d/dt of {eq} is not {premise}"
        )

    def op_differentiate(self, step: Step, shown: list[Any], how: Any) -> None:
        (premise, *sources) = self.used(how.uses)
        mapping = {eq.lhs: eq.rhs for eq in sources}
        expression = sp.sympify(premise.rhs).subs(mapping)
        assert len(shown) == len(how.args)
        for eq, variable in zip(shown, how.args, strict=True):
            expected = sp.diff(expression, variable)
            assert self.zero(eq.rhs - expected), f"{step.tag}: {eq.rhs} is not d/d{variable}"

    def op_rearrange(self, step: Step, shown: list[Any], how: Any) -> None:
        premises = self.equations(how.uses[0])
        if len(premises) != len(shown):
            premises = premises[: len(shown)]
        for eq, premise in zip(shown, premises, strict=True):
            assert self.same(eq, premise), f"{step.tag}: {eq} is not a form of {premise}"

    def op_divide(self, step: Step, shown: list[Any], how: Any) -> None:
        (premise,) = self.used(how.uses)
        (eq,) = shown
        factor = how.args[0]
        assert self.same(eq, sp.cancel(self.residual(premise) / factor)), step.tag

    def _coordinates(self) -> list[sp.Symbol]:
        return list(self.sym.q)

    def op_linearise(self, step: Step, shown: list[Any], how: Any) -> None:
        premises = self.used(how.uses)
        q = self._coordinates()
        at_zero = dict.fromkeys(q, 0)
        assert len(shown) == len(premises)
        for eq, premise in zip(shown, premises, strict=True):
            r = self.residual(premise)
            linear = r.subs(at_zero) + sp.Add(*[sp.diff(r, x).subs(at_zero) * x for x in q])
            assert self.same(eq, linear), f"{step.tag}: {eq} is not the first order of {premise}"

    def op_expand_to_second_order(self, step: Step, shown: list[Any], how: Any) -> None:
        (premise,) = self.used(how.uses)
        q = list(how.args[0])
        at_zero = dict.fromkeys(q, 0)
        v = sp.sympify(premise.rhs)
        taylor = v.subs(at_zero) + sp.Add(*[sp.diff(v, x).subs(at_zero) * x for x in q])
        taylor += sp.Add(*[sp.diff(v, x, y).subs(at_zero) * x * y / 2 for x in q for y in q])
        (eq,) = shown
        assert self.zero(eq.rhs - taylor), f"{step.tag}: not the second order of V"

    def op_second_derivative(self, step: Step, shown: list[Any], how: Any) -> None:
        (premise,) = self.used(how.uses)
        q = list(how.args[0])
        at_zero = dict.fromkeys(q, 0)
        v = sp.sympify(premise.rhs)
        (eq,) = shown
        matrix = sp.Matrix(eq.rhs)
        for i, x in enumerate(q):
            for j, y in enumerate(q):
                assert self.zero(matrix[i, j] - sp.diff(v, x, y).subs(at_zero)), (
                    f"{step.tag}: entry ({i + 1},{j + 1})"
                )

    def op_matrix_form(self, step: Step, shown: list[Any], how: Any) -> None:
        premises = self.used(how.uses)
        (eq,) = shown
        rows = sp.Matrix(eq.lhs.doit()) - sp.Matrix(eq.rhs)
        assert rows.shape[0] == len(premises)
        for row, premise in zip(rows, premises, strict=True):
            assert self.same(row, premise), f"{step.tag}: {row} is not {premise}"

    def op_characteristic_equation(self, step: Step, shown: list[Any], how: Any) -> None:
        mass, stiffness = how.args
        omega2 = next(s for s in self._all_symbols() if s.name == "Omega^2")
        (eq,) = shown
        if isinstance(eq.lhs, sp.Function) or eq.lhs.has(sp.Function("det")):
            return  # not expanded: only named
        determinant = sp.expand((sp.Matrix(stiffness) - omega2 * sp.Matrix(mass)).det())
        assert self.same(eq, determinant), f"{step.tag}: not det(K - Omega^2 M)"

    def op_read_off(self, step: Step, shown: list[Any], how: Any) -> None:
        premises = self.used(how.uses)
        if isinstance(shown[0].lhs, sp.MatrixSymbol):
            (eq,) = shown
            (premise,) = premises
            rates = sp.Matrix(how.args[0])
            quadratic = (rates.T * sp.Matrix(eq.rhs) * rates)[0, 0] / 2
            assert self.zero(premise.rhs - quadratic), f"{step.tag}: not 1/2 q'^T M q'"
            return
        law = how.law if isinstance(how.law, list) else [how.law]
        mapping = {eq.lhs: eq.rhs for eq in shown}
        assert len(law) == len(premises), step.tag
        for form, premise in zip(law, premises, strict=True):
            assert self.same(premise, self.residual(form).subs(mapping)), (
                f"{step.tag}: {premise} is not {form} with {mapping}"
            )

    def op_evaluate(self, step: Step, shown: list[Any], how: Any) -> None:
        mapping: dict[Any, Any] = {}
        for eq in self.used(how.uses):
            if isinstance(eq.lhs, sp.MatrixSymbol):
                name = str(eq.lhs.name)
                matrix = sp.Matrix(eq.rhs)
                for i in range(matrix.rows):
                    for j in range(matrix.cols):
                        mapping[sp.Symbol(f"{name}_{i + 1}{j + 1}")] = matrix[i, j]
                if matrix.rows == matrix.cols:
                    mapping[_det_name(name)] = matrix.det()
            else:
                mapping[eq.lhs] = eq.rhs
        for eq in shown:
            assert self.zero(self.residual(eq).subs(mapping)), f"{step.tag}: {eq} does not hold"

    def op_with_your_values(self, step: Step, shown: list[Any], how: Any) -> None:
        """Each squared frequency of the step used, with the system's numbers, to the digits
        shown (four significant: within 5e-4 relative), and each Omega its square root."""
        squared = {eq.lhs: eq.rhs for eq in self.used(how.uses)}
        by_name = {str(getattr(lhs, "name", lhs)): rhs for lhs, rhs in squared.items()}
        assert shown, step.tag
        for eq in shown:
            name = str(getattr(eq.lhs, "name", eq.lhs))
            if name.endswith("^2"):
                expected = float(sp.sympify(by_name[name]).xreplace(self.sym.values))
            else:
                expected = float(
                    sp.sqrt(sp.sympify(by_name[name + "^2"]).xreplace(self.sym.values))
                )
            value = float(eq.rhs)
            assert isinstance(eq.rhs, sp.Float), f"{step.tag}: {eq} is not in decimals"
            assert abs(value - expected) <= 5e-4 * abs(expected), f"{step.tag}: {eq} vs {expected}"


def _det_name(name: str) -> sp.Symbol:
    return Named(f"det {name}")


def test_every_operation_is_known() -> None:
    assert set(OPERATIONS) >= {"given", "substitute", "solve", "add", "linearise"}


def test_every_step_follows_from_the_ones_it_names(derivation: Derivation) -> None:
    checker = Checker(derivation)
    for section in derivation.sections:
        for step in section.steps:
            checker.check(step)
            if step.how is not None:
                for ref in step.how.uses:
                    tag = ref.partition(":")[0]
                    assert tag in checker.steps, f"{step.tag} uses {tag}, which is not shown"


def test_every_step_is_numbered_and_says_how(derivation: Derivation) -> None:
    for section in derivation.sections:
        for step in section.steps:
            assert step.how is not None and step.how.op in OPERATIONS
            if step.how.op != "check":
                assert re.fullmatch(r"[A-Z]\d+", step.tag), step.tag
                assert rf"\tag{{{step.tag}}}" in step.latex
                # nothing displayed lacks its right side ("= 0" included); a data table may
                for item in step.equations:
                    assert isinstance(item, sp.Eq) or (
                        step.how.op == "given" and isinstance(item, sp.MatrixBase)
                    ), f"{step.tag}: {item} is not an equation"


def test_each_step_refers_only_to_earlier_steps(derivation: Derivation) -> None:
    seen: set[str] = set()
    for section in derivation.sections:
        for step in section.steps:
            if step.how is not None:
                for ref in step.how.uses:
                    assert ref.partition(":")[0] in seen, f"{step.tag} uses a later step {ref}"
            seen.add(step.tag)
