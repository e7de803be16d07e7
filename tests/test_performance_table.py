"""The performance table's plumbing (benchmarks/performance_table.py,
benchmarks/calculix_loading.py): the table in docs/performance.md is the one the stored
measurements render, the block is replaced in place, and the CalculiX deck is our coarse
mesh with its boundary sets.  Nothing here times anything."""
import json
import sys

import numpy as np
import pytest

from conftest import REPO

sys.path.insert(0, str(REPO / "benchmarks"))
import calculix_loading as ccx  # noqa: E402
import performance_table as pt  # noqa: E402


def test_docs_table_is_the_stored_measurements():
    store = json.loads(pt.STORE.read_text())
    text = pt.DOC.read_text()
    assert pt.replace_block(text, pt.render(store)) == text
    assert set(store) <= set(pt.ORDER)


def test_block_replaced_in_place_and_markers_required():
    text = f"before\n{pt.BEGIN}\nold table\n{pt.END}\nafter\n"
    assert pt.replace_block(text, "new") == f"before\n{pt.BEGIN}\nnew\n{pt.END}\nafter\n"
    with pytest.raises(ValueError, match="markers"):
        pt.replace_block("no markers here\n", "new")


def test_calculix_reaction_parsed_with_the_wedge_and_sign():
    dat = ("\n total force (fx,fy,fz) for set RIM and time  0.5000000E+00\n\n"
           "       -1.0E-02 -2.0E-02  0.0E+00\n"
           "\n total force (fx,fy,fz) for set RIM and time  0.1000000E+01\n\n"
           "       -3.0E-02 -5.0E-02  1.0E-17\n")
    delta, P = ccx.parse_dat(dat)
    np.testing.assert_allclose(delta, [2.5, 5.0])
    np.testing.assert_allclose(P, [3.6, 9.0])          # 180 x minus RF_z: compression > 0


def test_calculix_deck_is_our_coarse_mesh():
    xy, conn, face, used, rim, axis = ccx.shell_mesh("coarse")
    c = xy[conn[:, :4]]
    area = 0.5 * np.sum(c[:, :, 0] * np.roll(c[:, :, 1], -1, 1)
                        - np.roll(c[:, :, 0], -1, 1) * c[:, :, 1], axis=1)
    assert (area > 0).all()                            # corners anticlockwise in (r, z)
    # the contact faces hold every outer-surface node once the midsides are counted
    on_face = {int(n) for e in np.flatnonzero(face >= 0)
               for n in (conn[e, face[e]], conn[e, (face[e] + 1) % 4], conn[e, 4 + face[e]])}
    rho = np.hypot(xy[:, 0], xy[:, 1] - ccx.R_MM)
    outer = set(np.flatnonzero(np.abs(rho - ccx.R_MM) < 1e-9).tolist()) & set(used.tolist())
    assert on_face == outer
    np.testing.assert_allclose(xy[rim, 1], ccx.H_MM, atol=1e-12)
    np.testing.assert_allclose(xy[axis, 0], 0.0, atol=1e-12)
    text, nodes = ccx.deck("coarse")
    assert nodes == len(used) + 3 * (2 * ccx.SLAB_ELEMENTS + 1) - ccx.SLAB_ELEMENTS
    assert "*FRICTION" not in text and "TYPE=CAX8R, ELSET=SHELL" in text


def test_a_calculix_run_that_diverges_is_repeated_a_bounded_number_of_times(monkeypatch,
                                                                            capsys):
    """ccx on two threads is not deterministic and sometimes diverges before 5 mm: such a
    run is repeated, at most CALCULIX_TRIES runs in all, then the row fails."""
    ok = ("CalculiX CAX8R, coarse mesh, frictionless: 1282 dofs, 81 increments, 13.32 s "
          "(16.62 s CPU), D1 0.000667 /MPa, P(5 mm) = 13.3927 N")
    failed = "RuntimeError: ccx did not reach delta = 5 mm:  average force= nan"
    runs = []

    def timed(cmd, **kwargs):           # the first run diverges, the second reaches 5 mm
        runs.append(cmd)
        code, out = (0, ok) if len(runs) == 2 else (1, failed)
        return 1.0, 1.0, code, out

    def diverging(cmd, **kwargs):
        runs.append(cmd)
        return 1.0, 1.0, 1, failed
    monkeypatch.setattr(pt.shutil, "which", lambda name: "/usr/bin/" + name)
    monkeypatch.setattr(pt, "timed", timed)
    assert pt.calculix() == (13.32, 13.3927, 16.62) and len(runs) == 2
    assert "CalculiX run 1 of 3 failed: RuntimeError: ccx did not reach" in capsys.readouterr().out
    runs.clear()
    monkeypatch.setattr(pt, "timed", diverging)
    with pytest.raises(RuntimeError, match="failed 3 times"):
        pt.calculix()
    assert len(runs) == pt.CALCULIX_TRIES == 3
