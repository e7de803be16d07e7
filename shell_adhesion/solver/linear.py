"""Sparse direct solves of the free block of the tangent, K_ff dx = b.

Two factorisations of the same matrix:

- "qdldl": a sparse LDL^T (QDLDL, with an AMD ordering) of the whole tangent with the
  prescribed dofs' rows and columns replaced by the identity.  The sparsity pattern is then
  the discretisation's, whatever the constraints, so the ordering and the symbolic analysis
  are done once per pattern and thread (shared by the loading and relaxation paths that
  follow each other there) and every later factorisation is numeric only.  QDLDL does not
  pivot: every solve is checked for finite values and the first solve of each
  factorisation for its backward error (below `BACKWARD_ERROR`); a factorisation that
  fails is redone by SuperLU, and after MAX_FAILURES in a row the path keeps to SuperLU.
- "superlu": scipy's SuperLU of the free block (the fallback, and the only one when QDLDL
  cannot be imported or the fast solver is switched off).

The chosen solver and the number of fallbacks are counted in the path's Timer.
"""
from dataclasses import dataclass, fields
import threading
import time
import weakref

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

try:
    import qdldl
except ImportError:       # the fast solver is optional: SuperLU does the work then
    qdldl = None

MAX_FAILURES = 3          # consecutive QDLDL failures after which a path keeps to SuperLU
BACKWARD_ERROR = 1e-9     # largest |K x - b| / (max|K_ij| |x| + |b|) (max norms) from QDLDL


class SingularTangent(RuntimeError):
    """Neither factorisation could solve with the tangent."""


@dataclass
class Timer:
    """Where a path's time goes (seconds) and how often (counts)."""

    assembly: float = 0.0       # tangent and residual assembly
    factor: float = 0.0         # factorisations (symbolic and numeric)
    solve: float = 0.0          # triangular solves and their checks
    event: float = 0.0          # bordered Newton solves that locate contact events
    newton_iterations: int = 0
    chord_iterations: int = 0   # Newton iterations with the previous factorisation
    factorisations: int = 0
    symbolic: int = 0           # orderings / symbolic analyses
    fallbacks: int = 0          # QDLDL factorisations redone by SuperLU
    backend: str = ""           # linear solver used: "qdldl" or "superlu"

    @property
    def solves(self) -> int:    # the name of the factorisation count before timing blocks
        return self.factorisations

    def as_dict(self) -> dict:
        return {f.name: getattr(self, f.name) for f in fields(self)}


def backend(fast: bool) -> str:
    """The linear solver a path will use: QDLDL if asked for and importable."""
    return "qdldl" if fast and qdldl is not None else "superlu"


class Factor:
    """A factorisation of K_ff: `solve(b)` for b over the free dofs."""

    def __init__(self, solve, timer):
        self._solve, self.timer = solve, timer

    def solve(self, b):
        t0 = time.perf_counter()
        out = self._solve(b)
        self.timer.solve += time.perf_counter() - t0
        return out


