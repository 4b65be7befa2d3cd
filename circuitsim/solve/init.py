"""Consistent initial values, shared by the transient and the operating point.

Given the differential states, the algebraic states and all derivatives are solved for (IDA's
own correction does not give the derivatives of algebraic unknowns; a wrong y' there makes
the first step fail)."""

from __future__ import annotations

import numpy as np

from circuitsim.errors import SolverError, spoken


def _newton_matrix(model, t0: float, y: np.ndarray, yp: np.ndarray, p, nd: int):
    """[dF/dy' of the differential | dF/dy of the algebraic unknowns], dF/dy of the
    differential ones, and dF/dt: sparse for a large model, dense otherwise."""
    if model.linsolver == "sparse":
        import scipy.sparse as sps

        Fy, Fyp, Ft = model.sparse_parts(t0, y, yp, p)
        return sps.hstack([Fyp[:, :nd], Fy[:, nd:]], format="csc"), Fy[:, :nd], Ft
    _, _, parts, _, _ = model.fns
    Fy, Fyp, Ft = parts(t0, y, yp, p)
    return np.hstack([Fyp[:, :nd], Fy[:, nd:]]), Fy[:, :nd], Ft


def _solve(A, b: np.ndarray, least_squares: bool = False) -> np.ndarray:
    """A x = b, or its least-squares solution if A is singular (or when asked)."""
    if not isinstance(A, np.ndarray):
        import scipy.sparse.linalg as spla

        try:
            if not least_squares:
                x = spla.splu(A).solve(b)
                if np.all(np.isfinite(x)):
                    return x
        except RuntimeError:  # exactly singular
            pass
        return spla.lsqr(A, b, atol=1e-14, btol=1e-14)[0]
    if least_squares:
        return np.linalg.lstsq(A, b, rcond=None)[0]
    try:
        return np.linalg.solve(A, b)
    except np.linalg.LinAlgError:
        return np.linalg.lstsq(A, b, rcond=None)[0]


def consistent_initial(model, t0: float, y: np.ndarray, p: tuple[float, ...],
                       yp_guess: np.ndarray | None = None, tol: float = 1e-10,
                       max_iter: int = 60) -> tuple[np.ndarray, np.ndarray]:
    """Given the differential states in ``y``, solve F = 0 for the algebraic states and the
    derivatives of the differential ones (damped Newton with the analytic Jacobian), then the
    derivatives of the algebraic states from dF/dt = 0.

    Raises SolverError naming the equation that could not be satisfied.
    """
    nd = model.meta["n_diff"]
    y = np.array(y, float)
    yp = np.zeros(len(y)) if yp_guess is None else np.array(yp_guess, float)
    y, yp = _newton(model, t0, y, yp, p, nd, tol, max_iter)
    if nd == len(y):  # no algebraic unknowns: every y' is Newton's already
        return y, yp
    # d/dt F = Ft + Fy y' + Fyp y'' = 0; unknowns: y' of algebraic, y'' of differential.
    A, Fy_d, Ft = _newton_matrix(model, t0, y, yp, p, nd)
    # a derivative that does not exist at t0 (x**n/x at x = 0) leaves the algebraic y' at 0:
    # they only seed the integrator, which corrects them on its first step
    finite = np.all(np.isfinite(A.data if not isinstance(A, np.ndarray) else A))
    if finite and np.all(np.isfinite(Ft)):
        rhs = -(Ft + Fy_d @ yp[:nd])
        yp[nd:] = _solve(A, rhs, least_squares=isinstance(A, np.ndarray))[nd:]
    return y, yp


