"""A run's driver does not keep what it sent to the workers.

dask logs the last messages of each comm (1000 by default), and with them every task's
arguments: each relaxation task carries its start state (the displacement fields), so the
driver of a long study grew with every path.  After the paths of a study are computed the
driver holds only the few states of the bounded logs."""
import gc

import numpy as np

from shell_adhesion.solver.path import State
from shell_adhesion.study import run as run_module

STUDY = dict(name="memory", R_mm=20, mesh="coarse", error_bars=False,
             base=dict(C10_MPa=1.0, t_over_R=0.1, h_over_R=1.0, gamma_J_m2=300))


def _states_with_fields():
    gc.collect()
    return sum(1 for o in gc.get_objects()
               if isinstance(o, State) and o.x is not None and np.size(o.x) > 0)


def test_the_driver_drops_the_start_states_it_sent(tmp_path, monkeypatch):
    held = {}
    compute = run_module.compute

    def counting(*args, **kwargs):
        before = _states_with_fields()      # other tests' states may be alive in this process
        result = compute(*args, **kwargs)
        held["states"] = _states_with_fields() - before
        return result

    monkeypatch.setattr(run_module, "compute", counting)
    outcome = run_module.execute(STUDY, out=tmp_path / "out", catalogue=tmp_path / "cat",
                                 progress=False, workers=2)
    assert outcome.exit_code == 0
    paths = outcome.relaxations_computed
    assert paths >= 60                  # enough paths to tell (83 measured)
    # the logs of the client's comm and the two workers' hold a few messages each (8);
    # with dask's default of 1000 the driver held one start state per path
    assert held["states"] <= 30, (held["states"], paths)


def test_the_driver_opens_a_bounded_number_of_shells_at_once(tmp_path, monkeypatch):
    """Each open shell's relaxation tasks carry their start states until they run; with
    every shell of a study open at once, the default-mesh map's driver grew to 23 GB.  On
    one worker at most OPEN_SHELLS_PER_WORKER shells are open: a shell's first loading is
    submitted only when fewer are in progress (counted from the driver's submissions and
    its stores of finished path sets)."""
    import distributed
    from shell_adhesion.catalogue import Catalogue
    events = []
    submit, store = distributed.Client.submit, Catalogue.store

    def submitting(self, fn, *args, key=None, **kwargs):
        if key and key.startswith("loading-"):
            events.append(("open", key.split("-")[1]))
        return submit(self, fn, *args, key=key, **kwargs)

    def storing(self, key, *args, **kwargs):
        events.append(("close", None))
        return store(self, key, *args, **kwargs)
    monkeypatch.setattr(distributed.Client, "submit", submitting)
    monkeypatch.setattr(Catalogue, "store", storing)
    # three thick shells: one more than the window holds (a small gamma: few paths each)
    study = dict(STUDY, name="window", base=dict(STUDY["base"], t_over_R=0.3, gamma_J_m2=60),
                 sweeps=dict(t_over_R=[0.3, 0.4, 0.5]))
    outcome = run_module.execute(study, out=tmp_path / "out", catalogue=tmp_path / "cat",
                                 progress=False, workers=1)
    assert outcome.exit_code == 0 and len(outcome.computed) == 3
    opened, in_progress, most = set(), 0, 0
    for kind, shell in events:
        if kind == "open" and shell not in opened:      # a refit loads its shell again
            opened.add(shell)
            in_progress += 1
        elif kind == "close":
            in_progress -= 1
        most = max(most, in_progress)
    assert len(opened) == 3 > run_module.OPEN_SHELLS_PER_WORKER
    assert most == run_module.OPEN_SHELLS_PER_WORKER, events
