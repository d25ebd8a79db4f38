"""Ready-made linkages, each defined once with the public API and reused everywhere.

Every entry is built the way a user builds a linkage: vectors, loops, a
:class:`~symlink.symbolic.linkage.Linkage`.  Nothing here is special-cased elsewhere;
:data:`CATALOG` maps the names used by ``symlink plan NAME`` to the builders.

>>> linkage = fourbar()
>>> linkage.unknowns
(beta, phi)
>>> sorted(CATALOG)  # doctest: +NORMALIZE_WHITESPACE
['fivebar', 'fourbar', 'inverted-slider-crank', 'jansen', 'offset-inverted-slider-crank', 'slider-crank', 'stephenson2',
 'watt2']
"""
from __future__ import annotations

import math

import sympy as sp

from ..symbolic.linkage import Linkage
from ..symbolic.loops import Loop
from ..symbolic.vectors import Vector, coordinates, lengths

__all__ = ["fourbar", "slider_crank", "inverted_slider_crank", "offset_inverted_slider_crank", "watt2", "stephenson2", "stephenson3", "fivebar", "jansen",
           "JANSEN_HOLY_NUMBERS", "jansen_parameters", "CATALOG", "EXAMPLE_VALUES", "with_point"]


def transmission_angle(coupler_angle: sp.Expr, rocker_angle: sp.Expr) -> sp.Expr:
    """Interior angle at the coupler-rocker joint, in [0, pi], accurate near 0 and pi (atan2, not acos)."""
    difference = coupler_angle - rocker_angle
    return sp.Abs(sp.atan2(sp.sin(difference), sp.cos(difference)))


def with_point(linkage: Linkage, through: str, angle: sp.Expr, name: str | None = None) -> Linkage:
    """``linkage`` with a point ``P = through + (u + i v) e^{i angle}``: a point on the link of angle ``angle``.

    ``u`` runs along the link from the point ``through``, ``v`` to its left; both become
    parameters (a coupler point for synthesis, a foot, a pen).  ``name`` defaults to the
    linkage's name with ``_point``.

    Parameters
    ----------
    linkage : Linkage
        The linkage to add the point to (left unchanged).
    through : str
        The named point (``"B"``) or joint the link passes through; ``u`` and ``v`` are measured from it.
    angle : sympy.Expr
        The angle of the link that carries the point (``linkage.roles["coupler"]``).
    name : str, optional
        The new linkage's name; default the linkage's name with ``_point``.

    Returns
    -------
    Linkage
        A new linkage with the point ``P`` (outputs ``P_x``, ``P_y``) and the parameters ``u`` and ``v`` last.

    Examples
    --------
    >>> import symlink
    >>> linkage = symlink.fourbar()
    >>> with_coupler = symlink.with_point(linkage, "B", linkage.roles["coupler"])
    >>> with_coupler.name, [str(p) for p in with_coupler.parameters][-2:]
    ('fourbar_point', ['u', 'v'])
    """
    u, v = sp.symbols("u v", real=True)
    start = linkage.points[through]  # None: the frame's origin
    along = Vector(u, angle, f"{through}U")
    point = (along if start is None else start + along) + Vector(v, angle + sp.pi / 2, "UP")
    return Linkage(name or f"{linkage.name}_point", linkage.loops, linkage.inputs, linkage.unknowns,
                   parameters=list(linkage.parameters) + [u, v], points={**linkage.points, "P": point},
                   roles=linkage.roles, extras=linkage.extras)


def fourbar() -> Linkage:
    """The four-bar of the conventions (crank at A, rocker pivot D = (d, 0)), closed as in the Maple worksheet.

    Crank a = AB at theta from pivot A at the origin, coupler b = BC at beta,
    rocker c = DC at phi from pivot D at (d, 0):
    ``a e^{i theta} + b e^{i beta} = d + c e^{i phi}``.  Branch +1 puts C to
    the left of the line from B to D.

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta``, unknowns
        ``beta, phi`` (roles crank, coupler, rocker), parameters ``a, b, c, d``; case 3: two angles.
        Example values: ``EXAMPLE_VALUES["fourbar"]``.

    Examples
    --------
    >>> import math, symlink
    >>> result = symlink.Solver(symlink.fourbar(), ["rocker"])(theta=0.0, a=20, b=66, c=56, d=80, branch=1)
    >>> round(math.degrees(float(result["rocker"])), 2)  # seed 003 at theta = 0
    110.74
    """
    theta, beta, phi = coordinates("theta beta phi")
    a, b, c, d = lengths("a b c d")
    AB, BC = Vector(a, theta, "AB"), Vector(b, beta, "BC")
    DC, AD = Vector(c, phi, "DC"), Vector(d, 0, "AD")
    closure = Loop(AD + DC - BC - AB, name="ABCD")
    return Linkage(
        "fourbar", [closure], inputs=[theta], unknowns=[beta, phi],
        points={"A": None, "B": AB.as_sum(), "C": AB + BC, "D": AD.as_sum()},
        roles={"crank": theta, "coupler": beta, "rocker": phi},
        extras={"transmission": transmission_angle(beta, phi)},
    )


