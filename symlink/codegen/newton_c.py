"""The compiled Newton fallback: the continuation of :mod:`symlink.codegen.newton_driver`, written in C.

Where a linkage has no loop-by-loop closed form, :class:`symlink.numeric.solver.NumericSolver`
solves the closure of all loops by Newton's method.  The NumPy driver does that
over whole blocks of the sweep with ``numpy.linalg`` (and a singular-value
decomposition on every Newton system for its condition number); this module
writes the same driver as one C library, which continues value by value:

* the residuals, the Jacobian and the right-hand sides of the velocity and
  acceleration systems (:mod:`symlink.symbolic.closure`) as C functions, printed with
  common subexpressions eliminated (:func:`symlink.codegen.program.straight_line`)
  by the C printer of :mod:`symlink.codegen.c`;
* the driver, a fixed C text: damped Newton at the first input value (the
  assembly, fixing the branch), then for each further value a second-order
  Taylor predictor and a Newton corrector with the NumPy driver's constants and
  tests (a first correction of at most ``MAX_CORRECTION``, contracting
  corrections after it, converged at ``RESIDUAL_TOLERANCE`` with a last
  correction below ``POSITION_TOLERANCE``), a step split down to
  ``MIN_FRACTION`` where they fail; then the rates and accelerations.  Each
  Newton system is the Jacobian scaled as the NumPy driver scales it (by the
  equations' scales and the unknowns' units), solved by Gaussian elimination
  with partial pivoting written out;
* the named points and extras as one vectorised loop function
  (:func:`symlink.codegen.c.c_function`).

What makes it fast, none of which changes what is solved:

* the sines and cosines of the closure's angles are computed once a point, in one
  loop over a whole number of vector registers (glibc's vector ``sin`` and ``cos``
  where the compiled backend's vector math is on), and, where every angle moved by
  at most 2^-18 since the iterate before, from that iterate's by the addition
  theorems to second order (the remainder is below a tenth of an ulp);
* with one input, dq/dx and d2q/dx2 are solved once a point and give the rates,
  the accelerations and the Taylor step (the closure's time derivatives are linear
  and quadratic in the rates);
* after a last correction of at most 4 ulp only the residual is evaluated again
  (the Jacobian is the corrected point's to rounding); after a larger one, at an
  ill-conditioned point, the whole system.

The condition number that tells a dead-centre position (``SINGULAR_CONDITION``)
is the exact 1-norm condition number of the scaled Jacobian, computed from its LU
factors, and only where it decides something: at every step of the assembly, once
at each converged point (which the final check reuses), and where a correction is
refused; a zero or non-finite pivot is singular at once.  (The NumPy driver uses the 2-norm condition
number, which differs from the 1-norm one by at most the number of unknowns: both
are far beyond the threshold at a dead centre.)  Failures come back as a status and
the input values involved, which :mod:`symlink.numeric.solver` turns into the NumPy
driver's messages.

>>> from symlink.mechanism.catalog import stephenson2
>>> facts = newton_c_facts(stephenson2())
>>> "int symlink_newton_sweep(" in facts["source"], facts["unknowns"]
(True, ['beta', 'mu', 'phi', 'eta'])
"""
from __future__ import annotations

from typing import Any, Sequence

import sympy as sp

from ..symbolic.closure import closure_system
from ..symbolic.linkage import Linkage, Program
from ..symbolic.vectors import acceleration, rate
from . import newton_driver
from .c import C_KEYWORDS, CPrinter, c_function, c_identifier, c_library
from .program import FreshNames, straight_line

__all__ = ["newton_c_source", "newton_c_facts", "STATUS"]

#: What the C driver's return value means (0: solved).  The report array holds the condition number, the
#: residual, the index of the value, then the start's and the target's input values (see the C source).
STATUS = {0: "solved", 1: "assembly did not converge", 2: "singular at the assembly's guess",
          3: "singular Jacobian", 4: "continuation did not converge", 5: "no converged, regular position"}


#: The angles' sines and cosines are called for a multiple of this many angles at once (AVX-512's doubles).
VECTOR = 8


