"""50-digit references for the catalog linkages, written by hand without symlink.

Each linkage's closure equations are typed out here as mpmath functions
``closure(x, q, p)`` (inputs x, unknowns q in the catalog's order, parameters
p), its positions are found by geometry (circle intersections, with the branch
taken from its documented definition) or by ``mpmath.findroot``, and the rates
and accelerations by mpmath linear solves of the differentiated closure, the
derivatives taken numerically by ``mpmath.diff`` at 50 digits:

    J qdot  = -F_x xdot
    J qddot = -(F_x xddot + d^2/ds^2 F(x + s xdot, q + s qdot))   at s = 0

so nothing here shares code or algebra with symlink's symbolic derivation.
"""
import mpmath as mp

DPS = 50


def _m(value):
    return mp.mpf(value) if not isinstance(value, mp.mpf) else value


def slider_closure(x, q, p):
    (theta,), (beta, s) = x, q
    return [p["a"] * mp.cos(theta) + p["b"] * mp.cos(beta) - s,
            p["a"] * mp.sin(theta) + p["b"] * mp.sin(beta) - p["offset"]]


def inverted_closure(x, q, p):
    (theta,), (phi, r) = x, q
    return [p["a"] * mp.cos(theta) - r * mp.cos(phi) - p["d"],
            p["a"] * mp.sin(theta) - r * mp.sin(phi)]


def fourbar_closure(x, q, p):
    (theta,), (beta, phi) = x, q
    return [p["a"] * mp.cos(theta) + p["b"] * mp.cos(beta) - p["d"] - p["c"] * mp.cos(phi),
            p["a"] * mp.sin(theta) + p["b"] * mp.sin(beta) - p["c"] * mp.sin(phi)]


def watt2_closure(x, q, p):
    (theta,), (beta, phi, mu, psi) = x, q
    a, b, c, d, e, f, g = (p[k] for k in "abcdefg")
    return [a * mp.cos(theta) + b * mp.cos(beta) - d - c * mp.cos(phi),
            a * mp.sin(theta) + b * mp.sin(beta) - c * mp.sin(phi),
            d + e * mp.cos(phi + p["alpha"]) + f * mp.cos(mu) - p["gx"] - g * mp.cos(psi),
            e * mp.sin(phi + p["alpha"]) + f * mp.sin(mu) - p["gy"] - g * mp.sin(psi)]


def fivebar_closure(x, q, p):
    (theta, psi), (beta, phi) = x, q
    a, b, c, d, e = (p[k] for k in "abcde")
    return [a * mp.cos(theta) + b * mp.cos(beta) - d - e * mp.cos(psi) - c * mp.cos(phi),
            a * mp.sin(theta) + b * mp.sin(beta) - e * mp.sin(psi) - c * mp.sin(phi)]


def stephenson2_closure(x, q, p):
    (theta,), (beta, mu, phi, eta) = x, q
    a, b, c, d, e, f, g, h = (p[k] for k in "abcdefgh")
    return [a * mp.cos(theta) + b * mp.cos(beta) + c * mp.cos(mu) - d - f * mp.cos(phi),
            a * mp.sin(theta) + b * mp.sin(beta) + c * mp.sin(mu) - f * mp.sin(phi),
            a * mp.cos(theta) + e * mp.cos(beta + p["alpha"]) + g * mp.cos(eta) - d - h * mp.cos(phi + p["delta"]),
            a * mp.sin(theta) + e * mp.sin(beta + p["alpha"]) + g * mp.sin(eta) - h * mp.sin(phi + p["delta"])]


STEPHENSON2_UNKNOWNS = ("beta", "mu", "phi", "eta")


def stephenson2_continued(p, thetas, guess, substeps=8, dps=30, jacobian=None):
    """Stephenson II's unknowns (beta, mu, phi, eta) as mpf lists at each crank angle in ``thetas``, in order.

    The assembly nearest ``guess`` (a mapping by name) is found by ``mpmath.findroot`` at thetas[0], then
    continued from each angle to the next in ``substeps`` equal steps (at thetas[0] itself too, steps of
    zero), at ``dps`` digits; ``jacobian(q, p)``, if given, is findroot's Jacobian (else its own differences).
    """
    with mp.workdps(dps):
        p = {k: _m(v) for k, v in p.items()}
        extra = {} if jacobian is None else {"J": lambda *q: jacobian(q, p)}

        def solve(theta, start):
            found = mp.findroot(lambda *q: stephenson2_closure((theta,), q, p), start, **extra)
            return [found[i] for i in range(len(start))]

        q = solve(_m(thetas[0]), [_m(guess[n]) for n in STEPHENSON2_UNKNOWNS])
        previous, solved = _m(thetas[0]), []
        for theta in map(_m, thetas):
            for k in range(1, substeps + 1):
                q = solve(previous + (theta - previous) * k / substeps, q)
            previous = theta
            solved.append(q)
        return solved


