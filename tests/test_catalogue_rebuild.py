"""A corrupt catalogue index is refused (exit 2); `catalogue rebuild` makes a new index from
the stored files, keeps the old one beside, and leaves out files it cannot trust."""
import shutil

import numpy as np
import pytest

from shell_adhesion.catalogue import Catalogue
from shell_adhesion.catalogue.store import check_index, CorruptIndex
from shell_adhesion.solver import solve_paths
from shell_adhesion.solver.pathset_dataset import from_dataset, to_dataset
from shell_adhesion.cli import main
from shell_adhesion.study.keys import pathset_key


def test_rebuild_from_stored_files(tmp_path, capsys):
    ps, _, _ = solve_paths(0.15, 1.0, "no_slip", "coarse", 0.02, relax_paths=False)
    key = pathset_key(0.15, 1.0, "no_slip", "coarse", 0.02, 0.006)
    folder = tmp_path / "cat"
    with Catalogue(folder) as cat:
        entry = cat.store(key, to_dataset(ps))
    check_index(folder)
    (folder / "pathsets" / "junk.nc").write_bytes(b"\x89HDF\r\n" + b"0" * 100)
    shutil.copy(entry.file, folder / "pathsets" / ("0" * 64 + ".nc"))     # a misnamed copy
    (folder / "index.sqlite").write_bytes(b"SQLite format 3\x00" + b"\xff" * 4000)
    for leftover in folder.glob("index.sqlite-*"):
        leftover.unlink()
    with pytest.raises(CorruptIndex, match="not a catalogue index"):
        check_index(folder)

    assert main(["catalogue", "list", "--catalogue", str(folder)]) == 2
    err = capsys.readouterr().err
    assert "not a catalogue index" in err and "catalogue rebuild --catalogue" in err

    assert main(["catalogue", "rebuild", "--catalogue", str(folder)]) == 0
    out, err = capsys.readouterr()
    assert "1 path sets, 2 files left out" in out
    assert err.count("left out") == 2
    assert len(list(folder.glob("index.sqlite.old-*"))) == 1

    with Catalogue(folder) as cat:
        rows = cat.entries()
        hit = cat.fetch(key)
    assert [r["fingerprint"] for r in rows] == [entry.fingerprint] and rows[0]["status"] == "ok"
    assert hit is not None and hit[0].sha256 == entry.sha256
    np.testing.assert_array_equal(from_dataset(hit[1]).loading_P, ps.loading_P)
    assert main(["catalogue", "list", "--catalogue", str(folder)]) == 0
    assert entry.fingerprint[:12] in capsys.readouterr().out