def _c_block(name: str, arrays: Sequence[tuple[str, Sequence[sp.Symbol | None]]],
             results: Sequence[tuple[str, Sequence[sp.Expr]]], doc: str) -> str:
    """A static C function reading its symbols from arrays and writing each result array, CSE across them all.

    ``arrays`` are ``(C array name, symbols read from it in order)`` (``None``: an entry not read); ``results``
    are ``(C array name, expressions written to it in order)``.
    """
    printer = CPrinter()
    arguments = tuple(symbol for _, symbols in arrays for symbol in symbols if symbol is not None)
    flat = {f"{label}_{k}": sp.sympify(expr) for label, exprs in results for k, expr in enumerate(exprs)}
    code = straight_line(Program(arguments, (), flat))
    signature = ", ".join([f"const double *restrict {array}" for array, _ in arrays]
                          + [f"double *restrict {label}" for label, _ in results])
    lines = [f"/* {doc} */", f"static void {name}({signature})", "{"]
    for array, symbols in arrays:
        lines += [f"    const double {c_identifier(s.name, 'symbol')} = {array}[{k}];"
                  for k, s in enumerate(symbols) if s is not None]
        lines += [f"    (void){s.name};" for s in symbols if s is not None]
    for symbol, expr in code.assignments:
        lines.append(f"    const double {c_identifier(symbol.name, 'symbol')} = {printer.doprint(expr)};")
    for label, exprs in results:
        lines += [f"    {label}[{k}] = {printer.doprint(code.outputs[f'{label}_{k}'])};" for k in range(len(exprs))]
    return "\n".join(lines + ["}", ""])


def _output_names(linkage: Linkage) -> list[str]:
    """The named points' coordinates and the extras: what the NumPy module's ``_outputs`` returns, in its order."""
    return [f"{point}_{axis}" for point in linkage.points for axis in "xy"] + list(linkage.extras)