def circle_point(P, r, Q, s, side):
    """The point X (complex) with |X - P| = r and |X - Q| = s, left (+1) or right (-1) of the line P -> Q."""
    length = abs(Q - P)
    u = (Q - P) / length
    along = (r * r - s * s + length * length) / (2 * length)
    height2 = r * r - along * along
    if height2 < 0:
        raise ValueError("the two circles do not meet: not assembled")
    return P + u * (along + side * 1j * mp.sqrt(height2))


def inverted_positions(x, p, branch=None):
    B = p["a"] * mp.expj(x[0])
    return [mp.arg(B - p["d"]), abs(B - p["d"])]


def watt2_positions(x, p, branch):
    first, second = branch
    B = p["a"] * mp.expj(x[0])
    C = circle_point(B, p["b"], p["d"], p["c"], first)
    phi = mp.arg(C - p["d"])
    E = p["d"] + p["e"] * mp.expj(phi + p["alpha"])
    G = mp.mpc(p["gx"], p["gy"])
    F = circle_point(E, p["f"], G, p["g"], second)
    return [mp.arg(C - B), phi, mp.arg(F - E), mp.arg(F - G)]


def fivebar_positions(x, p, branch):
    B = p["a"] * mp.expj(x[0])
    D = p["d"] + p["e"] * mp.expj(x[1])
    C = circle_point(B, p["b"], D, p["c"], branch)
    return [mp.arg(C - B), mp.arg(C - D)]


def kinematics(closure, x, q, p, xdot, xddot, refine=True):
    """Positions (refined by findroot from q), rates and accelerations at 50 digits, as mpf lists."""
    with mp.workdps(DPS):
        x = [_m(v) for v in x]
        xdot, xddot = [_m(v) for v in xdot], [_m(v) for v in xddot]
        p = {k: _m(v) for k, v in p.items()}
        q = [_m(v) for v in q]
        n = len(q)
        if refine:
            found = mp.findroot(lambda *unknowns: closure(x, list(unknowns), p), q)
            q = [found[i] for i in range(n)]
        residual = max(abs(v) for v in closure(x, q, p))
        if residual > mp.mpf(10) ** (-DPS + 10):
            raise ValueError(f"not a solution: residual {residual}")

        def moved(dq, dx):
            return lambda s: closure([xi + s * di for xi, di in zip(x, dx)],
                                     [qi + s * di for qi, di in zip(q, dq)], p)

        jacobian = mp.matrix(n, n)
        for j in range(n):
            unit = [mp.mpf(int(i == j)) for i in range(n)]
            for i in range(n):
                jacobian[i, j] = mp.diff(lambda s: moved(unit, [0] * len(x))(s)[i], 0)
        if abs(mp.det(jacobian)) < mp.mpf(10) ** -30:
            raise ValueError("singular Jacobian")
        along_input = [mp.diff(lambda s: moved([0] * n, xdot)(s)[i], 0) for i in range(n)]
        qdot = mp.lu_solve(jacobian, mp.matrix([-v for v in along_input]))
        qdot = [qdot[i] for i in range(n)]
        curvature = [mp.diff(lambda s: moved(qdot, xdot)(s)[i], 0, 2) for i in range(n)]
        push = [mp.diff(lambda s: moved([0] * n, xddot)(s)[i], 0) for i in range(n)]
        qddot = mp.lu_solve(jacobian, mp.matrix([-(c + f) for c, f in zip(curvature, push)]))
        return q, qdot, [qddot[i] for i in range(n)], jacobian


def continue_sweep(closure, inputs, q0, p, substeps=4):
    """Positions at each input tuple, continued from q0 at the first with findroot in small steps."""
    with mp.workdps(DPS):
        p = {k: _m(v) for k, v in p.items()}
        previous_x = [_m(v) for v in inputs[0]]
        q = mp.findroot(lambda *u: closure(previous_x, list(u), p), [_m(v) for v in q0])
        q = [q[i] for i in range(len(q0))]
        solved = [q]
        for x in inputs[1:]:
            x = [_m(v) for v in x]
            for k in range(1, substeps + 1):
                here = [a + (b - a) * k / substeps for a, b in zip(previous_x, x)]
                found = mp.findroot(lambda *u: closure(here, list(u), p), q)
                q = [found[i] for i in range(len(q))]
            solved.append(q)
            previous_x = x
        return solved


def offset_inverted_positions(theta, a, d, e, branch):
    """50-digit reference for the offset inverted slider-crank: the guide is a tangent from B to the circle
    of radius e about D (a circle/tangent construction, not the solver's formula); +1 the larger s."""
    import mpmath as mp
    with mp.workdps(max(50, mp.mp.dps)):  # never lower: mp.diff raises the precision to step
        b = mp.mpc(a * mp.cos(theta), a * mp.sin(theta)) - d
        w = abs(b)
        opening = mp.acos(e / w)
        solutions = []
        for turn in (opening, -opening):
            foot = e * b / w * mp.expj(turn)                 # T - D, the foot of the offset
            phi = mp.arg(foot) - mp.pi / 2
            s = mp.re((b - foot) * mp.expj(-phi))
            solutions.append((s, phi))
        s, phi = max(solutions) if branch > 0 else min(solutions)
        return s, phi