def slider_crank() -> Linkage:
    """The slider-crank with offset: ``a e^{i theta} + b e^{i beta} = s + i offset``.

    ::

            B
           / \\  b (conrod, beta)
        a /   \\
         /     C ===[slider]===  y = offset, C = (s, offset)
        A (theta)
        ======================= x

    Crank a = AB at theta from A at the origin, connecting rod b = BC at beta,
    slider pin C at x = s on the line y = offset (any sign).  Branch +1 is the
    assembly with the larger s (the slider to the right of the crank pin).

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta``, unknowns
        ``beta, s`` (roles crank, conrod, slider), parameters ``a, b, offset``; case 2b: a length and an angle of different vectors.
        Example values: ``EXAMPLE_VALUES["slider-crank"]``.

    Examples
    --------
    >>> linkage = slider_crank()
    >>> [step.case.name for step in linkage.plan], linkage.parameters
    (['2b'], (a, b, offset))
    """
    theta, beta, s = coordinates("theta beta s")
    a, b = lengths("a b")
    offset = sp.Symbol("offset", real=True)
    AB, BC = Vector(a, theta, "AB"), Vector(b, beta, "BC")
    travel, guide = Vector(s, 0, "AS"), Vector(offset, sp.pi / 2, "SC")
    closure = Loop(AB + BC - guide - travel, name="ABC")
    return Linkage(
        "slider-crank", [closure], inputs=[theta], unknowns=[beta, s],
        points={"A": None, "B": AB.as_sum(), "C": travel + guide},
        roles={"crank": theta, "conrod": beta, "slider": s},
    )


def inverted_slider_crank() -> Linkage:
    """The inverted slider-crank (crank-shaper, Whitworth quick return): a slider on a rotating rocker.

    ::

                B  <- block pinned to the crank at B, sliding on the rocker
               /|
            a / | r (slider, along the rocker)
             /  |
            A   D (phi: rocker angle, about D)
        ====^===^====   A at the origin, D at (d, 0)

    Crank a = AB at theta from A; the rocker turns about D = (d, 0) and its
    guide passes through D, so the block at B sits at distance r along the
    rocker at angle phi: ``a e^{i theta} = d + r e^{i phi}``.  With d < a the
    rocker turns fully (Whitworth), with d > a it swings (crank-shaper).  One
    assembly (r >= 0); undefined where B passes over D.

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta``, unknowns
        ``phi, r`` (roles crank, rocker, slider), parameters ``a, d``; case 2a: length and angle of one vector.
        Example values: ``EXAMPLE_VALUES["inverted-slider-crank"]``.

    Examples
    --------
    >>> linkage = inverted_slider_crank()
    >>> [step.case.name for step in linkage.plan], linkage.branches
    (['2a'], ())
    """
    theta, phi, r = coordinates("theta phi r")
    a, d = lengths("a d")
    AB, DB, AD = Vector(a, theta, "AB"), Vector(r, phi, "DB"), Vector(d, 0, "AD")
    closure = Loop(AB - DB - AD, name="ABD")
    return Linkage(
        "inverted-slider-crank", [closure], inputs=[theta], unknowns=[phi, r],
        points={"A": None, "B": AB.as_sum(), "D": AD.as_sum()},
        roles={"crank": theta, "rocker": phi, "slider": r},
    )