#: The driver: the same algorithm as :mod:`symlink.codegen.newton_driver`, one input value at a time.
_DRIVER = r"""
/* The Newton driver (symlink.codegen.newton_c): the NumPy driver's algorithm and constants, value by value. */
static const double symlink_epsilon = {EPSILON!r};
static const double symlink_residual_tolerance = {RESIDUAL_TOLERANCE!r};
static const double symlink_singular_condition = {SINGULAR_CONDITION!r};
static const double symlink_position_tolerance = {POSITION_TOLERANCE!r};
static const double symlink_max_prediction = {MAX_PREDICTION!r};
static const double symlink_max_correction = {MAX_CORRECTION!r};
static const double symlink_contraction = {CONTRACTION!r};
static const int symlink_max_iterations = {MAX_ITERATIONS!r};
static const int symlink_assembly_iterations = {ASSEMBLY_ITERATIONS!r};
static const double symlink_min_fraction = {MIN_FRACTION!r};
/* An angle that moves by at most this much gets its sine and cosine from the ones before, to second order:
 * the remainder, |d|^3 / 6 < 1e-17, is below a tenth of a unit in the last place of 1. */
static const double symlink_small_turn = 0x1p-18;
/* A last correction at most this large (in units) leaves the Jacobian as it was, to rounding. */
static const double symlink_same_jacobian = 0x1p-50;

/* The closure at one point (x, q): its angles' sines and cosines, the residuals, the scaled Jacobian's LU
 * factors, the scales and units, and its 1-norm condition number once computed. */
typedef struct {{
    double angle[SYMLINK_NV];      /* the angles, then zeros up to a whole number of vector registers */
    double trig[2 * SYMLINK_NV];   /* the sines of the angles, then their cosines */
    double F[SYMLINK_N];
    double LU[SYMLINK_N * SYMLINK_N];  /* J * unit[j] / scale[i], factored in place (unit lower L below the diagonal) */
    double scale[SYMLINK_N];
    double unit[SYMLINK_N];
    double inverse_scale[SYMLINK_N];   /* 1 / scale: a solve multiplies */
    double inverse_pivot[SYMLINK_N];   /* 1 / U[k][k] */
    int row[SYMLINK_N];            /* row i of LU is row row[i] of the scaled Jacobian (partial pivoting) */
    int regular;                   /* 0: a zero or non-finite pivot, or a non-finite entry (singular) */
    double norm;                   /* 1-norm of the scaled Jacobian (NaN propagates) */
    double residual;               /* max |F_i| / scale_i (NaN propagates) */
    double condition;              /* the 1-norm condition number; negative until computed */
    int derived;                   /* whether slope and curvature are computed (one input) */
    double slope[SYMLINK_N];       /* dq/dx: J slope = r(xdot = 1) */
    double curvature[SYMLINK_N];   /* d2q/dx2: J curvature = r(qdot = slope, xdot = 1, xddot = 0) */
}} symlink_system;

/* The larger of m and v, NaN once either is NaN (numpy.max's semantics). */
static inline double symlink_max(double m, double v)
{{
    return (v > m || v != v) ? v : m;
}}

/* Every angle's sine and cosine, called: one loop over a whole number of vector registers, which the compiled
 * backend's vector math (SYMLINK_LOOP) turns into calls of glibc's vector sin and cos. */
SYMLINK_LOOP static void symlink_trig_called(double *restrict trig, const double *restrict angle)
{{
    for (int k = 0; k < SYMLINK_NV; ++k) {{
        trig[k] = sin(angle[k]);
        trig[SYMLINK_NV + k] = cos(angle[k]);
    }}
}}

/* Each angle's sine and cosine: called; or, where every angle moved by at most a small turn from the point before
 * (from), from that point's by the addition theorems to second order (exact where an angle did not move). */
static void symlink_trig(double *trig, const double *angle, const symlink_system *from)
{{
    int near = from != 0;
    for (int k = 0; k < SYMLINK_NA && near; ++k) {{
        near = fabs(angle[k] - from->angle[k]) <= symlink_small_turn;
    }}
    if (!near) {{
        symlink_trig_called(trig, angle);
        return;
    }}
    for (int k = 0; k < SYMLINK_NV; ++k) {{
        const double d = angle[k] - from->angle[k];
        const double s = from->trig[k], c = from->trig[SYMLINK_NV + k];
        trig[k] = s + (d * c - 0.5 * d * d * s);
        trig[SYMLINK_NV + k] = c - (d * s + 0.5 * d * d * c);
    }}
}}

/* The angles at (x, q), the padding after them zero. */
static void symlink_angles_at(const double *x, const double *p, const double *q, double *angle)
{{
    symlink_angles(x, p, q, angle);
    for (int k = SYMLINK_NA; k < SYMLINK_NV; ++k) {{
        angle[k] = 0.0;
    }}
}}

/* The system at (x, q), its sines and cosines moved from the point before where there is one (from). */
static void symlink_system_at(const double *x, const double *p, const double *q, const symlink_system *from,
                              symlink_system *s)
{{
    double J[SYMLINK_N * SYMLINK_N];
    symlink_angles_at(x, p, q, s->angle);
    symlink_trig(s->trig, s->angle, from);
    symlink_closure(x, p, q, s->trig, s->F, J, s->scale, s->unit);
    s->condition = -1.0;
    s->derived = 0;
    double residual = 0.0;
    for (int i = 0; i < SYMLINK_N; ++i) {{
        residual = symlink_max(residual, fabs(s->F[i]) / s->scale[i]);
    }}
    s->residual = residual;
    for (int i = 0; i < SYMLINK_N; ++i) {{
        s->inverse_scale[i] = 1.0 / s->scale[i];
        s->row[i] = i;
        for (int j = 0; j < SYMLINK_N; ++j) {{
            s->LU[i * SYMLINK_N + j] = J[i * SYMLINK_N + j] * s->unit[j] * s->inverse_scale[i];
        }}
    }}
    double norm = 0.0;
    for (int j = 0; j < SYMLINK_N; ++j) {{
        double column = 0.0;
        for (int i = 0; i < SYMLINK_N; ++i) {{
            column += fabs(s->LU[i * SYMLINK_N + j]);
        }}
        norm = symlink_max(norm, column);
    }}
    s->norm = norm;
    s->regular = norm - norm == 0.0;  /* finite */
    double *A = s->LU;
    for (int k = 0; k < SYMLINK_N && s->regular; ++k) {{
        int row = k;
        double largest = fabs(A[k * SYMLINK_N + k]);
        for (int i = k + 1; i < SYMLINK_N; ++i) {{
            if (fabs(A[i * SYMLINK_N + k]) > largest) {{
                largest = fabs(A[i * SYMLINK_N + k]);
                row = i;
            }}
        }}
        if (!(largest > 0.0) || largest - largest != 0.0) {{
            s->regular = 0;
            break;
        }}
        if (row != k) {{
            for (int j = 0; j < SYMLINK_N; ++j) {{
                const double t = A[k * SYMLINK_N + j];
                A[k * SYMLINK_N + j] = A[row * SYMLINK_N + j];
                A[row * SYMLINK_N + j] = t;
            }}
            const int t = s->row[k];
            s->row[k] = s->row[row];
            s->row[row] = t;
        }}
        s->inverse_pivot[k] = 1.0 / A[k * SYMLINK_N + k];
        for (int i = k + 1; i < SYMLINK_N; ++i) {{
            const double l = A[i * SYMLINK_N + k] * s->inverse_pivot[k];
            A[i * SYMLINK_N + k] = l;
            for (int j = k + 1; j < SYMLINK_N; ++j) {{
                A[i * SYMLINK_N + j] -= l * A[k * SYMLINK_N + j];
            }}
        }}
    }}
}}

/* The residual alone at (x, q) (the largest |F_i| / scale_i), the sines and cosines moved from those of a point
 * nearby where there is one (from). */
static double symlink_residual_at(const double *x, const double *p, const double *q, const symlink_system *from)
{{
    double angle[SYMLINK_NV], trig[2 * SYMLINK_NV], F[SYMLINK_N], scale[SYMLINK_N];
    symlink_angles_at(x, p, q, angle);
    symlink_trig(trig, angle, from);
    symlink_residuals(x, p, q, trig, F, scale);
    double residual = 0.0;
    for (int i = 0; i < SYMLINK_N; ++i) {{
        residual = symlink_max(residual, fabs(F[i]) / scale[i]);
    }}
    return residual;
}}

/* z = A^-1 b with A's LU factors (b in the scaled Jacobian's row order). */
static void symlink_lu_solve(const symlink_system *restrict s, const double *restrict b, double *restrict z)
{{
    for (int i = 0; i < SYMLINK_N; ++i) {{
        z[i] = b[s->row[i]];
    }}
    for (int i = 1; i < SYMLINK_N; ++i) {{
        for (int j = 0; j < i; ++j) {{
            z[i] -= s->LU[i * SYMLINK_N + j] * z[j];
        }}
    }}
    for (int i = SYMLINK_N - 1; i >= 0; --i) {{
        for (int j = i + 1; j < SYMLINK_N; ++j) {{
            z[i] -= s->LU[i * SYMLINK_N + j] * z[j];
        }}
        z[i] *= s->inverse_pivot[i];
    }}
}}

/* The solution of J out = r with the unscaled Jacobian J: the scaled system, then the units. */
static void symlink_solve(const symlink_system *s, const double *r, double *out)
{{
    double b[SYMLINK_N], z[SYMLINK_N];
    for (int i = 0; i < SYMLINK_N; ++i) {{
        b[i] = r[i] * s->inverse_scale[i];
    }}
    symlink_lu_solve(s, b, z);
    for (int j = 0; j < SYMLINK_N; ++j) {{
        out[j] = z[j] * s->unit[j];
    }}
}}

/* The 1-norm condition number of the scaled Jacobian, its norm times its inverse's (infinite where singular):
 * computed once a point, where it decides something. */
static double symlink_condition(symlink_system *s)
{{
    if (s->condition >= 0.0) {{
        return s->condition;
    }}
    double inverse = 0.0;
    for (int j = 0; j < SYMLINK_N && s->regular; ++j) {{
        double e[SYMLINK_N], z[SYMLINK_N];
        for (int i = 0; i < SYMLINK_N; ++i) {{
            e[i] = i == j ? 1.0 : 0.0;
        }}
        symlink_lu_solve(s, e, z);
        double column = 0.0;
        for (int i = 0; i < SYMLINK_N; ++i) {{
            column += fabs(z[i]);
        }}
        inverse = symlink_max(inverse, column);
    }}
    const double condition = s->norm * inverse;
    s->condition = s->regular && condition - condition == 0.0 ? condition : INFINITY;
    return s->condition;
}}

/* The largest of |v_j| / unit_j (NaN propagates). */
static double symlink_size(const double *v, const double *unit)
{{
    double size = 0.0;
    for (int j = 0; j < SYMLINK_N; ++j) {{
        size = symlink_max(size, fabs(v[j]) / unit[j]);
    }}
    return size;
}}

/* Newton from q (in place) at the input values x (the NumPy driver's _correct, for one point): 1 where it
 * converged while staying on its branch, with s the system at the converged q; else 0, with *singular where the
 * Jacobian is singular. */
static int symlink_correct(const double *x, const double *p, double *q, symlink_system *s, int *singular,
                           double *condition)
{{
    symlink_system other, *now = s, *next = &other;
    double previous = INFINITY;
    symlink_system_at(x, p, q, 0, now);
    *singular = 0;
    for (int iteration = 0;; ++iteration) {{
        if (!now->regular) {{
            *singular = 1;
            *condition = INFINITY;
            return 0;
        }}
        const int converged = now->residual <= symlink_residual_tolerance;
        if (iteration == symlink_max_iterations) {{
            *condition = symlink_condition(now);
            *singular = *condition > symlink_singular_condition;
            if (now != s) {{
                *s = *now;
            }}
            return converged && !*singular;
        }}
        double minus[SYMLINK_N], step[SYMLINK_N];
        for (int i = 0; i < SYMLINK_N; ++i) {{
            minus[i] = -now->F[i];
        }}
        symlink_solve(now, minus, step);
        const double size = symlink_size(step, now->unit);
        const double limit = iteration == 0 ? symlink_max_correction
                             : fmax(symlink_contraction * previous, 1e3 * symlink_epsilon);
        if (converged) {{
            /* A last, rounding-sized correction; where it is not small, a singular position. s is the system at
             * the corrected point: the residual the final check tests, the Jacobian the rates are solved with.
             * Where the correction is a few units in the last place (most points), the Jacobian and the sines
             * before it are those of the corrected point to rounding, and only the residual is evaluated again;
             * else (an ill-conditioned point, where the correction can reach the condition number times the
             * residual tolerance) the whole system. */
            for (int j = 0; j < SYMLINK_N; ++j) {{
                q[j] += step[j];
            }}
            if (size <= symlink_same_jacobian) {{
                now->residual = symlink_residual_at(x, p, q, now);
            }} else {{
                symlink_system_at(x, p, q, now, next);
                now = next;
            }}
            *condition = symlink_condition(now);
            *singular = *condition > symlink_singular_condition || !(size <= symlink_position_tolerance);
            if (now != s) {{
                *s = *now;
            }}
            return !*singular;
        }}
        if (!(size <= limit)) {{  /* refused: it could leave the branch */
            *condition = symlink_condition(now);
            *singular = *condition > symlink_singular_condition;
            return 0;
        }}
        for (int j = 0; j < SYMLINK_N; ++j) {{
            q[j] += step[j];
        }}
        symlink_system_at(x, p, q, now, next);
        symlink_system *t = now;
        now = next;
        next = t;
        previous = size;
    }}
}}

/* The second-order Taylor guess at target from the solved point (here, q), whose system s is: 1 where local. */
#if SYMLINK_NI == 1
/* One input: the point's dq/dx and d2q/dx2, once. The rates are then qdot = slope xdot and qddot = curvature
 * xdot^2 + slope xddot, and the Taylor step h is slope h + curvature h^2 / 2: the velocity system's right-hand
 * side is linear in xdot and the acceleration system's is quadratic in (xdot, qdot) plus the velocity system's
 * in xddot (the closure's second time derivative), so that one solve of each serves every rate and step. */
static void symlink_derive(symlink_system *s, const double *x, const double *p, const double *q)
{{
    if (s->derived) {{
        return;
    }}
    const double one[1] = {{1.0}}, zero[1] = {{0.0}};
    double r[SYMLINK_N];
    symlink_velocity_rhs(x, p, q, s->trig, one, r);
    symlink_solve(s, r, s->slope);
    symlink_acceleration_rhs(x, p, q, s->trig, s->slope, one, zero, r);
    symlink_solve(s, r, s->curvature);
    s->derived = 1;
}}
#endif

static int symlink_predict(const double *here, const double *p, const double *q, symlink_system *s,
                           const double *target, double *guess)
{{
    double first[SYMLINK_N], second[SYMLINK_N], change[SYMLINK_N];
#if SYMLINK_NI == 1
    const double h = target[0] - here[0];
    symlink_derive(s, here, p, q);
    for (int j = 0; j < SYMLINK_N; ++j) {{
        first[j] = s->slope[j] * h;
        second[j] = s->curvature[j] * (h * h);
    }}
#else
    double steps[SYMLINK_NI], zeros[SYMLINK_NI], r[SYMLINK_N];
    for (int k = 0; k < SYMLINK_NI; ++k) {{
        steps[k] = target[k] - here[k];
        zeros[k] = 0.0 * steps[k];
    }}
    symlink_velocity_rhs(here, p, q, s->trig, steps, r);
    symlink_solve(s, r, first);
    symlink_acceleration_rhs(here, p, q, s->trig, first, steps, zeros, r);
    symlink_solve(s, r, second);
#endif
    for (int j = 0; j < SYMLINK_N; ++j) {{
        change[j] = first[j] + 0.5 * second[j];
        guess[j] = q[j] + change[j];
    }}
    return symlink_size(change, s->unit) <= symlink_max_prediction;
}}

static void symlink_report(double *report, double condition, double residual, double index, const double *start,
                           const double *target)
{{
    report[0] = condition;
    report[1] = residual;
    report[2] = index;
    for (int k = 0; k < SYMLINK_NI; ++k) {{
        report[3 + k] = start[k];
        report[3 + SYMLINK_NI + k] = target[k];
    }}
}}

/* Damped Newton from the guess at the first input value (the NumPy driver's _assemble): 0 with s the system at
 * the assembly q, or a status. */
static int symlink_assemble(const double *x, const double *p, const double *guess, double *q, symlink_system *s,
                            double *report)
{{
    double trial[SYMLINK_N];
    for (int j = 0; j < SYMLINK_N; ++j) {{
        q[j] = guess[j];
    }}
    for (int iteration = 0; iteration < symlink_assembly_iterations; ++iteration) {{
        symlink_system_at(x, p, q, 0, s);
        const double condition = symlink_condition(s);
        if (condition > symlink_singular_condition) {{
            symlink_report(report, condition, s->residual, 0.0, x, x);
            return 2;
        }}
        double step[SYMLINK_N], minus[SYMLINK_N];
        for (int i = 0; i < SYMLINK_N; ++i) {{
            minus[i] = -s->F[i];
        }}
        symlink_solve(s, minus, step);
        const double size = symlink_size(step, s->unit);
        if (s->residual <= symlink_residual_tolerance) {{
            if (size > symlink_position_tolerance) {{
                symlink_report(report, condition, s->residual, 0.0, x, x);
                return 3;
            }}
            for (int j = 0; j < SYMLINK_N; ++j) {{
                q[j] += step[j];
            }}
            const symlink_system before = *s;
            symlink_system_at(x, p, q, &before, s);  /* the system at the assembly, as in symlink_correct */
            return 0;
        }}
        const double divisor = fmax(1.0, size / 0.5);  /* at most half a radian a step */
        for (int j = 0; j < SYMLINK_N; ++j) {{
            step[j] /= divisor;
        }}
        double fraction = 1.0;
        while (fraction > 1e-3) {{
            for (int j = 0; j < SYMLINK_N; ++j) {{
                trial[j] = q[j] + fraction * step[j];
            }}
            if (symlink_residual_at(x, p, trial, 0) < s->residual) {{
                break;
            }}
            fraction /= 2;
        }}
        for (int j = 0; j < SYMLINK_N; ++j) {{
            q[j] = trial[j];
        }}
    }}
    symlink_report(report, INFINITY, s->residual, 0.0, x, x);
    return 1;
}}

/* Continue from (here, q), whose system s is, to the input values there, splitting the step as often as it
 * takes (the NumPy driver's _substeps): 0 with q and s there, or a status. */
static int symlink_substeps(const double *here, const double *p, double *q, symlink_system *s,
                            const double *there, double *report, double index)
{{
    double done = 0.0, fraction = 1.0, start[SYMLINK_NI], target[SYMLINK_NI], guess[SYMLINK_N];
    symlink_system solved;
    for (;;) {{
        const double end = done + fraction < 1.0 ? done + fraction : 1.0;
        for (int k = 0; k < SYMLINK_NI; ++k) {{
            start[k] = here[k] + done * (there[k] - here[k]);
            target[k] = here[k] + end * (there[k] - here[k]);
        }}
        const int local = symlink_predict(start, p, q, s, target, guess);
        int singular;
        double condition;
        const int good = symlink_correct(target, p, guess, &solved, &singular, &condition);
        if (good && local && condition <= symlink_singular_condition) {{
            done = end;
            for (int j = 0; j < SYMLINK_N; ++j) {{
                q[j] = guess[j];
            }}
            *s = solved;
            if (done >= 1.0) {{
                return 0;
            }}
            fraction *= 2;
            continue;
        }}
        fraction /= 2;
        if (fraction < symlink_min_fraction) {{
            if (singular || condition > symlink_singular_condition) {{
                symlink_report(report, condition, NAN, index, target, target);
                return 3;
            }}
            symlink_report(report, condition, NAN, index, start, there);
            return 4;
        }}
    }}
}}

/* Newton's method over a sweep of count input values (the NumPy driver's _sweep, after its checks).
 *
 * inputs: SYMLINK_NI rows of count values; parameters: one number each; guess: the SYMLINK_N unknowns near the
 * wanted assembly at the first value. Writes q (SYMLINK_N rows of count values: unknown by unknown), residual
 * (count), and where rates is not 0 the unknowns' rates and accelerations qdot, qddot (SYMLINK_N rows of count)
 * from input_rates and input_accels (SYMLINK_NI rows of count values each). Returns 0, or a status (1 to 5)
 * with report: the condition number, the residual, the index of the value, the start's and the target's input
 * values. */
int symlink_newton_sweep(size_t count, const double *inputs, const double *parameters, const double *guess,
                         int rates, const double *input_rates, const double *input_accels,
                         double *q, double *qdot, double *qddot, double *residual, double *report)
{{
    double x[SYMLINK_NI], next[SYMLINK_NI], xdot[SYMLINK_NI], xddot[SYMLINK_NI], r[SYMLINK_N], qi[SYMLINK_N],
        rate[SYMLINK_N], accel[SYMLINK_N];
    symlink_system s;
    for (int k = 0; k < SYMLINK_NI; ++k) {{
        x[k] = inputs[(size_t)k * count];
    }}
    int status = symlink_assemble(x, parameters, guess, qi, &s, report);
    if (status) {{
        return status;
    }}
    size_t worst = 0;
    double worst_score = -1.0;
    int bad = 0;
    for (size_t i = 0; i < count; ++i) {{
        for (int j = 0; j < SYMLINK_N; ++j) {{
            q[(size_t)j * count + i] = qi[j];
        }}
        for (int k = 0; k < SYMLINK_NI; ++k) {{
            x[k] = inputs[(size_t)k * count + i];
        }}
        /* s is the system at (x, qi): the final check (NumPy's, after the sweep: the worst point is reported) */
        residual[i] = s.residual;
        const double condition = symlink_condition(&s);
        if (!(s.residual <= symlink_residual_tolerance) || condition > symlink_singular_condition) {{
            const double score = s.residual / symlink_residual_tolerance + condition / symlink_singular_condition;
            if (!bad || score > worst_score || (score != score && worst_score == worst_score)) {{
                worst = i;
                worst_score = score;
            }}
            bad = 1;
        }}
        if (rates) {{
            for (int k = 0; k < SYMLINK_NI; ++k) {{
                xdot[k] = input_rates[(size_t)k * count + i];
                xddot[k] = input_accels[(size_t)k * count + i];
            }}
#if SYMLINK_NI == 1
            symlink_derive(&s, x, parameters, qi);
            for (int j = 0; j < SYMLINK_N; ++j) {{
                rate[j] = s.slope[j] * xdot[0];
                accel[j] = s.curvature[j] * (xdot[0] * xdot[0]) + s.slope[j] * xddot[0];
            }}
            (void)r;
#else
            symlink_velocity_rhs(x, parameters, qi, s.trig, xdot, r);
            symlink_solve(&s, r, rate);
            symlink_acceleration_rhs(x, parameters, qi, s.trig, rate, xdot, xddot, r);
            symlink_solve(&s, r, accel);
#endif
            for (int j = 0; j < SYMLINK_N; ++j) {{
                qdot[(size_t)j * count + i] = rate[j];
                qddot[(size_t)j * count + i] = accel[j];
            }}
        }}
        if (i + 1 < count) {{
            for (int k = 0; k < SYMLINK_NI; ++k) {{
                next[k] = inputs[(size_t)k * count + i + 1];
            }}
            status = symlink_substeps(x, parameters, qi, &s, next, report, (double)(i + 1));
            if (status) {{
                return status;
            }}
        }}
    }}
    if (bad) {{
        for (int k = 0; k < SYMLINK_NI; ++k) {{
            x[k] = inputs[(size_t)k * count + worst];
        }}
        symlink_report(report, NAN, residual[worst], (double)worst, x, x);
        return 5;
    }}
    return 0;
}}
"""


