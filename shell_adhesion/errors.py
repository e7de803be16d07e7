"""The package's exceptions: bad input (the command exits with 2) and the solver's failure
to find an equilibrium.  A leaf that imports nothing, so that the solver, the study and
the analysis of a results cube raise and catch the same classes."""


class InputError(ValueError):
    """Bad input: the message names the field, the value and the rule."""


class ConvergenceError(RuntimeError):
    """No equilibrium could be found: the message says where and why."""


class MaterialLimitError(ConvergenceError):
    """The solid locks up: a Gent solid's I1bar - 3 has come within solver.path.LOCK_UP of Jm, so the
    loading cannot go on (`delta` / R, `ratio` = (I1bar - 3) / Jm, `I1bar`, `stretch` the
    largest principal stretch, at the worst point of the last converged state)."""

    def __init__(self, delta, Jm, ratio, I1bar, stretch):
        self.delta, self.Jm, self.ratio, self.I1bar, self.stretch = delta, Jm, ratio, I1bar, stretch
        super().__init__(self.text())

    def text(self, scale=1.0, unit="R", delta_flag="delta_max", Jm_flag="Jm") -> str:
        """The one-line reason; delta times `scale` in `unit` (default delta / R), the
        inputs named `delta_flag` and `Jm_flag`."""
        return (f"gent limit: the solid locks up at delta = {self.delta * scale:.4g} {unit}: "
                f"I1bar - 3 = {self.I1bar - 3:.4g} reaches {100 * self.ratio:.2f} % of "
                f"{Jm_flag} = {self.Jm:g} (I1bar = {self.I1bar:.6g}, largest principal "
                f"stretch {self.stretch:.4g}); lower {delta_flag} below "
                f"{self.delta * scale:.3g} {unit} or raise {Jm_flag}")


class QualityError(ConvergenceError):
    """A converged state's elements are inverted or too distorted, or its pointwise J is
    too far from 1, for the result to be trusted (see solver.quality)."""