def offset_inverted_slider_crank() -> Linkage:
    r"""The inverted slider-crank with its guide offset from the rocker pivot by ``e``.

    ::

                  B  <- block pinned to the crank at B, sliding along the guide
                 /|
              a / | s (along the guide, from its foot T)
               /  T
              A    \ e (perpendicular offset, turning with the rocker)
        ====^=======D====   A at the origin, D at (d, 0)

    The guide turns with the rocker: its foot is T = D + e e^{i (phi + pi/2)}
    and the block sits at distance s along it, ``a e^{i theta} = d +
    e e^{i (phi + pi/2)} + s e^{i phi}``.  The rocker angle turns two vectors
    (the offset and the guide), so the loop is solved in closed form as one
    vector of constant length and offset angle (case 2c).  Branch +1: the
    larger s (the guide a tangent from B to the circle of radius e about D).

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta``, unknowns
        ``phi, s`` (roles crank, rocker, slider), parameters ``a, d, e``; case 2c: one angle turning two vectors, and a length.
        Example values: ``EXAMPLE_VALUES["offset-inverted-slider-crank"]``.

    Examples
    --------
    >>> linkage = offset_inverted_slider_crank()
    >>> [step.case.name for step in linkage.plan], [b.name for b in linkage.branches]
    (['2c'], ['branch'])
    """
    theta, phi, s = coordinates("theta phi s")
    a, d, e = lengths("a d e")
    AB, AD = Vector(a, theta, "AB"), Vector(d, 0, "AD")
    DT, TB = Vector(e, phi + sp.pi / 2, "DT"), Vector(s, phi, "TB")
    closure = Loop(AB - TB - DT - AD, name="ABTD")  # walked A -> B -> T -> D -> A
    return Linkage(
        "offset-inverted-slider-crank", [closure], inputs=[theta], unknowns=[phi, s],
        points={"A": None, "B": AB.as_sum(), "D": AD.as_sum(), "T": AD + DT},
        roles={"crank": theta, "rocker": phi, "slider": s},
    )


def watt2() -> Linkage:
    """Watt II six-bar: two four-bars in series sharing the ternary rocker DCE.

    ::

                C                  F
               / \\               / \\
            b /   \\ c         f /   \\ g
             /     \\   E ------'     \\
            B       \\ / e             \\
           a \\       D                 G = (gx, gy)
              A
        ======^=======^=================^====   ground: A, D, G

    Loop ABCD is the four-bar of :func:`fourbar` (crank a at theta, coupler
    b at beta, rocker c = DC at phi, D at (d, 0)).  The rocker is a ternary
    link: DE = e at phi + alpha (alpha fixed).  Loop DEFG: coupler f = EF at
    mu, output rocker g = GF at psi about G = (gx, gy):
    ``d + e e^{i(phi + alpha)} + f e^{i mu} = gx + i gy + g e^{i psi}``.
    The ternary ground (A, D, G) and ternary rocker (D, C, E) are adjacent, so
    each loop in turn has two unknowns: (beta, phi), then (mu, psi).  Branch
    signs as in the four-bar: C left of B->D, F left of E->G.

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta``, unknowns
        ``beta, phi, mu, psi`` (roles crank, coupler, rocker, coupler2, output), parameters ``a, b, c, d, e, f, g, alpha, gx, gy``; two loops of case 3, in series.
        Example values: ``EXAMPLE_VALUES["watt2"]``.

    Examples
    --------
    >>> [(step.loop.name, step.case.name) for step in watt2().plan]
    [('ABCD', '3'), ('DEFG', '3')]
    """
    theta, beta, phi, mu, psi = coordinates("theta beta phi mu psi")
    a, b, c, d, e, f, g = lengths("a b c d e f g")
    alpha, gx, gy = sp.symbols("alpha gx gy", real=True)
    AB, BC, DC, AD = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(c, phi, "DC"), Vector(d, 0, "AD")
    DE, EF, GF = Vector(e, phi + alpha, "DE"), Vector(f, mu, "EF"), Vector(g, psi, "GF")
    AG = Vector(gx, 0, "AGx") + Vector(gy, sp.pi / 2, "AGy")
    first = Loop(AD + DC - BC - AB, name="ABCD")
    second = Loop(AG + GF - EF - DE - AD, name="DEFG")
    return Linkage(
        "watt2", [first, second], inputs=[theta], unknowns=[beta, phi, mu, psi],
        parameters=[a, b, c, d, e, f, g, alpha, gx, gy],
        points={"A": None, "B": AB.as_sum(), "C": AB + BC, "D": AD.as_sum(), "E": AD + DE,
                "F": AD + DE + EF, "G": AG},
        roles={"crank": theta, "coupler": beta, "rocker": phi, "coupler2": mu, "output": psi},
    )