def _newton(model, t0: float, y: np.ndarray, yp: np.ndarray, p, nd: int, tol: float,
            max_iter: int) -> tuple[np.ndarray, np.ndarray]:
    """Damped Newton on F(t0, y, y') = 0 for y' of the differential and y of the algebraic
    unknowns."""
    residual = model.fns[0]
    n = len(y)
    res = np.zeros(n)

    def F(y_, yp_):
        residual(t0, y_, yp_, res, p)
        return res.copy()

    f = F(y, yp)
    for _ in range(max_iter):
        if np.max(np.abs(f), initial=0.0) < tol * (1 + np.max(np.abs(y), initial=0.0)):
            return y, yp
        A, _, _ = _newton_matrix(model, t0, y, yp, p, nd)
        if not (np.all(np.isfinite(A.data if not isinstance(A, np.ndarray) else A))
                and np.all(np.isfinite(f))):  # LAPACK's SVD would fail with no words
            raise SolverError(f"no consistent initial values at t = {t0:g} s: the equations "
                              f"or their derivatives are not finite there (inf or NaN): a "
                              f"value overflows the arithmetic, or a quantity is divided by "
                              f"zero at the start")
        dz = _solve(A, -f)
        step = 1.0
        norm0 = np.linalg.norm(f)
        for _ in range(30):
            yp_t, y_t = yp.copy(), y.copy()
            yp_t[:nd] += step * dz[:nd]
            y_t[nd:] += step * dz[nd:]
            f_t = F(y_t, yp_t)
            if np.all(np.isfinite(f_t)) and np.linalg.norm(f_t) < (1 - 1e-4 * step) * norm0:
                break
            step *= 0.5
        y, yp, f = y_t, yp_t, f_t
    if np.max(np.abs(f), initial=0.0) < tol * (1 + np.max(np.abs(y), initial=0.0)):
        return y, yp
    worst = int(np.argmax(np.abs(f)))
    raise SolverError(f"no consistent initial values at t = {t0:g} s: residual of "
                      f"equation {worst} stays at {f[worst]:.3g} (state "
                      f"{spoken(model.state_names[worst]) if worst < n else '?'}). Try "
                      f"init: op, or give initial values")


def initial_state(model, t0: float, p: tuple[float, ...],
                  overridden: frozenset[str] = frozenset()) -> tuple[np.ndarray, list[str]]:
    """Differential states at rest, then the components' initial values applied.

    A value given for a state is set directly; one given for an expression of states (a
    capacitor between two floating nodes, an eliminated inductor current) is met by the
    smallest change of the differential states (Gauss-Newton, minimum norm). Returns the
    states and a description of every initial value that conflicts with the others.
    """
    n = len(model.state_names)
    nd = model.meta["n_diff"]
    y = np.zeros(n)
    _, _, _, _, initial = model.fns
    entries = model.meta["initial"]
    k = len(entries)
    if not k:
        return y, []
    target = np.array(initial(t0, y, np.zeros(n), p)[:k], float)
    # Only initial values written in the netlist are constraints; a parameter's default
    # (i0 = 0, v0 = 0) is just "from rest" and yields to them.
    strong = _given(model, overridden)
    direct = [(j, idx) for j, (_, idx, _) in enumerate(entries) if 0 <= idx < nd and
              strong[j]]
    for j, idx in direct:
        y[idx] = target[j]

    def lhs(yy: np.ndarray) -> np.ndarray:
        return np.array(initial(t0, yy, np.zeros(n), p)[k:], float)

    others = [j for j in range(k) if strong[j] and j not in {d for d, _ in direct}]
    for _ in range(8):
        gap = (target - lhs(y))[others]
        if not others or np.max(np.abs(gap)) <= 1e-12 * (1 + np.max(np.abs(target))):
            break
        G = np.zeros((len(others), nd))
        for c in range(nd):
            h = 1e-7 * (1 + abs(y[c]))
            yy = y.copy()
            yy[c] += h
            G[:, c] = (lhs(yy)[others] - lhs(y)[others]) / h
        y[:nd] += np.linalg.lstsq(G, gap, rcond=None)[0]
    gap = target - lhs(y)
    bad = [f"{entries[j][0]} = {target[j]:.6g} (got {target[j] - gap[j]:.6g})"
           for j in others if abs(gap[j]) > 1e-9 * (1 + abs(target[j]))]
    return y, bad


def check_initial(model, t0: float, y: np.ndarray, yp: np.ndarray,
                  p: tuple[float, ...], overridden: frozenset[str] = frozenset()) -> list[str]:
    """Initial values that the consistent start could not honour (for a warning)."""
    _, _, _, _, initial = model.fns
    k = len(model.meta["initial"])
    if not k:
        return []
    vals = np.array(initial(t0, y, yp, p), float)
    target, got = vals[:k], vals[k:]
    strong = _given(model, overridden)
    return [f"{name} = {target[j]:.6g} (the circuit gives {got[j]:.6g})"
            for j, (name, _, _) in enumerate(model.meta["initial"])
            if strong[j] and abs(got[j] - target[j]) > 1e-6 * (1 + abs(target[j]))]


def _given(model, overridden: frozenset[str] = frozenset()) -> list[bool]:
    """Which initial-value entries come from values written in the netlist or overridden
    at run time (``params``)."""
    explicit = {name for c in model.netlist.components for name, v in c.values.items()
                if v.explicit or name in overridden}
    return [any(q in explicit for q in params) for _, _, params in model.meta["initial"]]
