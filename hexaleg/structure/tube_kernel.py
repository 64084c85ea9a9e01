"""The tube choice compiled: which grid tubes hold, and the lightest triple bending within limits.

:func:`~.sizing.choose_tubes` is a loop over small arrays (a few hundred tubes, a hundred
cases), run several times for every design a decision sizes: in NumPy its time went to the
calls, not the arithmetic. The same steps here, compiled:

- :func:`holding_tubes`: whether each tube's worst ratio over the section loads is at
  most 1, the ratio as :func:`~.stresses.tube_stresses` and :func:`~.stresses.stress_ratio`
  compute it (the same operations in the same order);
- :func:`lightest_triple`: of each segment's holding tubes, those stiffer than every
  lighter one (the fronts: no other can be the lightest and still hold the deflection),
  a bound on the mass from a triple that holds (the tubes given as a hint, else each
  front walked up at the same share of its length), and the lightest triple whose foot
  deflects within the limit in every case: searched over the cases found binding (each
  case's deflection ‖b + x·c‖ bounds the tibia's 1/I x to an interval, the lightest tibia
  is the least stiff one inside them all), checked on every case, the worst added to them
  until it holds.

hexaleg's tests hold the choice against a brute force over every triple of a small grid.
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from hexaleg._compiled import compiled
from hexaleg._typing import ArrayF

IntArray = npt.NDArray[np.int64]


@compiled
def holding_tubes(
    rows: ArrayF,
    outer: ArrayF,
    area: ArrayF,
    moment: ArrayF,
    allowed: float,
    safety_factor: float,
    shear: float,
) -> npt.NDArray[np.bool_]:  # pragma: no cover - compiled; tested against the formulas
    """Whether each tube holds every row of section loads of each segment (3, n).

    A tube's ratio grows with each of |N|, |M_b| and |T|, so it holds every row when it
    holds their three maxima together, and breaks when one of the rows largest in one of
    them breaks it; only the tubes those two do not decide are loaded with every row.

    Args:
        rows: |N|, |M_b|, |T| (3 segments, R, 3) [N, N·m, N·m].
        outer: The tubes' outer diameters (n,) [m].
        area: Their areas (n,) [m²].
        moment: Their second moments (n,) [m⁴].
        allowed: Strength / safety factor [Pa].
        safety_factor: The safety factor [-] (the shear check's).
        shear: The shear strength [Pa], or 0 where the material has none.

    """
    count = outer.shape[0]
    out = np.zeros((3, count), dtype=np.bool_)
    for segment in range(3):
        loads = rows[segment]
        peaks = np.empty(3)
        largest = np.empty(3, dtype=np.int64)
        for k in range(3):
            largest[k] = np.argmax(loads[:, k])
            peaks[k] = loads[largest[k], k]
        for tube in range(count):
            limits = (outer[tube] / 2, area[tube], moment[tube], allowed, safety_factor, shear)
            if _ratio(peaks, *limits) <= 1:
                out[segment, tube] = True
                continue
            holds = True
            for k in range(3):
                if not _ratio(loads[largest[k]], *limits) <= 1:
                    holds = False
            if holds:
                for r in range(loads.shape[0]):
                    if not _ratio(loads[r], *limits) <= 1:
                        holds = False
                        break
            out[segment, tube] = holds
    return out


@compiled
def _ratio(
    load: ArrayF,
    fibre: float,
    area: float,
    moment: float,
    allowed: float,
    safety_factor: float,
    shear: float,
) -> float:  # pragma: no cover
    """The ratio [-] of one section load |N|, |M_b|, |T| (3,) on one tube (its D/2, A, I)."""
    sigma = load[0] / area + load[1] * fibre / moment
    tau = load[2] * fibre / (2 * moment)
    ratio = math.sqrt(sigma * sigma + 3 * (tau * tau)) / allowed
    if shear > 0:
        ratio = max(ratio, tau * safety_factor / shear)
    return ratio


@compiled
def lightest_triple(
    holds: npt.NDArray[np.bool_],
    order: IntArray,
    area: ArrayF,
    moment: ArrayF,
    masses_per_area: ArrayF,
    vectors: ArrayF,
    limit: float,
    active: IntArray,
    hint: IntArray,
) -> tuple[IntArray, IntArray]:  # pragma: no cover - compiled; tested by brute force
    """The lightest triple of holding tubes whose feet deflect within ``limit``, if any.

    Args:
        holds: Whether each tube holds each segment's loads (3, n) (:func:`holding_tubes`).
        order: The tubes by area, the stiffer first among equal areas (n,).
        area: Their areas (n,) [m²].
        moment: Their second moments (n,) [m⁴].
        masses_per_area: ρ·l of each segment (3,) [kg/m²]: a tube's mass is it times A.
        vectors: Each case's foot deflection per unit 1/I of each segment (C, 3, 3) [m⁵].
        limit: The deflection limit [m].
        active: The cases searched from the start (flat indices into ``vectors``).
        hint: Tubes (3,) likely to hold, or -1s.

    Returns:
        The triple (3,) of tube indices (-1s: none holds), and the cases added to
        ``active`` while searching.

    """
    fronts = [_front(holds[s], order, moment) for s in range(3)]
    none = -np.ones(3, dtype=np.int64)
    added = np.zeros(0, dtype=np.int64)
    for s in range(3):
        if fronts[s].shape[0] == 0:
            return none, added
    masses = [masses_per_area[s] * area[fronts[s]] for s in range(3)]
    inverse = [1.0 / moment[fronts[s]] for s in range(3)]
    bound = _hint_bound(holds, hint, area, moment, masses_per_area, vectors, limit)
    if bound == math.inf:
        bound = _share_bound(masses, inverse, vectors, limit)
    if bound < math.inf:  # no triple heavier than a feasible one can be the lightest
        for s, kept in enumerate(_within(masses, bound)):
            fronts[s], masses[s], inverse[s] = fronts[s][:kept], masses[s][:kept], inverse[s][:kept]
    cases, grams = list(active), _grams(vectors)
    while True:
        best = _least_mass(masses, inverse, grams, cases, limit)
        if best[0] < 0:
            return none, added
        x = np.array([inverse[0][best[0]], inverse[1][best[1]], inverse[2][best[2]]])
        worst, bent = _worst_bend(vectors, x)
        if bent <= limit:
            triple = np.array([fronts[0][best[0]], fronts[1][best[1]], fronts[2][best[2]]])
            return triple, added
        cases.append(worst)
        added = np.append(added, worst)


@compiled
def _hint_bound(
    holds: npt.NDArray[np.bool_],
    hint: IntArray,
    area: ArrayF,
    moment: ArrayF,
    masses_per_area: ArrayF,
    vectors: ArrayF,
    limit: float,
) -> float:  # pragma: no cover
    """The hint's mass [kg] if it holds every case (else inf, as without a hint: -1s)."""
    if hint[0] < 0 or not (holds[0, hint[0]] and holds[1, hint[1]] and holds[2, hint[2]]):
        return math.inf
    x = np.array([1.0 / moment[hint[0]], 1.0 / moment[hint[1]], 1.0 / moment[hint[2]]])
    if _worst_bend(vectors, x)[1] > limit:
        return math.inf
    return (
        masses_per_area[0] * area[hint[0]]
        + masses_per_area[1] * area[hint[1]]
        + (masses_per_area[2] * area[hint[2]])
    )


@compiled
def _within(masses: list[ArrayF], bound: float) -> IntArray:  # pragma: no cover
    """How many of each front's tubes (ascending masses) some triple within ``bound`` [kg] has.

    A tube is kept while it and the other fronts' lightest weigh no more than the bound
    (a little more: lest rounding drop the feasible triple the bound is).
    """
    floor = masses[0][0] + masses[1][0] + masses[2][0]
    room = bound - floor + 1e-9 * bound
    kept = np.zeros(3, dtype=np.int64)
    for s in range(3):
        while kept[s] < masses[s].shape[0] and masses[s][kept[s]] - masses[s][0] <= room:
            kept[s] += 1
    return kept


@compiled
def _front(
    holds: npt.NDArray[np.bool_], order: IntArray, moment: ArrayF
) -> IntArray:  # pragma: no cover
    """The holding tubes, by area, each stiffer (I) than every lighter one."""
    kept = np.empty(order.shape[0], dtype=np.int64)
    count, stiffest = 0, -math.inf
    for tube in order:
        if holds[tube] and moment[tube] > stiffest:
            kept[count] = tube
            count += 1
            stiffest = moment[tube]
    return kept[:count]


@compiled
def _bend(vectors: ArrayF, case: int, x: ArrayF) -> float:  # pragma: no cover
    """Case ``case``'s foot deflection [m] with the segments' 1/I ``x`` (3,) [m⁻⁴]."""
    total = 0.0
    for k in range(3):
        component = x[0] * vectors[case, 0, k] + x[1] * vectors[case, 1, k]
        component += x[2] * vectors[case, 2, k]
        total += component * component
    return math.sqrt(total)


@compiled
def _worst_bend(vectors: ArrayF, x: ArrayF) -> tuple[int, float]:  # pragma: no cover
    """The case of the largest deflection with 1/I ``x`` (3,), and that deflection [m]."""
    worst, largest = 0, -1.0
    for case in range(vectors.shape[0]):
        bent = _bend(vectors, case, x)
        if bent > largest:
            worst, largest = case, bent
    return worst, largest


@compiled
def _share_bound(
    masses: list[ArrayF], inverse: list[ArrayF], vectors: ArrayF, limit: float
) -> float:  # pragma: no cover
    """The mass of a triple that holds every case, or inf when none is found.

    Each front is walked up together, at the same share of its length: the first share
    whose triple holds, to 1/4096 of the way by bisection, bounds the lightest from above.
    """

    def at(share: float) -> IntArray:
        index = np.empty(3, dtype=np.int64)
        for s in range(3):
            end = masses[s].shape[0] - 1
            index[s] = min(round(share * end), end)
        return index

    def holds(index: IntArray) -> bool:
        x = np.array([inverse[0][index[0]], inverse[1][index[1]], inverse[2][index[2]]])
        return _worst_bend(vectors, x)[1] <= limit

    if not holds(at(1.0)):
        return math.inf
    low, high = 0.0, 1.0
    for _ in range(12):
        middle = (low + high) / 2
        if holds(at(middle)):
            high = middle
        else:
            low = middle
    index = at(high)
    return masses[0][index[0]] + masses[1][index[1]] + masses[2][index[2]]


@compiled
def _grams(vectors: ArrayF) -> ArrayF:  # pragma: no cover
    """Each case's products v_s·v_t of its segments' vectors (C, 6): 00, 01, 11, 02, 12, 22."""
    out = np.zeros((vectors.shape[0], 6))
    pairs = ((0, 0), (0, 1), (1, 1), (0, 2), (1, 2), (2, 2))
    for case in range(vectors.shape[0]):
        for p in range(6):
            s, t = pairs[p]
            total = 0.0
            for k in range(3):
                total += vectors[case, s, k] * vectors[case, t, k]
            out[case, p] = total
    return out


@compiled
def _least_mass(
    masses: list[ArrayF], inverse: list[ArrayF], grams: ArrayF, cases: list[int], limit: float
) -> IntArray:  # pragma: no cover
    """Indices into each front of the lightest triple within ``limit`` in ``cases`` (-1s: none).

    A case's deflection is ‖x_c·v_c + x_f·v_f + x·v_t‖ (x_c, x_f, x the segments' 1/I),
    within the limit on an interval of the tibia's x (a convex quadratic's sublevel set,
    written with the case's products v_s·v_t: ``grams``). The lightest tibia is the least
    stiff one inside every case's interval: the tibia's front runs from light (large 1/I)
    to stiff.
    """
    best = -np.ones(3, dtype=np.int64)
    lightest = math.inf
    tibias = inverse[2].shape[0]
    square_limit = limit * limit
    for i in range(masses[0].shape[0]):
        if masses[0][i] + masses[1][0] + masses[2][0] >= lightest:
            break
        xc = inverse[0][i]
        for j in range(masses[1].shape[0]):
            if masses[0][i] + masses[1][j] + masses[2][0] >= lightest:
                break
            xf = inverse[1][j]
            low, high = -math.inf, math.inf
            for case in cases:
                g = grams[case]
                bb = g[0] * xc * xc + 2 * g[1] * xc * xf + g[2] * xf * xf
                bc, cc = g[3] * xc + g[4] * xf, g[5]
                if cc > 0:
                    square = bc * bc - cc * (bb - square_limit)
                    if square < 0:
                        low, high = math.inf, -math.inf
                        break
                    root = math.sqrt(square)
                    low, high = max(low, (-bc - root) / cc), min(high, (-bc + root) / cc)
                elif bb > square_limit:
                    low, high = math.inf, -math.inf
                    break
            if low > high:
                continue
            first = _first_at_most(inverse[2], high)  # the least stiff tibia below high
            if first < tibias and inverse[2][first] >= low:
                total = masses[0][i] + masses[1][j] + masses[2][first]
                if total < lightest:
                    lightest = total
                    best[0], best[1], best[2] = i, j, first
    return best


@compiled
def _first_at_most(descending: ArrayF, value: float) -> int:  # pragma: no cover
    """The first index of ``descending`` whose value is at most ``value`` (its length: none)."""
    low, high = 0, descending.shape[0]
    while low < high:
        middle = (low + high) // 2
        if descending[middle] <= value:
            high = middle
        else:
            low = middle + 1
    return low