def newton_c_source(linkage: Linkage) -> str:
    """The C library of ``linkage``'s compiled Newton fallback: ``symlink_newton_sweep`` and ``newton_outputs``.

    Plain C99 with ``math.h``; see the module docstring for what it computes and
    :data:`STATUS` for what it returns.
    """
    return newton_c_facts(linkage)["source"]


def _angles(expressions: Sequence[sp.Expr], known: set[sp.Symbol]) -> list[sp.Expr]:
    """The arguments of every sine and cosine in ``expressions`` that depend on ``known`` symbols only, in a fixed
    order: the closure's angles, whose sines and cosines the driver computes once a point."""
    found: set[sp.Expr] = set()
    for expr in expressions:
        found |= {f.args[0] for f in sp.sympify(expr).atoms(sp.sin, sp.cos) if f.args[0].free_symbols <= known}
    return sorted(found, key=sp.default_sort_key)


def newton_c_facts(linkage: Linkage) -> dict[str, Any]:
    """The compiled Newton fallback's source and calling facts: ``{"source", "inputs", "parameters", "unknowns",
    "outputs", "output_flags", "output_arguments"}`` (``outputs`` empty where the linkage names no points or
    extras; ``output_arguments`` the arguments of ``newton_outputs``)."""
    system = closure_system(linkage)
    inputs, parameters, unknowns = linkage.inputs, linkage.parameters, linkage.unknowns
    input_rates = tuple(rate(x) for x in inputs)
    input_accels = tuple(acceleration(x) for x in inputs)
    unknown_rates = tuple(rate(u) for u in unknowns)
    jacobian = [system.jacobian[i, j] for i in range(system.jacobian.rows) for j in range(system.jacobian.cols)]
    arguments = tuple(inputs + parameters + unknowns)
    every = list(system.residuals) + jacobian + list(system.velocity_rhs) + list(system.acceleration_rhs)
    angles = _angles(every, set(arguments))
    # The sines and cosines as symbols read from the point's trig array (names no linkage symbol takes).
    fresh = FreshNames({s.name for e in every for s in sp.sympify(e).free_symbols} | {s.name for s in arguments},
                       C_KEYWORDS)
    sines = [sp.Symbol(fresh(f"sin_{k}"), real=True) for k in range(len(angles))]
    cosines = [sp.Symbol(fresh(f"cos_{k}"), real=True) for k in range(len(angles))]
    trig = {sp.sin(a): s for a, s in zip(angles, sines)}
    trig.update({sp.cos(a): c for a, c in zip(angles, cosines)})
    own = lambda exprs: [sp.sympify(e).xreplace(trig) for e in exprs]  # noqa: E731
    padded = -(-max(1, len(angles)) // VECTOR) * VECTOR
    table: list[sp.Symbol | None] = [*sines, *[None] * (padded - len(angles)), *cosines]
    base = [("symlink_x", inputs), ("symlink_p", parameters), ("symlink_q", unknowns)]
    point = base + [("symlink_trig", table)]
    blocks = [
        _c_block("symlink_angles", base, [("symlink_angle", angles or [sp.S.Zero])],
                 "The closure's angles, whose sines and cosines the driver computes once a point."),
        _c_block("symlink_closure", point,
                 [("symlink_F", own(system.residuals)), ("symlink_J", own(jacobian)),
                  ("symlink_scale", system.scales), ("symlink_unit", system.units)],
                 "Closure residuals F, Jacobian J = dF/dq (row by row), each equation's scale and each unknown's "
                 "unit."),
        _c_block("symlink_residuals", point, [("symlink_F", own(system.residuals)), ("symlink_scale", system.scales)],
                 "Closure residuals F and each equation's scale."),
        _c_block("symlink_velocity_rhs", point + [("symlink_xdot", input_rates)],
                 [("symlink_r", own(system.velocity_rhs))], "Right-hand side of J qdot = r."),
        _c_block("symlink_acceleration_rhs", point + [("symlink_qdot", unknown_rates), ("symlink_xdot", input_rates),
                                                     ("symlink_xddot", input_accels)],
                 [("symlink_r", own(system.acceleration_rhs))], "Right-hand side of J qddot = r."),
    ]
    names = _output_names(linkage)
    functions = [c_function(Program(arguments, (), {name: linkage.output(name) for name in names}),
                            "newton_outputs", "Named points and extras from the solved coordinates.")] if names else []
    _, library = c_library(functions, "newton", f"{linkage.name}: Newton's method on the closure equations.",
                           standalone=True)
    constants = {name: getattr(newton_driver, name) for name in (
        "EPSILON", "RESIDUAL_TOLERANCE", "SINGULAR_CONDITION", "POSITION_TOLERANCE", "MAX_PREDICTION",
        "MAX_CORRECTION", "CONTRACTION", "MAX_ITERATIONS", "ASSEMBLY_ITERATIONS", "MIN_FRACTION")}
    sizes = [f"#define SYMLINK_N {len(unknowns)}", f"#define SYMLINK_NI {len(inputs)}",
             f"#define SYMLINK_NA {max(1, len(angles))}", f"#define SYMLINK_NV {padded}", ""]
    source = "\n".join([library] + sizes + blocks + [_DRIVER.format(**constants)])
    return {"source": source, "inputs": [s.name for s in inputs], "parameters": [s.name for s in parameters],
            "unknowns": [s.name for s in unknowns],
            "outputs": list(functions[0].outputs) if functions else [],
            "output_flags": list(functions[0].flags) if functions else [],
            "output_arguments": list(functions[0].arguments) if functions else []}