class LinearSolver:
    """Factorisations of the free block of tangents sharing one sparsity pattern (CSR,
    symmetric pattern and values, as `forms.tangent` assembles them)."""

    def __init__(self, indptr, indices, fast: bool, timer: Timer):
        self.timer = timer
        self.backend = backend(fast)
        timer.backend = self.backend
        n = len(indptr) - 1
        self.rows = np.repeat(np.arange(n), np.diff(indptr))
        self.cols = np.asarray(indices)
        self._shared = _shared(indptr)
        self._failures = 0
        self._plan_key = self._rows_key = None
        if self.backend == "qdldl":
            # the upper triangle in CSC is the lower triangle of the symmetric CSR
            lower = np.flatnonzero(self.cols <= self.rows)
            self._low = lower
            self._low_indices = self.cols[lower].astype(np.int32)
            self._low_indptr = np.concatenate(
                [[0], np.cumsum(np.bincount(self.rows[lower], minlength=n))]).astype(np.int32)
            self._low_diag = np.flatnonzero(self.cols[lower] == self.rows[lower])
            self._n = n

    def factor(self, K, c) -> Factor:
        """Factorise the free block of K (constraints c); raises SingularTangent."""
        t0 = time.perf_counter()
        try:
            if self.backend == "qdldl":
                f = self._factor_qdldl(K, c) or self._fallback(K, c)
            else:
                f = self._factor_superlu(K, c)
        finally:
            self.timer.factor += time.perf_counter() - t0
        self.timer.factorisations += 1
        return f

    def _fallback(self, K, c):
        """SuperLU in place of a failed QDLDL factorisation (counted)."""
        self.timer.fallbacks += 1
        self._failures += 1
        if self._failures >= MAX_FAILURES:   # this path's tangents need pivoting
            self.backend = "superlu"
            self.timer.backend = "qdldl+superlu"
        return self._factor_superlu(K, c)

    # SuperLU of the free block
    def _plan(self, K, c):
        if self._plan_key is not c:
            free_pos = c.free_pos
            sel = (free_pos[self.rows] >= 0) & (free_pos[self.cols] >= 0)
            sub_rows = free_pos[self.rows[sel]]
            indptr = np.concatenate([[0], np.cumsum(np.bincount(sub_rows,
                                                                minlength=len(c.free)))])
            self._plan_cache = (np.flatnonzero(sel), free_pos[self.cols[sel]].astype(np.int32),
                                indptr.astype(np.int32))
            self._plan_key = c
        return self._plan_cache

    def _factor_superlu(self, K, c):
        sel, indices, indptr = self._plan(K, c)
        n = len(c.free)
        # K is symmetric, so its CSR arrays restricted to the free block are also CSC
        Kff = sp.csc_matrix((K.data[sel], indices, indptr), shape=(n, n))
        try:
            lu = spla.splu(Kff, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.0)
        except RuntimeError:
            try:
                lu = spla.splu(Kff, permc_spec="COLAMD")
            except RuntimeError as err:
                raise SingularTangent(str(err)) from None
        return Factor(lu.solve, self.timer)

    # QDLDL of the whole pattern, prescribed dofs as identity rows
    def _identity_rows(self, c):
        """Positions (in the lower-triangle data) to zero and to set to 1 for c."""
        if self._rows_key is not c:
            fixed = c.free_pos < 0
            rows, cols = self.rows[self._low], self.cols[self._low]
            self._rows_cache = (np.flatnonzero(fixed[rows] | fixed[cols]),
                                self._low_diag[fixed[rows[self._low_diag]]])
            self._rows_key = c
        return self._rows_cache

    def _factor_qdldl(self, K, c):
        zero, one = self._identity_rows(c)
        data = K.data[self._low]
        data[zero] = 0.0
        data[one] = 1.0
        A = sp.csc_matrix((data, self._low_indices, self._low_indptr), shape=(self._n,) * 2)
        shared = self._shared
        try:
            if shared.solver is None:
                shared.solver = qdldl.Solver(A, upper=True)
                self.timer.symbolic += 1
            else:
                shared.solver.update(A, upper=True)
        except (RuntimeError, ValueError):   # a zero pivot: QDLDL does not pivot
            shared.solver = None
            return None
        shared.generation += 1
        solver, free, n, generation = shared.solver, c.free, self._n, shared.generation
        K_max = float(np.abs(K.data).max())
        checked = []

        def solve(b):
            if shared.generation != generation or solver is not shared.solver:
                raise _Inaccurate   # QDLDL has refactorised since: this factor is gone
            x = np.zeros(n)
            x[free] = b
            x = solver.solve(x)
            xf = x[free]
            if not np.all(np.isfinite(xf)):
                raise _Inaccurate
            if not checked:    # the backward error of the first solve vouches for the factor
                x[c.free_pos < 0] = 0.0
                res = (K @ x)[free] - b
                if np.abs(res).max() > BACKWARD_ERROR * (K_max * np.abs(xf).max()
                                                         + np.abs(b).max()):
                    raise _Inaccurate
                checked.append(True)
                self._failures = 0
            return xf

        return Factor(_checked(solve, lambda: self._fallback(K, c)), self.timer)


class Bordered:
    """Solves with the free block of constraints c from a factorisation `lu` of the free
    block of c_before, whose free dofs include c's: the m dofs that c holds besides are held
    by Lagrange multipliers, an m x m Schur complement (m solves once, then one per solve).
    Raises ValueError if c frees a dof that c_before holds, SingularTangent if the Schur
    complement is singular."""

    BORDER_COND = 1e12   # largest condition number of the Schur complement

    def __init__(self, lu, c_before, c):
        self.lu = lu
        self.keep = c_before.free_pos[c.free]             # c's free dofs among c_before's
        if np.any(self.keep < 0):
            raise ValueError("the constraints free a held dof")
        held = np.ones(len(c_before.free), dtype=bool)
        held[self.keep] = False
        extra = np.flatnonzero(held)                      # (a mask: setdiff1d sorts, 1 ms)
        E = np.zeros((len(c_before.free), len(extra)))
        E[extra, np.arange(len(extra))] = 1.0
        self.AE = np.column_stack([lu.solve(e) for e in E.T]) if len(extra) else E
        self.S = self.AE[extra]
        if len(extra) and not np.linalg.cond(self.S) < self.BORDER_COND:
            raise SingularTangent("the bordered tangent is singular")
        self.extra = extra

    def solve(self, b):
        z = np.zeros(len(self.AE))
        z[self.keep] = b
        z = self.lu.solve(z)
        if len(self.extra):
            z -= self.AE @ np.linalg.solve(self.S, z[self.extra])
        return z[self.keep]


class _Symbolic:
    """The QDLDL solver of one sparsity pattern (its ordering and symbolic analysis) and
    the count of its numeric factorisations, which tells a factor that it is gone."""

    def __init__(self):
        self.solver, self.generation = None, 0


_THREAD = threading.local()


def _shared(indptr) -> _Symbolic:
    """The _Symbolic of the pattern whose CSR indptr is this array, for this thread (paths
    run one after the other in a thread; a dead pattern's entry is dropped)."""
    store = _THREAD.__dict__.setdefault("store", {})
    for key in [k for k, (ref, _) in store.items() if ref() is None]:
        del store[key]
    entry = store.get(id(indptr))
    if entry is None or entry[0]() is not indptr:
        entry = store[id(indptr)] = (weakref.ref(indptr), _Symbolic())
    return entry[1]


class _Inaccurate(ArithmeticError):
    pass


def _checked(solve, fallback):
    """solve, or (once a right-hand side exposes an inaccurate factorisation) the solve of
    the factorisation `fallback()` returns, from then on."""
    state = {"solve": solve}

    def run(b):
        try:
            return state["solve"](b)
        except _Inaccurate:
            state["solve"] = fallback()._solve
            return state["solve"](b)
    return run