def stephenson2() -> Linkage:
    """Stephenson II six-bar: the ground is a binary link between the crank and a ternary link.

    ::

              E -------- g -------- H
             /  \\                 / \\
          e /    \\              h/   \\
           / alpha\\   c         /delta\\
          B ------ C ---------- F       \\   BCE and DFH are ternary links,
          |    b                  \\ f    |   joined by the binary links CF and EH
        a |                        \\     |
          A (theta)                  D (phi)
        ==^==========================^=====   ground: A at the origin, D at (d, 0)

    Crank a = AB at theta; ternary coupler BCE (BC = b at beta, BE = e at
    beta + alpha); ternary rocker DFH about D (DF = f at phi, DH = h at
    phi + delta); binary links CF = c at mu and EH = g at eta.  Loops
    ``ABCFD: a e^{i theta} + b e^{i beta} + c e^{i mu} = d + f e^{i phi}`` and
    ``ABEHD: a e^{i theta} + e e^{i(beta + alpha)} + g e^{i eta} = d + h e^{i(phi + delta)}``.
    The two ternary links are not adjacent (a Stephenson chain) and the
    ground holds the crank and the ternary rocker, so every loop has three
    unknowns whatever the order: there is no loop-by-loop closed form, and
    the linkage is solved numerically (:class:`symlink.numeric.solver.NumericSolver`); it has up to
    six assemblies, chosen by the initial guess.

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta``, unknowns
        ``beta, mu, phi, eta`` (roles crank, coupler, rocker), parameters ``a, b, c, d, e, f, g, h, alpha, delta``; no closed form: solve it with :class:`~symlink.numeric.solver.NumericSolver`.
        Example values: ``EXAMPLE_VALUES["stephenson2"]``.

    Examples
    --------
    >>> stephenson2().has_closed_form
    False
    """
    theta, beta, mu, phi, eta = coordinates("theta beta mu phi eta")
    a, b, c, d, e, f, g, h = lengths("a b c d e f g h")
    alpha, delta = sp.symbols("alpha delta", real=True)
    AB, BC, BE = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(e, beta + alpha, "BE")
    CF, EH, AD = Vector(c, mu, "CF"), Vector(g, eta, "EH"), Vector(d, 0, "AD")
    DF, DH = Vector(f, phi, "DF"), Vector(h, phi + delta, "DH")
    outer = Loop(AB + BC + CF - DF - AD, name="ABCFD")
    inner = Loop(AB + BE + EH - DH - AD, name="ABEHD")
    return Linkage(
        "stephenson2", [outer, inner], inputs=[theta], unknowns=[beta, mu, phi, eta],
        parameters=[a, b, c, d, e, f, g, h, alpha, delta],
        points={"A": None, "B": AB.as_sum(), "C": AB + BC, "E": AB + BE, "D": AD.as_sum(),
                "F": AD + DF, "H": AD + DH},
        roles={"crank": theta, "coupler": beta, "rocker": phi},
    )


def stephenson3() -> Linkage:
    """:func:`stephenson2` by its former name, with a one-line note (``DeprecationWarning``) saying so.

    symlink numbered the Stephenson six-bars II and III the other way before it followed the numbering its atlas
    cites (:mod:`symlink.mechanism.atlas`); code written for the old name keeps working.

    Returns
    -------
    Linkage
        The catalog's Stephenson six-bar (its ground a binary link pinned to one ternary link).

    Examples
    --------
    >>> import warnings, symlink
    >>> with warnings.catch_warnings():
    ...     warnings.simplefilter("ignore")
    ...     symlink.stephenson3().name
    'stephenson2'
    """
    import warnings
    warnings.warn("symlink.stephenson3 is the former name of symlink.stephenson2 (the Stephenson six-bar whose ground "
                  "is a binary link pinned to one ternary link)", DeprecationWarning, stacklevel=2)
    return stephenson2()


def fivebar() -> Linkage:
    """The five-bar with two inputs (two degrees of freedom), e.g. a planar parallel robot.

    ::

                   C
                  / \\
               b /   \\ c
                /     \\
               B       D
            a /         \\ e
             A (theta)   E (psi)
        =====^===========^=====   A at the origin, E at (d, 0)

    Cranks a = AB at theta and e = ED at psi are both driven; the links
    b = BC at beta and c = DC at phi meet at C:
    ``a e^{i theta} + b e^{i beta} = d + e e^{i psi} + c e^{i phi}``.  One
    loop with two unknowns (case 3); branch +1 puts C left of the line B->D.

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta, psi``, unknowns
        ``beta, phi`` (roles crank, crank2, coupler, coupler2), parameters ``a, b, c, d, e``; case 3, with two inputs.
        Example values: ``EXAMPLE_VALUES["fivebar"]``.

    Examples
    --------
    >>> linkage = fivebar()
    >>> linkage.inputs, [step.case.name for step in linkage.plan]
    ((theta, psi), ['3'])
    """
    theta, psi, beta, phi = coordinates("theta psi beta phi")
    a, b, c, d, e = lengths("a b c d e")
    AB, BC, DC = Vector(a, theta, "AB"), Vector(b, beta, "BC"), Vector(c, phi, "DC")
    ED, AE = Vector(e, psi, "ED"), Vector(d, 0, "AE")
    closure = Loop(AE + ED + DC - BC - AB, name="ABCDE")
    return Linkage(
        "fivebar", [closure], inputs=[theta, psi], unknowns=[beta, phi],
        points={"A": None, "B": AB.as_sum(), "C": AB + BC, "D": AE + ED, "E": AE.as_sum()},
        roles={"crank": theta, "crank2": psi, "coupler": beta, "coupler2": phi},
    )


#: Theo Jansen's "holy numbers" (strandbeest.com, "Explains"; the lengths of the Wikipedia article
#: "Jansen's linkage"), in his letters: a and l place the fixed pivot D relative to the crank axle A,
#: m is the crank; j and k join the crank pin to the upper and lower rockers b and c; b, d, e are
#: the upper triangle, f and g join it to the lower triangle g, h, i, whose corner H is the foot.
JANSEN_HOLY_NUMBERS = dict(a=38.0, b=41.5, c=39.3, d=40.1, e=55.8, f=39.4, g=36.7, h=65.7,
                           i=49.0, j=50.0, k=61.9, l=7.8, m=15.0)


def jansen_parameters(numbers: dict[str, float] | None = None) -> dict[str, float]:
    """The parameters of :func:`jansen` from Jansen's 13 lengths (default: the holy numbers).

    The triangles are rigid, so their third sides e and h enter as the corner
    angles opposite them (law of cosines): alpha at D between DC (b) and DE
    (d), gamma at F between FG (g) and FH (i).

    Parameters
    ----------
    numbers : dict of str to float, optional
        Jansen's 13 lengths by letter (``a`` to ``m``); default :data:`JANSEN_HOLY_NUMBERS`.

    Returns
    -------
    dict of str to float
        The values :func:`jansen` takes: the lengths less e and h, and alpha and gamma in radians.

    Raises
    ------
    KeyError
        A letter missing from ``numbers``.

    Examples
    --------
    >>> values = jansen_parameters()
    >>> round(math.degrees(values["alpha"]), 4), round(math.degrees(values["gamma"]), 4)
    (86.2683, 99.0963)
    """
    n = dict(JANSEN_HOLY_NUMBERS if numbers is None else numbers)
    alpha = math.acos((n["b"] ** 2 + n["d"] ** 2 - n["e"] ** 2) / (2 * n["b"] * n["d"]))
    gamma = math.acos((n["g"] ** 2 + n["i"] ** 2 - n["h"] ** 2) / (2 * n["g"] * n["i"]))
    values = {k: v for k, v in n.items() if k not in ("e", "h")}
    return values | {"alpha": alpha, "gamma": gamma}


def jansen() -> Linkage:
    """Theo Jansen's strandbeest leg: one crank, eight links, three four-bar-like loops in a chain.

    Crank axle A at the origin, crank pin B (AB = m at theta), fixed pivot D
    at (-a, -l); the upper triangle DCE (sides b, e, d) and the lower rocker
    DF (c) turn about D; the links j = BC and k = BF drive them from the
    crank pin; the tie f = EG and the lower triangle FGH (sides g, h, i)
    carry the foot H.  With the holy numbers at theta = 0 the joints are
    near B (15, 0), C (-24, 31), D (-38, -8), E (-75, 8), F (-27, -45),
    G (-59, -28) and the foot H (-43, -92): the leg hangs left of and below
    the crank.

    Lengths in Jansen's letters (:data:`JANSEN_HOLY_NUMBERS`; e and h enter
    as the triangle angles alpha and gamma, :func:`jansen_parameters`).  The
    loops, each with two unknown angles (case 3), solved in turn:

    * ``ABCD``: ``AD + DC = AB + BC``, upper rocker DC = b at phi and
      j = BC at beta; branch +1 puts C left of the line D -> B;
    * ``ABFD``: ``AB + BF = AD + DF``, k = BF at mu and lower rocker
      DF = c at psi; branch +1 puts F left of B -> D;
    * ``DFGE``: ``DF + FG = DE + EG`` with DE = d at phi + alpha, the lower
      triangle's side FG = g at eta and f = EG at kappa; branch +1 puts G
      left of F -> E.  The foot is H = F + FH, FH = i at eta + gamma.

    Every branch +1 is Jansen's leg (the foot below the crank).

    Returns
    -------
    Linkage
        A new linkage each call (change it freely): inputs ``theta``, unknowns
        ``phi, beta, mu, psi, eta, kappa`` (roles upper_rocker, upper_link, lower_link, lower_rocker, leg, tie), parameters ``a, b, c, d, f, g, i, j, k, l, m, alpha, gamma``; three loops of case 3 (the holy numbers in :func:`jansen_parameters`).
        Example values: ``EXAMPLE_VALUES["jansen"]``.

    Examples
    --------
    >>> linkage = jansen()
    >>> [(step.loop.name, step.case.name) for step in linkage.plan]
    [('ABCD', '3'), ('ABFD', '3'), ('DFGE', '3')]
    """
    theta, phi, beta, mu, psi, eta, kappa = coordinates("theta phi beta mu psi eta kappa")
    a, b, c, d, f, g, i, j, k, l, m = lengths("a b c d f g i j k l m")
    alpha, gamma = sp.symbols("alpha gamma", real=True)
    AB, BC, BF = Vector(m, theta, "AB"), Vector(j, beta, "BC"), Vector(k, mu, "BF")
    ADx, ADy = Vector(a, sp.pi, "ADx"), Vector(l, -sp.pi / 2, "ADy")
    AD = ADx + ADy
    DC, DE, DF = Vector(b, phi, "DC"), Vector(d, phi + alpha, "DE"), Vector(c, psi, "DF")
    FG, FH, EG = Vector(g, eta, "FG"), Vector(i, eta + gamma, "FH"), Vector(f, kappa, "EG")
    upper = Loop(AD + DC - BC - AB, name="ABCD")
    lower = Loop(AB + BF - DF - ADy - ADx, name="ABFD")  # terms in walking order: A, B, F, D, A
    legs = Loop(DF + FG - EG - DE, name="DFGE")
    return Linkage(
        "jansen", [upper, lower, legs], inputs=[theta], unknowns=[phi, beta, mu, psi, eta, kappa],
        parameters=[a, b, c, d, f, g, i, j, k, l, m, alpha, gamma],
        points={"A": None, "B": AB.as_sum(), "C": AD + DC, "D": AD, "E": AD + DE, "F": AD + DF,
                "G": AD + DF + FG, "H": AD + DF + FH},
        roles={"crank": theta, "upper_rocker": phi, "upper_link": beta, "lower_link": mu, "lower_rocker": psi,
               "leg": eta, "tie": kappa},
    )


#: Catalog entries by name: functions that build a fresh :class:`Linkage`.
CATALOG = {
    "fourbar": fourbar,
    "slider-crank": slider_crank,
    "inverted-slider-crank": inverted_slider_crank,
    "offset-inverted-slider-crank": offset_inverted_slider_crank,
    "watt2": watt2,
    "stephenson2": stephenson2,
    "fivebar": fivebar,
    "jansen": jansen,
}

#: Example dimensions of each entry (the defaults of its shipped linkage file, ``symlink/linkages/``): the four-bar
#: of the C-program paper (20, 66, 56, 80), Jansen's holy numbers, and for the others dimensions whose input turns fully.
EXAMPLE_VALUES = {
    "fourbar": dict(a=20.0, b=66.0, c=56.0, d=80.0),
    "slider-crank": dict(a=1.3, b=4.1, offset=0.7),
    "inverted-slider-crank": dict(a=2.0, d=1.2),
    "offset-inverted-slider-crank": dict(a=1.0, d=2.5, e=0.4),
    "watt2": dict(a=1.0, b=3.5, c=3.0, d=3.2, e=2.0, f=4.0, g=3.0, alpha=0.6, gx=4.5, gy=3.5),
    "stephenson2": dict(a=1.0, b=3.1, c=2.2, d=4.5, e=3.9, f=3.1, g=4.1, h=3.1, alpha=0.9, delta=0.3),
    "fivebar": dict(a=2.0, b=4.0, c=4.0, d=3.0, e=2.0, psi=2.2),
    "jansen": jansen_parameters(),
}
